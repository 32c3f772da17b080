//! Reading input files without trusting them: only regular files (a device such as /dev/zero
//! never ends, a FIFO may never start), never more than a stated size, read with that bound
//! even if the file grows meanwhile.

use std::io::Read;
use std::path::Path;

/// Largest scene or probe case file read, in bytes.
pub const MAX_TEXT_BYTES: u64 = 64 << 20;

/// The bytes of the regular file at `path`, if it holds at most `limit` bytes; the error
/// says why not, in words fit to follow "cannot read FILE: ".
pub fn read_bounded(path: &Path, limit: u64) -> Result<Vec<u8>, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if meta.len() > limit {
        return Err(format!("{} bytes, over the limit of {limit}", meta.len()));
    }
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    if bytes.len() as u64 > limit {
        return Err(format!("grew past the limit of {limit} bytes while being read"));
    }
    Ok(bytes)
}

/// As `read_bounded`, as UTF-8 text.
pub fn read_text(path: &Path, limit: u64) -> Result<String, String> {
    String::from_utf8(read_bounded(path, limit)?).map_err(|e| format!("not UTF-8 text ({e})"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_devices_directories_and_large_files() {
        assert_eq!(read_bounded(Path::new("/dev/zero"), 100).unwrap_err(), "not a regular file");
        assert_eq!(read_bounded(Path::new("."), 100).unwrap_err(), "not a regular file");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f");
        std::fs::write(&path, [b'x'; 10]).unwrap();
        assert_eq!(read_bounded(&path, 10).unwrap().len(), 10);
        assert!(read_bounded(&path, 9).unwrap_err().contains("10 bytes, over the limit of 9"));
        std::fs::write(&path, [0xff, 0xfe]).unwrap();
        assert!(read_text(&path, 10).unwrap_err().starts_with("not UTF-8 text"));
    }
}
