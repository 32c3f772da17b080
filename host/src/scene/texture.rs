//! Textures: what a material's texture is (an image, the coordinate set and transform it is
//! read through, how it is sampled), its image decoded at load (PNG or JPEG, bounded) and the
//! mip chain the upload builds from it.

use crate::error::{Error, Result};
use crate::util::srgb;
use serde::Deserialize;
use std::sync::Arc;

/// Largest texture side accepted: Vulkan guarantees 4096 for 2D images; every device twinray
/// has run on (lavapipe, NVIDIA) offers 16384.
pub const MAX_SIDE: u32 = 16384;

/// How a texture coordinate outside [0, 1] is brought back.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Wrap {
    #[default]
    Repeat,
    Clamp,
    Mirror,
}

/// How texels are combined: the nearest, or bilinearly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Filter {
    #[default]
    Linear,
    Nearest,
}

/// How a texture is sampled: wrap along u and v, the filter within a level and between levels
/// (`None`: level 0 only, as glTF's minification filters without a mipmap mode ask).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SamplerDesc {
    pub wrap: [Wrap; 2],
    pub mag: Filter,
    pub min: Filter,
    pub mipmap: Option<Filter>,
}

impl SamplerDesc {
    /// Repeat, bilinear, trilinear between levels: glTF's default and twinray's.
    pub const DEFAULT: SamplerDesc =
        SamplerDesc { wrap: [Wrap::Repeat; 2], mag: Filter::Linear, min: Filter::Linear, mipmap: Some(Filter::Linear) };
}

/// A material's texture.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureDesc {
    /// The image: a PNG or JPEG file relative to the scene file; for a glTF model's texture,
    /// the model's file and the image's index, and its file if it has one (`model.glb#image 2`,
    /// `model.gltf#image 0 (wood.png)`).
    pub file: String,
    /// The vertex texture coordinate set it reads: 0 or 1.
    #[serde(default)]
    pub uv: u32,
    #[serde(default = "default_sampler")]
    pub sampler: SamplerDesc,
    /// Rows of the 2x3 matrix the coordinates go through: (u, v) to
    /// (a u + b v + c, d u + e v + f) for [[a, b, c], [d, e, f]].
    #[serde(default = "identity")]
    pub transform: [[f32; 3]; 2],
    /// The decoded image: filled at load.
    #[serde(skip)]
    pub image: Option<Arc<TextureImage>>,
}

fn default_sampler() -> SamplerDesc {
    SamplerDesc::DEFAULT
}

fn identity() -> [[f32; 3]; 2] {
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
}

/// An image as 8-bit RGBA rows, top row first; `srgb` when its values are sRGB-encoded colours
/// (a base colour texture), decoded to linear by the sampler.
pub struct TextureImage {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
    pub srgb: bool,
}

impl std::fmt::Debug for TextureImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TextureImage({}, {}x{})", self.name, self.width, self.height)
    }
}

/// Bytes an image of `width` x `height` takes decoded, as RGBA with its mip chain (which adds
/// at most a third).
pub fn decoded_bytes(width: u32, height: u32) -> u64 {
    let level0 = u64::from(width) * u64::from(height) * 4;
    level0 + level0.div_ceil(3)
}

/// Decodes `bytes` (PNG or JPEG), called `name` in errors, as RGBA, charging what it takes
/// decoded ([`decoded_bytes`]) to `budget` first, by the size its header gives: refused with
/// the cause named if it is neither, damaged, larger than [`MAX_SIDE`] on a side, or larger
/// decoded than what is left of the budget (a small file can hold a huge image).
pub fn decode(name: &str, bytes: &[u8], srgb: bool, budget: &mut u64) -> Result<TextureImage> {
    let refuse = |why: String| Error::Input(format!("texture {name}: {why}"));
    let bytes = &*picture_only(bytes);
    let reader = || {
        let reader = image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format();
        let reader = reader.map_err(|e| refuse(e.to_string()))?;
        match reader.format() {
            Some(_) => Ok(reader),
            None => Err(refuse("neither a PNG nor a JPEG image".into())),
        }
    };
    let (width, height) = reader()?.into_dimensions().map_err(|e| refuse(e.to_string()))?;
    let charged = decoded_bytes(width.min(MAX_SIDE), height.min(MAX_SIDE));
    if charged > *budget {
        let left = *budget;
        return Err(refuse(format!(
            "{width}x{height} takes {charged} bytes decoded, over the {left} bytes left of the model's budget (TWINRAY_MAX_MESH_BYTES raises it)"
        )));
    }
    let mut reader = reader()?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    limits.max_alloc = Some(u64::from(MAX_SIDE) * u64::from(MAX_SIDE) * 4);
    reader.limits(limits);
    let decoded = reader.decode().map_err(|e| refuse(e.to_string()))?.into_rgba8();
    let (width, height) = decoded.dimensions();
    if width == 0 || height == 0 {
        return Err(refuse("an image with no pixels".into()));
    }
    *budget = budget.saturating_sub(charged.max(decoded_bytes(width, height)));
    Ok(TextureImage { name: name.to_string(), width, height, rgba: decoded.into_raw(), srgb })
}

/// The PNG signature.
const PNG_SIGNATURE: &[u8; 8] = b"\x89PNG\r\n\x1a\n";

/// `bytes` with, where they are a PNG, only the chunks its picture needs: the critical ones
/// (IHDR, PLTE, IDAT, IEND, and any other, which the decoder must see to refuse) and tRNS.
/// Ancillary chunks may hold compressed metadata that inflates far past the file's size and
/// outside the image budget (an iCCP profile, zTXt or iTXt text: a 1 KB chunk can inflate to
/// 1 GiB), and twinray reads none of them. A chunk cut short ends the sequence there (the
/// decoder then refuses a picture cut short): a damaged file passes no metadata either. A
/// JPEG's metadata (EXIF, ICC profile markers) is not compressed: it takes no more than the
/// file's own size.
fn picture_only(bytes: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    use std::borrow::Cow;
    let Some(mut rest) = bytes.strip_prefix(PNG_SIGNATURE) else { return Cow::Borrowed(bytes) };
    let mut kept = PNG_SIGNATURE.to_vec();
    while !rest.is_empty() {
        // length (4, big-endian), type (4), data (length), CRC (4)
        let length = rest.get(..4).map(|b| u32::from_be_bytes([b[0], b[1], b[2], b[3]]) as usize);
        let Some(chunk) = length.and_then(|l| l.checked_add(12)).and_then(|n| rest.get(..n)) else { break };
        let kind = &chunk[4..8];
        // Bit 5 of the first letter (lower case) marks an ancillary chunk.
        if kind[0] & 0x20 == 0 || kind == b"tRNS" {
            kept.extend_from_slice(chunk);
        }
        rest = &rest[chunk.len()..];
    }
    Cow::Owned(kept)
}

/// The levels of `image`'s mip chain after level 0, each half the last (rounded down, at least
/// 1), every texel the mean of the 2x2 (or fewer, at an odd edge) below it; averaged in linear
/// light for sRGB images, as the sampler's filtering is.
pub fn mip_chain(image: &TextureImage) -> Vec<(u32, u32, Vec<u8>)> {
    let srgb = image.srgb;
    let decode = |v: u8| if srgb { srgb::decode(v) } else { f32::from(v) / 255.0 };
    let encode = |c: f32| if srgb { srgb::encode(c) } else { srgb::unorm(c) };
    let mut levels: Vec<(u32, u32, Vec<u8>)> = Vec::new();
    let (mut w, mut h) = (image.width, image.height);
    while w > 1 || h > 1 {
        let last = levels.last().map_or(image.rgba.as_slice(), |(_, _, t)| t.as_slice());
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let mut next = vec![0u8; (nw * nh * 4) as usize];
        for y in 0..nh {
            for x in 0..nw {
                for c in 0..4 {
                    let (mut sum, mut n) = (0.0, 0.0);
                    for sy in (2 * y)..(2 * y + 2).min(h) {
                        for sx in (2 * x)..(2 * x + 2).min(w) {
                            let v = last[((sy * w + sx) * 4 + c) as usize];
                            // Alpha is never sRGB-encoded.
                            sum += if c == 3 { f32::from(v) / 255.0 } else { decode(v) };
                            n += 1.0;
                        }
                    }
                    let mean = sum / n;
                    next[((y * nw + x) * 4 + c) as usize] = if c == 3 { srgb::unorm(mean) } else { encode(mean) };
                }
            }
        }
        levels.push((nw, nh, next));
        (w, h) = (nw, nh);
    }
    levels
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, rgba: Vec<u8>, srgb: bool) -> TextureImage {
        TextureImage { name: "t".into(), width, height, rgba, srgb }
    }

    fn chunk(kind: &[u8; 4], body: &[u8]) -> Vec<u8> {
        let mut out = (body.len() as u32).to_be_bytes().to_vec();
        out.extend(kind);
        out.extend(body);
        let crc = crc32(&out[4..]);
        out.extend(crc.to_be_bytes());
        out
    }

    /// zlib's CRC-32 (the PNG chunk checksum), bit by bit: a test needs no table.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    }

    /// A PNG's ancillary chunks (here a text chunk and a damaged profile that no decoder
    /// could inflate) are dropped before it is decoded, and its picture kept, also where the
    /// file is cut short.
    #[test]
    fn a_png_reaches_the_decoder_with_its_picture_chunks_only() {
        let mut png = Vec::new();
        image::RgbaImage::from_pixel(3, 2, image::Rgba([10, 20, 30, 255]))
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        let (head, tail) = png.split_at(PNG_SIGNATURE.len() + 25); // the signature and IHDR
        let mut noisy = head.to_vec();
        noisy.extend(chunk(b"iCCP", b"profile\0\0not a zlib stream"));
        noisy.extend(chunk(b"tEXt", b"Comment\0hello"));
        noisy.extend(tail);
        assert_eq!(&*picture_only(&noisy), &png[..], "only the picture's chunks are left");
        let mut budget = u64::MAX;
        let decoded = decode("noisy.png", &noisy, true, &mut budget).unwrap();
        assert_eq!((decoded.width, decoded.height, &decoded.rgba[..4]), (3, 2, &[10u8, 20, 30, 255][..]));
        // Cut inside its last chunk, the file keeps its whole chunks, metadata still dropped.
        let cut = &noisy[..noisy.len() - 3];
        assert_eq!(&*picture_only(cut), &png[..png.len() - 12], "all but IEND");
    }

    /// A small file of a large image is charged its decoded size from its header, before it
    /// is decoded: refused over the budget, and the budget spent when it fits.
    #[test]
    fn an_image_is_charged_its_decoded_size_before_it_is_decoded() {
        let mut png = Vec::new();
        let pixels = image::GrayImage::new(512, 256);
        pixels.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
        assert!(png.len() < 4096, "{} bytes encoded", png.len());
        let size = decoded_bytes(512, 256);
        assert_eq!(size, 512 * 256 * 4 * 4 / 3 + 1);
        let mut budget = size - 1;
        let e = decode("big.png", &png, true, &mut budget).unwrap_err().to_string();
        assert!(e.contains("512x256") && e.contains(&format!("{size} bytes decoded")), "{e}");
        assert_eq!(budget, size - 1, "nothing spent on a refusal");
        let mut budget = size + 10;
        let decoded = decode("big.png", &png, true, &mut budget).unwrap();
        assert_eq!((decoded.width, decoded.height, budget), (512, 256, 10));
    }

    /// A 3x2 image: levels 1x1 (rounded down); black and white average to 50% in linear light,
    /// which sRGB encodes as 188, and to 128 in a linear image; alpha is averaged as is.
    #[test]
    fn mips_halve_to_one_texel_averaging_in_linear_light() {
        let px = |v: u8| [v, v, v, v];
        let rgba: Vec<u8> = [px(0), px(255), px(0), px(255), px(0), px(255)].concat();
        let srgb = mip_chain(&image(3, 2, rgba.clone(), true));
        assert_eq!(srgb.len(), 1);
        assert_eq!((srgb[0].0, srgb[0].1), (1, 1));
        assert_eq!(srgb[0].2, vec![188, 188, 188, 128]);
        let linear = mip_chain(&image(3, 2, rgba, false));
        assert_eq!(linear[0].2, vec![128; 4]);
        assert_eq!(mip_chain(&image(8, 1, vec![7; 32], false)).len(), 3, "8x1 -> 4x1, 2x1, 1x1");
    }

    #[test]
    fn what_is_not_an_image_is_refused_by_name() {
        let mut budget = u64::MAX;
        let plenty = &mut budget;
        let e = decode("wood.png", b"not an image at all", true, plenty).unwrap_err().to_string();
        assert!(e.contains("wood.png") && e.contains("neither a PNG nor a JPEG"), "{e}");
        let mut png = Vec::new();
        image::RgbaImage::new(2, 1).write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
        let t = decode("ok.png", &png, false, plenty).unwrap();
        assert_eq!((t.width, t.height, t.rgba.len()), (2, 1, 8));
        let e = decode("cut.png", &png[..png.len() / 2], false, plenty).unwrap_err().to_string();
        assert!(e.contains("cut.png"), "{e}");
    }
}
