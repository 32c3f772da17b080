//! A glTF file's bytes and its buffers, each read once and bounded: the file itself (JSON or
//! GLB), the GLB's binary chunk, `data:` URIs (base64) and files beside the model. Nothing is
//! read past `max_mesh_bytes` in all, and a buffer shorter than its declared `byteLength` is
//! refused here, so no accessor can later read past the data it names.

use super::super::mesh::max_mesh_bytes;
use crate::util::input::{confined, read_bounded};
use base64::Engine as _;
use std::path::Path;

/// Extensions twinray reads, so a model may require them.
pub const SUPPORTED_EXTENSIONS: [&str; 6] = [
    "KHR_lights_punctual",
    super::quantized::EXTENSION,
    "KHR_texture_transform",
    "KHR_materials_emissive_strength",
    "KHR_materials_unlit",
    super::instancing::EXTENSION,
];

/// The parsed document and its buffers' bytes, in buffer order.
pub struct Loaded {
    pub gltf: gltf::Gltf,
    pub buffers: Vec<Vec<u8>>,
    /// Per animation, the last key of its channels left out (`node_channels`), 0 for none.
    pub left_out_ends: Vec<f32>,
    /// Where image files are read from, and how many more bytes may be read.
    pub folder: std::path::PathBuf,
    pub budget: u64,
}

/// Reads and parses `path` (`.gltf` or `.glb`) and every buffer it names. A GLB file is read
/// chunk by chunk, its binary chunk straight into the buffer it is: the file is never held
/// whole beside it (the `gltf` crate's own reader of a GLB slice copies its binary chunk).
pub fn load(path: &Path) -> Result<Loaded, String> {
    let limit = max_mesh_bytes()?;
    let raise = |e: String| if e.contains("limit") { format!("{e} (TWINRAY_MAX_MESH_BYTES raises it)") } else { e };
    let folder = path.parent().unwrap_or(Path::new("."));
    match glb_chunks(path, limit).map_err(|e| format!("cannot read: {}", raise(e)))? {
        Some((json, bin, size)) => {
            let (json, left_out_ends) = node_channels(&json)?;
            let mut gltf = gltf::Gltf::from_slice_without_validation(&json).map_err(invalid)?;
            gltf.blob = bin;
            with_buffers((gltf, left_out_ends), size, folder, limit)
        }
        None => {
            let bytes = read_bounded(path, limit).map_err(|e| format!("cannot read: {}", raise(e)))?;
            parse(&bytes, folder, limit)
        }
    }
}

fn invalid(e: gltf::Error) -> String {
    format!("not a valid glTF 2.0 file: {e}")
}

/// A GLB file's JSON chunk, its binary chunk (if it has one) and its size in bytes.
type Chunks = (Vec<u8>, Option<Vec<u8>>, u64);

/// The chunks of the GLB file at `path`, each read on its own; `None` for a file that is not
/// GLB (no `glTF` magic). Chunks of other types are skipped, as the format asks.
fn glb_chunks(path: &Path, limit: u64) -> Result<Option<Chunks>, String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if meta.len() > limit {
        return Err(format!("{} bytes, over the limit of {limit}", meta.len()));
    }
    let mut file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut header = [0u8; 12];
    if meta.len() < 12 || file.read_exact(&mut header).is_err() || &header[..4] != b"glTF" {
        return Ok(None);
    }
    let word = |b: &[u8]| u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
    let (version, length) = (word(&header[4..8]), word(&header[8..12]));
    if version != 2 {
        return Err(format!("a GLB file of version {version} (glTF 2.0 is version 2)"));
    }
    if length > meta.len() {
        return Err(format!("its GLB header says {length} bytes, the file holds {}", meta.len()));
    }
    let (mut json, mut bin, mut at) = (None, None, 12u64);
    while at + 8 <= length {
        let mut chunk = [0u8; 8];
        file.read_exact(&mut chunk).map_err(|e| e.to_string())?;
        let (size, kind) = (word(&chunk[..4]), &chunk[4..]);
        at += 8;
        if at + size > length {
            return Err(format!("a GLB chunk of {size} bytes at byte {} reaches past its {length} bytes", at - 8));
        }
        let mut data = Vec::with_capacity(size as usize);
        (&mut file).take(size).read_to_end(&mut data).map_err(|e| e.to_string())?;
        if data.len() as u64 != size {
            return Err(format!("a GLB chunk of {size} bytes ends early"));
        }
        match kind {
            b"JSON" if json.is_none() => json = Some(data),
            b"BIN\0" if bin.is_none() => bin = Some(data),
            _ => {}
        }
        at += size;
    }
    let json = json.ok_or("a GLB file without a JSON chunk")?;
    Ok(Some((json, bin, meta.len())))
}

/// Parses a glTF file's `bytes` and reads every buffer it names, files relative to `folder`,
/// all of them together at most `limit` bytes.
pub fn parse(bytes: &[u8], folder: &Path, limit: u64) -> Result<Loaded, String> {
    let (json, left_out_ends) = node_channels(bytes)?;
    let gltf = gltf::Gltf::from_slice_without_validation(&json).map_err(invalid)?;
    with_buffers((gltf, left_out_ends), bytes.len() as u64, folder, limit)
}

/// The glTF JSON `json` without the animation channels of `KHR_animation_pointer`, which
/// target a property by a JSON pointer (a material's colour, a light's intensity) in place of
/// a node, and which the `gltf` crate cannot read: twinray animates nodes and morph weights
/// only, and names the extension in the notice as any it does not read, so a file that
/// animates its materials too plays its nodes' channels rather than being refused whole. Only
/// a file that names the extension is parsed a second time. Beside it, per animation, the
/// last key of the channels left out (their input accessor's `max`, as glTF-Sample-Viewer
/// reads an animation's length; 0 for none), which still count toward the animation's length.
fn node_channels(json: &[u8]) -> Result<(std::borrow::Cow<'_, [u8]>, Vec<f32>), String> {
    const POINTER: &[u8] = b"KHR_animation_pointer";
    if !json.windows(POINTER.len()).any(|w| w == POINTER) {
        return Ok((std::borrow::Cow::Borrowed(json), Vec::new()));
    }
    let mut root: serde_json::Value =
        serde_json::from_slice(json).map_err(|e| format!("not a valid glTF 2.0 file: {e}"))?;
    // Each accessor's `max`, read where an animation sampler's input names it.
    let accessors = root.get("accessors").and_then(|a| a.as_array()).map(Vec::as_slice).unwrap_or_default();
    let key_ends: Vec<f32> =
        accessors.iter().map(|a| a.pointer("/max/0").and_then(|m| m.as_f64()).unwrap_or(0.0) as f32).collect();
    let animations = root.get_mut("animations").and_then(|a| a.as_array_mut());
    let ends = animations.into_iter().flatten().map(|a| without_pointer_channels(a, &key_ends)).collect();
    Ok((std::borrow::Cow::Owned(serde_json::to_vec(&root).map_err(|e| e.to_string())?), ends))
}

/// Removes `animation`'s `KHR_animation_pointer` channels and returns their last key (by
/// `key_ends`, each accessor's `max`), 0 for none or none readable.
fn without_pointer_channels(animation: &mut serde_json::Value, key_ends: &[f32]) -> f32 {
    let samplers = animation.get("samplers").and_then(|s| s.as_array()).map(Vec::as_slice).unwrap_or_default();
    let inputs: Vec<Option<u64>> = samplers.iter().map(|s| s.get("input").and_then(|i| i.as_u64())).collect();
    let mut end = 0.0f32;
    if let Some(channels) = animation.get_mut("channels").and_then(|c| c.as_array_mut()) {
        channels.retain(|c| {
            let pointer = c.pointer("/target/path").and_then(|p| p.as_str()) == Some("pointer");
            if pointer {
                let input = c.get("sampler").and_then(|s| s.as_u64()).and_then(|s| *inputs.get(s as usize)?);
                let key_end = input.and_then(|i| key_ends.get(i as usize)).copied().unwrap_or(0.0);
                end = end.max(if key_end.is_finite() { key_end } else { 0.0 });
            }
            !pointer
        });
    }
    end
}

/// `gltf` (read from a file of `size` bytes) checked, and every buffer it names read; the ends
/// of its animations' channels left out (`node_channels`) kept beside it.
fn with_buffers(
    (mut gltf, left_out_ends): (gltf::Gltf, Vec<f32>),
    size: u64,
    folder: &Path,
    limit: u64,
) -> Result<Loaded, String> {
    // Before validation, which refuses every extension the crate does not know by one message.
    if let Some(ext) = gltf.extensions_required().find(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
        return Err(format!("it requires the extension {ext}, which twinray does not support"));
    }
    let mut json = gltf.document.into_json();
    // The crate's validation refuses a required extension it has no feature for, even one
    // twinray reads itself (quantized attributes, instancing): checked above, then left out.
    json.extensions_required.retain(|e| gltf::json::extensions::ENABLED_EXTENSIONS.contains(&e.as_str()));
    unchecked_by_the_crate(&json)?;
    gltf.document = gltf::Document::from_json(json).map_err(invalid)?;
    let mut budget = limit.saturating_sub(size);
    let mut buffers = Vec::new();
    let mut blob = gltf.blob.take();
    for buffer in gltf.buffers() {
        let which = format!("buffer {}", buffer.index());
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => {
                blob.take().ok_or_else(|| format!("{which} is the GLB's binary chunk, which the file lacks"))?
            }
            gltf::buffer::Source::Uri(uri) => read_uri(uri, folder, budget).map_err(|e| format!("{which}: {e}"))?,
        };
        if data.len() < buffer.length() {
            return Err(format!("{which} holds {} bytes, fewer than its byteLength {}", data.len(), buffer.length()));
        }
        budget = budget.saturating_sub(data.len() as u64);
        buffers.push(data);
    }
    Ok(Loaded { gltf, buffers, left_out_ends, folder: folder.to_path_buf(), budget })
}

/// What the gltf crate assumes without checking, and panics on (each found by the fuzz
/// campaign, docs/testing.md): every primitive's POSITION names an accessor that exists (its
/// validation indexes the accessors with it first), and every image has exactly one of `uri`
/// and `bufferView`, with a `mimeType` beside a `bufferView` (`Image::source` unwraps both).
fn unchecked_by_the_crate(json: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::validation::Checked;
    for (i, image) in json.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (Some(_), None, _) | (None, Some(_), Some(_)) => {}
            (None, Some(_), None) => return Err(format!("image {i} has a bufferView but no mimeType")),
            _ => return Err(format!("image {i} needs exactly one of uri and bufferView")),
        }
    }
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let position = primitive.attributes.get(&Checked::Valid(gltf::json::mesh::Semantic::Positions));
            if let Some(index) = position.filter(|i| i.value() >= json.accessors.len()) {
                return Err(format!(
                    "mesh {m} primitive {p}: POSITION names accessor {}, but the file has {} accessors",
                    index.value(),
                    json.accessors.len()
                ));
            }
        }
    }
    Ok(())
}

/// The bytes of a buffer's or image's URI: a base64 `data:` URI, or a file relative to the
/// model's folder, at most `limit` bytes.
pub fn read_uri(uri: &str, folder: &Path, limit: u64) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest.split_once(";base64,").ok_or("a data URI that is not base64")?;
        if data.len() as u64 / 4 * 3 > limit {
            return Err(format!("its data URI holds more than the limit of {limit} bytes"));
        }
        return base64::engine::general_purpose::STANDARD.decode(data).map_err(|e| format!("its data URI: {e}"));
    }
    if uri.contains("://") {
        return Err(format!("{uri:?} is not a file beside the model (twinray reads no network URIs)"));
    }
    let file = confined(folder, &percent_decoded(uri)?).map_err(|e| format!("cannot read {uri:?}: {e}"))?;
    read_bounded(&file, limit).map_err(|e| format!("cannot read {uri:?}: {e}"))
}

/// A relative URI's path with its %XX escapes decoded.
fn percent_decoded(uri: &str) -> Result<String, String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = uri.get(i + 1..i + 3).and_then(|h| u8::from_str_radix(h, 16).ok());
            out.push(hex.ok_or_else(|| format!("{uri:?} has a bad %-escape"))?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("{uri:?} is not UTF-8 once decoded"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_uris_decode_and_escapes_resolve() {
        let folder = Path::new("/nonexistent");
        assert_eq!(read_uri("data:application/octet-stream;base64,AAEC", folder, 100).unwrap(), [0, 1, 2]);
        assert!(read_uri("data:application/octet-stream;base64,AAEC", folder, 2).is_err(), "over the limit");
        assert!(read_uri("data:text/plain,abc", folder, 100).unwrap_err().contains("not base64"));
        assert!(read_uri("https://example.com/a.bin", folder, 100).unwrap_err().contains("network"));
        assert_eq!(percent_decoded("a%20b.bin").unwrap(), "a b.bin");
        assert!(percent_decoded("a%2").is_err());
    }

    /// A GLB file read chunk by chunk gives what the `gltf` crate's reader of the whole file
    /// gives; a chunk of another type is skipped; a file cut short, or whose header claims
    /// more than it holds, is refused.
    #[test]
    fn glb_files_are_read_chunk_by_chunk() {
        let bytes =
            std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/gltf/square.glb")).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, b: &[u8]| {
            let path = dir.path().join(name);
            std::fs::write(&path, b).unwrap();
            path
        };
        let whole = parse(&bytes, dir.path(), 1 << 20).unwrap();
        let streamed = load(&write("square.glb", &bytes)).unwrap();
        assert_eq!(streamed.buffers, whole.buffers);
        assert!(!streamed.buffers.is_empty());
        // An unknown chunk between the JSON and the binary chunk.
        let json_end = 20 + u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let mut extra = bytes[..json_end].to_vec();
        extra.extend([4, 0, 0, 0]);
        extra.extend(b"XTRA");
        extra.extend([1, 2, 3, 4]);
        extra.extend(&bytes[json_end..]);
        let len = extra.len() as u32;
        extra[8..12].copy_from_slice(&len.to_le_bytes());
        assert_eq!(load(&write("extra.glb", &extra)).unwrap().buffers, whole.buffers);
        let cut = &bytes[..bytes.len() - 8];
        let e = load(&write("cut.glb", cut)).err().unwrap();
        assert!(e.contains("the file holds"), "{e}");
        let mut short = cut.to_vec();
        let len = short.len() as u32;
        short[8..12].copy_from_slice(&len.to_le_bytes());
        let e = load(&write("short.glb", &short)).err().unwrap();
        assert!(e.contains("reaches past"), "{e}");
    }
}
