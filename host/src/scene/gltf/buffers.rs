//! A glTF file's bytes and its buffers, each read once and bounded: the file itself (JSON or
//! GLB), the GLB's binary chunk, `data:` URIs (base64) and files beside the model. Nothing is
//! read past `max_mesh_bytes` in all, and a buffer shorter than its declared `byteLength` is
//! refused here, so no accessor can later read past the data it names.

use super::super::mesh::max_mesh_bytes;
use crate::util::input::read_bounded;
use base64::Engine as _;
use std::path::Path;

/// Extensions twinray reads, so a model may require them.
pub const SUPPORTED_EXTENSIONS: [&str; 3] =
    ["KHR_lights_punctual", "KHR_texture_transform", "KHR_materials_emissive_strength"];

/// The parsed document and its buffers' bytes, in buffer order.
pub struct Loaded {
    pub gltf: gltf::Gltf,
    pub buffers: Vec<Vec<u8>>,
    /// Where image files are read from, and how many more bytes may be read.
    pub folder: std::path::PathBuf,
    pub budget: u64,
}

/// Reads and parses `path` (`.gltf` or `.glb`) and every buffer it names.
pub fn load(path: &Path) -> Result<Loaded, String> {
    let limit = max_mesh_bytes()?;
    let raise = |e: String| if e.contains("limit") { format!("{e} (TWINRAY_MAX_MESH_BYTES raises it)") } else { e };
    let bytes = read_bounded(path, limit).map_err(|e| format!("cannot read: {}", raise(e)))?;
    parse(&bytes, path.parent().unwrap_or(Path::new(".")), limit)
}

/// Parses a glTF file's `bytes` and reads every buffer it names, files relative to `folder`,
/// all of them together at most `limit` bytes.
pub fn parse(bytes: &[u8], folder: &Path, limit: u64) -> Result<Loaded, String> {
    let invalid = |e: gltf::Error| format!("not a valid glTF 2.0 file: {e}");
    let mut gltf = gltf::Gltf::from_slice_without_validation(bytes).map_err(invalid)?;
    // Before validation, which refuses every extension the crate does not know by one message.
    if let Some(ext) = gltf.extensions_required().find(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
        return Err(format!("it requires the extension {ext}, which twinray does not support"));
    }
    gltf.document = gltf::Document::from_json(gltf.document.into_json()).map_err(invalid)?;
    let mut budget = limit.saturating_sub(bytes.len() as u64);
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
    Ok(Loaded { gltf, buffers, folder: folder.to_path_buf(), budget })
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
    let file = folder.join(percent_decoded(uri)?);
    read_bounded(&file, limit).map_err(|e| format!("cannot read {}: {e}", file.display()))
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
}
