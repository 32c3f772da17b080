//! A glTF material's base colour or emissive texture as a twinray texture: its image decoded once per
//! model (a file beside it, a `data:` URI or a buffer view, within the model's byte budget),
//! its sampler's wrap modes and filters, its texture coordinate set and KHR_texture_transform.

use super::super::texture::{self, Filter, SamplerDesc, TextureDesc, TextureImage, Wrap};
use super::buffers::read_uri;
use gltf::texture::{MagFilter, MinFilter, WrappingMode};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::Arc;

/// Where a model's images are read from: its buffers, its folder, and how many more bytes
/// may be read.
pub struct Files<'a> {
    pub buffers: &'a [Vec<u8>],
    pub folder: &'a Path,
    pub budget: &'a mut u64,
}

/// The model's images decoded so far, by index.
pub type Images = BTreeMap<usize, Arc<TextureImage>>;

/// The texture `info` refers to (a material's base colour or emissive texture: sRGB colours
/// both); `source` names the model in errors.
pub fn read(
    info: gltf::texture::Info,
    files: &mut Files,
    images: &mut Images,
    source: &str,
    ignored: &mut BTreeSet<String>,
) -> Result<TextureDesc, String> {
    let t = info.texture();
    let image = t.source();
    let decoded = match images.get(&image.index()) {
        Some(i) => i.clone(),
        None => {
            // The file too, where the image is one: a user looks for it by that name.
            let name = match image.source() {
                gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                    format!("{source}#image {} ({uri})", image.index())
                }
                _ => format!("{source}#image {}", image.index()),
            };
            let bytes = image_bytes(&image, files).map_err(|e| format!("image {}: {e}", image.index()))?;
            let decoded = Arc::new(texture::decode(&name, &bytes, true, files.budget).map_err(|e| e.to_string())?);
            images.insert(image.index(), decoded.clone());
            decoded
        }
    };
    let mut uv = info.tex_coord();
    let mut transform = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    if let Some(tt) = info.texture_transform() {
        uv = tt.tex_coord().unwrap_or(uv);
        // KHR_texture_transform: translation * rotation * scale. The rotation turns the image
        // counter-clockwise as seen (v runs down the image), so the coordinates turn the other
        // way: the sample model TextureTransformTest shows its red marker ("rotated the wrong
        // way") for the matrix its README's GLSL reads as, column-major.
        let ([ox, oy], r, [sx, sy]) = (tt.offset(), tt.rotation(), tt.scale());
        let (s, c) = r.sin_cos();
        transform = [[c * sx, s * sy, ox], [-s * sx, c * sy, oy]];
    }
    if uv > 1 {
        ignored.insert(format!("TEXCOORD_{uv} (set 0 read instead)"));
        uv = 0;
    }
    let sampler = t.sampler();
    let wrap = |w: WrappingMode| match w {
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
        WrappingMode::Repeat => Wrap::Repeat,
    };
    let nearest = |yes: bool| if yes { Filter::Nearest } else { Filter::Linear };
    let (min, mipmap) = match sampler.min_filter() {
        None | Some(MinFilter::LinearMipmapLinear) => (Filter::Linear, Some(Filter::Linear)),
        Some(MinFilter::Nearest) => (Filter::Nearest, None),
        Some(MinFilter::Linear) => (Filter::Linear, None),
        Some(MinFilter::NearestMipmapNearest) => (Filter::Nearest, Some(Filter::Nearest)),
        Some(MinFilter::LinearMipmapNearest) => (Filter::Linear, Some(Filter::Nearest)),
        Some(MinFilter::NearestMipmapLinear) => (Filter::Nearest, Some(Filter::Linear)),
    };
    let sampler = SamplerDesc {
        wrap: [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())],
        mag: nearest(sampler.mag_filter() == Some(MagFilter::Nearest)),
        min,
        mipmap,
    };
    Ok(TextureDesc { file: decoded.name.clone(), uv, sampler, transform, image: Some(decoded) })
}

/// The encoded bytes of `image`, read within what is left of the model's budget.
fn image_bytes(image: &gltf::Image, files: &mut Files) -> Result<Vec<u8>, String> {
    let bytes = match image.source() {
        gltf::image::Source::Uri { uri, .. } => read_uri(uri, files.folder, *files.budget)?,
        gltf::image::Source::View { view, .. } => {
            let buffer = files.buffers.get(view.buffer().index()).ok_or("its buffer is missing")?;
            let end = view.offset().checked_add(view.length()).filter(|&e| e <= buffer.len());
            let end = end.ok_or_else(|| format!("its buffer view {} reaches past its buffer", view.index()))?;
            buffer[view.offset()..end].to_vec()
        }
    };
    *files.budget = files.budget.saturating_sub(bytes.len() as u64);
    Ok(bytes)
}
