//! Reading input files without trusting them: only regular files (a device such as /dev/zero
//! never ends, a FIFO may never start), never more than a stated size, read with that bound
//! even if the file grows meanwhile.

use std::io::Read;
use std::path::{Component, Path, PathBuf};
use std::sync::OnceLock;

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

/// The folder every file a model or scene names must lie in, when the user names one
/// (`--asset-root`); unset, each naming file's own folder.
static ASSET_ROOT: OnceLock<PathBuf> = OnceLock::new();

/// Sets the asset root (`--asset-root DIR`), once per process (again with the same folder
/// does nothing): `dir` must be a folder.
pub fn set_asset_root(dir: &Path) -> Result<(), String> {
    let root = dir.canonicalize().map_err(|e| format!("--asset-root {}: {e}", dir.display()))?;
    if !root.is_dir() {
        return Err(format!("--asset-root {}: not a folder", dir.display()));
    }
    match ASSET_ROOT.get_or_init(|| root.clone()) {
        set if *set == root => Ok(()),
        set => Err(format!("the asset root is {} already", set.display())),
    }
}

/// The file `name` names, relative to `folder` (the folder of the model or scene that names
/// it), if it lies inside the asset root (`--asset-root`, else `folder`) and is a regular
/// file: an absolute path, a `..` or a symbolic link that leaves the root, and anything but a
/// regular file are refused. A model cannot lead twinray to read another file of the disk.
/// The error names `name`, never what the file holds.
pub fn confined(folder: &Path, name: &str) -> Result<PathBuf, Unconfined> {
    let folder = if folder.as_os_str().is_empty() { Path::new(".") } else { folder };
    let root = match ASSET_ROOT.get() {
        Some(root) => root.clone(),
        None => folder
            .canonicalize()
            .map_err(|e| Unconfined::Unreadable(format!("the folder {}: {e}", folder.display())))?,
    };
    confined_in(&root, folder, name, ASSET_ROOT.get().is_some())
}

/// Why a named file is not read: it lies (or would lie) outside the root, which a model may
/// not ask for; or it cannot be read, which some formats allow (an OBJ's missing material
/// library is a notice).
#[derive(Debug, PartialEq)]
pub enum Unconfined {
    Outside(String),
    Unreadable(String),
}

impl std::fmt::Display for Unconfined {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Unconfined::Outside(why) | Unconfined::Unreadable(why) => f.write_str(why),
        }
    }
}

/// `absolute_inside`: an absolute path is taken when it lies inside `root` (a root the user
/// named), else refused.
fn confined_in(root: &Path, folder: &Path, name: &str, absolute_inside: bool) -> Result<PathBuf, Unconfined> {
    let path = Path::new(name);
    let outside = |why: &str| Unconfined::Outside(format!("{name:?} {why}"));
    if name.is_empty() {
        return Err(Unconfined::Outside("an empty file name".into()));
    }
    if !absolute_inside && (path.has_root() || path.components().any(|c| matches!(c, Component::Prefix(_)))) {
        return Err(outside(
            "is an absolute path; a model names its files relative to its folder (or inside --asset-root)",
        ));
    }
    let leads_out = || {
        let root = root.display();
        outside(&format!(
            "leads outside {root} (files a model names must lie there; --asset-root names another folder)"
        ))
    };
    let real = match folder.join(path).canonicalize() {
        Ok(real) => real,
        // Missing: outside if its `..`s alone lead out, else unreadable.
        Err(e) => {
            let mut at = folder.canonicalize().map_err(|e| Unconfined::Unreadable(format!("{name:?}: {e}")))?;
            for part in path.components() {
                match part {
                    Component::ParentDir => drop(at.pop()),
                    Component::Normal(part) => at.push(part),
                    _ => {}
                }
            }
            return Err(if at.starts_with(root) {
                Unconfined::Unreadable(format!("{name:?}: {e}"))
            } else {
                leads_out()
            });
        }
    };
    if !real.starts_with(root) {
        return Err(leads_out());
    }
    match std::fs::metadata(&real) {
        Ok(meta) if meta.is_file() => Ok(real),
        Ok(_) => Err(outside("is not a regular file")),
        Err(e) => Err(Unconfined::Unreadable(format!("{name:?}: {e}"))),
    }
}

/// As `read_bounded`, as UTF-8 text.
pub fn read_text(path: &Path, limit: u64) -> Result<String, String> {
    String::from_utf8(read_bounded(path, limit)?).map_err(|e| format!("not UTF-8 text ({e})"))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every way out of a model's folder is refused, by name: absolute paths, `..`, a symbolic
    /// link to a file outside and one to a folder outside, a device, a folder; a file inside,
    /// also through `..` that stays inside or a link that does, is found.
    #[test]
    fn a_named_file_must_lie_inside_the_root() {
        let dir = tempfile::tempdir().unwrap();
        let (root, outside) = (dir.path().join("model"), dir.path().join("secret"));
        std::fs::create_dir_all(root.join("textures")).unwrap();
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::write(root.join("textures/a.png"), b"inside").unwrap();
        std::fs::write(outside.join("key.bin"), b"outside").unwrap();
        std::os::unix::fs::symlink(outside.join("key.bin"), root.join("link.bin")).unwrap();
        std::os::unix::fs::symlink(&outside, root.join("away")).unwrap();
        std::os::unix::fs::symlink(root.join("textures/a.png"), root.join("near.png")).unwrap();
        let root = root.canonicalize().unwrap();
        let at = |folder: &Path, name: &str| confined_in(&root, folder, name, false);
        let textures = root.join("textures");
        assert_eq!(at(&root, "textures/a.png").unwrap(), textures.join("a.png"));
        assert_eq!(at(&textures, "../textures/./a.png").unwrap(), textures.join("a.png"));
        assert_eq!(at(&root, "near.png").unwrap(), textures.join("a.png"));
        let refused = [
            (outside.join("key.bin").display().to_string(), "absolute path"),
            ("/etc/passwd".to_string(), "absolute path"),
            ("../secret/key.bin".to_string(), "leads outside"),
            ("textures/../../secret/key.bin".to_string(), "leads outside"),
            ("link.bin".to_string(), "leads outside"),
            ("away/key.bin".to_string(), "leads outside"),
            ("textures".to_string(), "not a regular file"),
            ("missing.png".to_string(), "No such file"),
            ("../secret/missing.png".to_string(), "leads outside"),
            (String::new(), "empty file name"),
        ];
        for (name, why) in refused {
            let e = at(&root, &name).unwrap_err();
            let unreadable = matches!(e, Unconfined::Unreadable(_));
            assert_eq!(unreadable, why == "No such file", "{name}: {e}");
            let e = e.to_string();
            assert!(e.contains(why) && (name.is_empty() || e.contains(&format!("{name:?}"))), "{name}: {e}");
            assert!(!e.contains("outside\"") && !e.contains("inside\""), "never the file's bytes: {e}");
        }
        // Under a root the user named, an absolute path inside it is taken, one outside not.
        let named = |name: &str| confined_in(&root, &root, name, true);
        assert_eq!(named(&textures.join("a.png").display().to_string()).unwrap(), textures.join("a.png"));
        assert!(named(&outside.join("key.bin").display().to_string())
            .unwrap_err()
            .to_string()
            .contains("leads outside"));
        // With no asset root set, a model's root is its own folder.
        std::fs::write(root.join("beside.bin"), b"beside").unwrap();
        assert!(confined(&root, "beside.bin").is_ok());
        assert!(confined(&textures, "../beside.bin").unwrap_err().to_string().contains("leads outside"));
    }

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
