//! Textured meshes handed to Mitsuba: each mesh's texture coordinates as the material's
//! texture reads them (its set, through its transform) written into its PLY file, and the
//! texture's decoded image as a PNG that Mitsuba's `bitmap` reads as sRGB, as twinray's
//! sampler does. Mitsuba filters by supersampling, without mip levels: at the reference's
//! samples per pixel the two converge to the same box-filtered image.

use glam::{Vec2, Vec4};
use serde_json::{json, Value};
use std::sync::Arc;
use twinray_host::error::{Error, Result};
use twinray_host::scene::file::MaterialDesc;
use twinray_host::scene::texture::{Filter, TextureDesc, TextureImage, Wrap};
use twinray_host::scene::{MeshData, Scene};

/// The images the Mitsuba scene reads, each once: `textures/N.png`.
#[derive(Default)]
pub struct Images {
    pub images: Vec<Arc<TextureImage>>,
}

impl Images {
    /// The `bitmap` texture of `t`, its image taking a file the first time.
    pub fn bitmap(&mut self, t: &TextureDesc, scene: &Scene, material: &str) -> Result<Value> {
        let refuse = |why: &str| Error::Input(format!("{}: material {material:?}: {why}", scene.source));
        let image = t.image.as_ref().ok_or_else(|| refuse("its texture is not loaded"))?;
        let k = match self.images.iter().position(|i| Arc::ptr_eq(i, image)) {
            Some(k) => k,
            None => {
                self.images.push(image.clone());
                self.images.len() - 1
            }
        };
        let wrap = match t.sampler.wrap {
            [Wrap::Repeat, Wrap::Repeat] => "repeat",
            [Wrap::Mirror, Wrap::Mirror] => "mirror",
            [Wrap::Clamp, Wrap::Clamp] => "clamp",
            _ => return Err(refuse("its texture wraps u and v differently, which Mitsuba's bitmap cannot")),
        };
        let filter = match t.sampler.mag {
            Filter::Linear => "bilinear",
            Filter::Nearest => "nearest",
        };
        Ok(json!({"type": "bitmap", "filename": format!("textures/{k}.png"), "filter_type": filter, "wrap_mode": wrap}))
    }
}

/// The texture of `material` that Mitsuba is handed on meshes, if it has one: a diffuse
/// material's, whose colour must be white (Mitsuba's diffuse reflectance is one texture, not a
/// colour times one).
pub fn texture<'a>(scene: &'a Scene, material: &str) -> Result<Option<&'a TextureDesc>> {
    match scene.file.materials.get(material) {
        Some(MaterialDesc::Diffuse { color, texture: Some(t), emission: None }) => {
            if *color != [1.0; 3] {
                return Err(Error::Input(format!(
                    "{}: material {material:?} multiplies its texture by a colour other than white, which the cross-check does not hand to Mitsuba",
                    scene.source
                )));
            }
            Ok(Some(t))
        }
        _ => Ok(None),
    }
}

/// Each vertex's coordinates in `t`, as the stages read them. Mitsuba's `bitmap`, read through
/// a PLY file's `u` and `v`, has v run down the image as twinray's (glTF's, Vulkan's) does:
/// a quad whose v = 1 edge is up showed the image's bottom rows there (Mitsuba 3.9.1).
/// Refused: vertex colours, which Mitsuba is not handed.
pub fn uvs(mesh: &MeshData, t: &TextureDesc, what: &str) -> Result<Vec<Vec2>> {
    if mesh.vertices.iter().any(|v| v.color != Vec4::ONE) {
        return Err(Error::Input(format!("{what}: vertex colours are not handed to Mitsuba")));
    }
    let [u, v] = t.transform.map(|row| (Vec2::new(row[0], row[1]), row[2]));
    Ok(mesh
        .vertices
        .iter()
        .map(|x| {
            let uv = if t.uv == 1 { Vec2::new(x.uv.z, x.uv.w) } else { Vec2::new(x.uv.x, x.uv.y) };
            Vec2::new(u.0.dot(uv) + u.1, v.0.dot(uv) + v.1)
        })
        .collect())
}
