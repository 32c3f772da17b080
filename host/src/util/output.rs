//! Writing results: PNG files are written to a temporary file beside the target and renamed,
//! so a failure never leaves a partial file behind.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Writes an RGBA8 image of sRGB values as PNG at `path`, atomically, tagged sRGB (an `sRGB`
/// chunk, with the `gAMA` and `cHRM` that stand for it in older readers).
pub fn write_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    encode_png(path, (width, height), rgba, true)
}

/// Writes an RGBA8 image of linear values (test data such as golden images, compared in linear
/// steps) as PNG at `path`, atomically, tagged linear (`gAMA` 1.0), so that a viewer that reads
/// the tag shows it right.
pub fn write_linear_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    encode_png(path, (width, height), rgba, false)
}

fn encode_png(path: &Path, (width, height): (u32, u32), rgba: &[u8], srgb: bool) -> Result<()> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    match srgb {
        true => encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual),
        false => encoder.set_source_gamma(png::ScaledFloat::new(1.0)),
    }
    let encoded = encoder.write_header().and_then(|mut w| w.write_image_data(rgba).and_then(|()| w.finish()));
    encoded.map_err(|e| Error::Input(format!("writing {}: {e}", path.display())))?;
    write_atomically(path, &bytes)
}

/// Writes linear RGB radiance as OpenEXR at `path` (32-bit float channels, as rendered:
/// nothing clipped or encoded), atomically.
pub fn write_exr(path: &Path, width: u32, height: u32, linear: &[[f32; 3]]) -> Result<()> {
    let flat: Vec<f32> = linear.iter().flatten().copied().collect();
    let image = image::Rgb32FImage::from_raw(width, height, flat)
        .ok_or_else(|| Error::Input(format!("writing {}: the pixels do not fill the image", path.display())))?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::OpenExr)
        .map_err(|source| Error::Image { path: path.to_path_buf(), source })?;
    write_atomically(path, bytes.get_ref())
}

/// Writes a rendered image at `path`: OpenEXR of the linear radiance for a name ending in
/// `.exr`, else the sRGB PNG `picture`.
pub fn write_image(path: &Path, (width, height): (u32, u32), linear: &[[f32; 3]], picture: &[u8]) -> Result<()> {
    match is_exr(path) {
        true => write_exr(path, width, height, linear),
        false => write_png(path, width, height, picture),
    }
}

fn is_exr(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// Writes `bytes` at `path`, atomically: through a temporary file beside it, renamed.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = temp_path(path);
    let written = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    written.map_err(|source| {
        let _ = std::fs::remove_file(&tmp);
        Error::Io { what: "writing", path: path.to_path_buf(), source }
    })
}

/// Checks up front that `path` can be written: a file name in an existing directory.
pub fn check_file_target(path: &Path) -> Result<()> {
    let dir = parent_dir(path);
    if path.file_name().is_none() || path.is_dir() {
        return Err(Error::Input(format!("{}: not a file name", path.display())));
    }
    if !dir.is_dir() {
        return Err(Error::Input(format!("{}: directory {} does not exist", path.display(), dir.display())));
    }
    Ok(())
}

/// Checks up front that `path` can be written: a PNG name in an existing directory.
pub fn check_png_target(path: &Path) -> Result<()> {
    let is_png = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(Error::Input(format!("output {}: the file name must end in .png", path.display())));
    }
    check_dir(path)
}

/// Checks up front that `path` can be written: a PNG or EXR name in an existing directory.
pub fn check_image_target(path: &Path) -> Result<()> {
    let is_png = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png && !is_exr(path) {
        let name = path.display();
        return Err(Error::Input(format!("output {name}: the file name must end in .png (sRGB) or .exr (linear)")));
    }
    check_dir(path)
}

fn check_dir(path: &Path) -> Result<()> {
    let dir = parent_dir(path);
    if !dir.is_dir() {
        return Err(Error::Input(format!("output {}: directory {} does not exist", path.display(), dir.display())));
    }
    Ok(())
}

fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A temporary name beside `path`, unique to this process and call: two threads (or two
/// processes) writing the same file never share one.
pub(crate) fn temp_path(path: &Path) -> PathBuf {
    static COUNT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    parent_dir(path).join(format!(".{name}.{}.{n}.tmp", std::process::id()))
}

/// `name` in twinray's cache folder: `$XDG_CACHE_HOME/twinray`, else `~/.cache/twinray`,
/// else `twinray-NAME` in the working directory.
pub fn cache_dir(name: &str) -> PathBuf {
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")));
    base.map_or_else(|| PathBuf::from(format!("twinray-{name}")), |b| b.join("twinray").join(name))
}

/// A name usable in a file name: letters, digits, '-' and '_' kept, anything else '_'.
pub fn file_safe(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_png_and_leaves_no_temp_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.png");
        write_png(&path, 1, 1, &[1, 2, 3, 255]).unwrap();
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, vec![std::ffi::OsString::from("x.png")]);
    }

    #[test]
    fn rejects_non_png_names_and_missing_directories() {
        assert!(check_png_target(Path::new("out.jpg")).is_err());
        assert!(check_png_target(Path::new("/no/such/dir/out.png")).is_err());
        assert!(check_png_target(Path::new("out.png")).is_ok());
    }
}
