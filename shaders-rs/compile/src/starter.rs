//! `twinray new`: a shader crate of one's own, written from the sources this binary carries
//! (`build.rs` embeds them), so that an installed `twinray` needs no checkout. The crate holds
//! the built-in Rust stages unchanged (it renders exactly as the `rust` set before any edit),
//! the contract they were built against (`twinray-shared/`, a path dependency), the pinned
//! toolchain file, a README, and with `glsl` the GLSL twins in `glsl/`.

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

include!(concat!(env!("OUT_DIR"), "/embedded_sources.rs"));

/// Where the contract's copy lives in a starter crate, relative to its root.
pub const SHARED_DIR: &str = "twinray-shared";
/// Where the GLSL twins live in a starter crate written with `glsl`.
pub const GLSL_DIR: &str = "glsl";

const README: &str = include_str!("../starter/README.md");

/// What `write` made: every file, relative to the crate.
pub struct Written {
    pub files: Vec<PathBuf>,
}

/// The package name for a crate in `dir`: `name` when given, else the folder's name made a
/// valid one (lower case, `-` for anything but letters, digits and `_`).
pub fn package_name(dir: &Path, name: Option<&str>) -> Result<String> {
    let raw = match name {
        Some(name) => name.to_string(),
        None => dir.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default(),
    };
    let cleaned: String = raw
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() || c == '_' || c == '-' { c.to_ascii_lowercase() } else { '-' })
        .collect();
    let cleaned = cleaned.trim_matches('-').to_string();
    if !cleaned.starts_with(|c: char| c.is_ascii_lowercase()) || cleaned.len() > 64 {
        bail!("{raw:?} cannot be a crate's name (a letter first, then letters, digits, - or _): give one with --name");
    }
    Ok(cleaned)
}

/// Writes a starter crate named `name` into `dir`, which must not exist or be empty: nothing
/// of a user's is overwritten. With `glsl`, the GLSL twins too.
pub fn write(dir: &Path, name: &str, glsl: bool) -> Result<Written> {
    if dir.exists() {
        let mut entries = std::fs::read_dir(dir).with_context(|| format!("{} is not a folder", dir.display()))?;
        if entries.next().is_some() {
            bail!("{} already holds files: give a new or empty folder (nothing is overwritten)", dir.display());
        }
    }
    let mut files = Vec::new();
    for (path, bytes) in STAGES {
        let text = match *path {
            "Cargo.toml" => manifest(bytes, name)?,
            "Cargo.lock" => lock(bytes, name)?,
            _ => bytes.to_vec(),
        };
        files.push((PathBuf::from(path), text));
    }
    files.extend(SHARED.iter().map(|(p, b)| (Path::new(SHARED_DIR).join(p), b.to_vec())));
    if glsl {
        files.extend(GLSL.iter().map(|(p, b)| (Path::new(GLSL_DIR).join(p), b.to_vec())));
    }
    let readme = README.replace("{name}", name).replace("{contract}", twinray_shared::contract::CONTRACT_VERSION);
    files.push(("README.md".into(), readme.into_bytes()));
    files.push((".gitignore".into(), b"target/\n".to_vec()));
    for (path, bytes) in &files {
        let full = dir.join(path);
        if let Some(parent) = full.parent() {
            std::fs::create_dir_all(parent).with_context(|| format!("creating {}", parent.display()))?;
        }
        std::fs::write(&full, bytes).with_context(|| format!("writing {}", full.display()))?;
    }
    // The crate's own shared library, where `twinray new --shape` puts shapes.
    let shared = crate::scaffold::ensure_shared(dir, name)?;
    let mut written: Vec<PathBuf> = files.into_iter().map(|(p, _)| p).collect();
    written.extend(shared.into_iter().filter(|p| !written.contains(p)).collect::<Vec<_>>());
    Ok(Written { files: written })
}

/// Replaces `from` by `to` in `text`, failing when `from` is not there: the embedded file
/// changed and this must follow.
fn swap(text: &str, from: &str, to: &str) -> Result<String> {
    if !text.contains(from) {
        bail!("the embedded shader crate has no {from:?} (twinray-compile's starter must follow it)");
    }
    Ok(text.replacen(from, to, 1))
}

/// The built-in crate's manifest, renamed, with the contract as a path beside it.
fn manifest(bytes: &[u8], name: &str) -> Result<Vec<u8>> {
    let text = String::from_utf8_lossy(bytes);
    let text = swap(&text, "name = \"twinray-stages\"", &format!("name = \"{name}\""))?;
    let text = swap(&text, "path = \"../shared\"", &format!("path = \"{SHARED_DIR}\""))?;
    // A path dependency inside the crate's folder would be a member of its workspace, its
    // optional dependencies locked too: the lock would need the network, and differ.
    let text = swap(&text, "[workspace]\n", &format!("[workspace]\nexclude = [\"{SHARED_DIR}\"]\n"))?;
    let start = text.find("description = ").context("the embedded manifest has no description")?;
    let end = start + text[start..].find('\n').unwrap_or(text.len() - start);
    let description = "description = \"Ray tracing stages for twinray, built by rust-gpu (`twinray build`).\"";
    Ok(format!("{}{description}{}", &text[..start], &text[end..]).into_bytes())
}

/// The built-in crate's lock file with the package renamed: the same versions of every
/// dependency, resolved without the network. Its packages are put back in cargo's order (by
/// name, then version), so that a build does not rewrite the file.
fn lock(bytes: &[u8], name: &str) -> Result<Vec<u8>> {
    let text = swap(&String::from_utf8_lossy(bytes), "name = \"twinray-stages\"", &format!("name = \"{name}\""))?;
    Ok(crate::scaffold::sorted_lock(&text).into_bytes())
}

/// The embedded builder's sources (`shaders-rs/builder`), for a machine without a checkout.
pub fn builder_sources() -> &'static [(&'static str, &'static [u8])] {
    BUILDER
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_come_from_the_folder_or_are_refused() {
        assert_eq!(package_name(Path::new("/tmp/My Stages"), None).unwrap(), "my-stages");
        assert_eq!(package_name(Path::new("x"), Some("mine_2")).unwrap(), "mine_2");
        assert!(package_name(Path::new("/tmp/2fast"), None).is_err());
        assert!(package_name(Path::new("/"), None).is_err());
    }

    /// The Rust source files of the starter: (path under the crate, text).
    fn sources() -> Vec<(&'static str, String)> {
        let rust = STAGES.iter().filter(|(p, _)| p.starts_with("src/") && p.ends_with(".rs"));
        rust.map(|(p, b)| (*p, String::from_utf8_lossy(b).into_owned())).collect()
    }

    /// Every entry point of the starter written out, each in the file named by its stage kind,
    /// as the README's table lists it; no macro makes one.
    #[test]
    fn each_entry_point_is_plain_in_its_stage_kinds_file_as_the_readme_says() {
        let mut entries = Vec::new();
        for (path, text) in sources() {
            let in_macros = text.split("macro_rules!").skip(1);
            assert!(!in_macros.clone().any(|m| m.contains("#[spirv(")), "{path}: a macro makes entry points");
            let lines: Vec<&str> = text.lines().collect();
            for (i, line) in lines.iter().enumerate() {
                let Some(kind) = line.strip_prefix("#[spirv(") else { continue };
                let kind = kind.split(['(', ')']).next().unwrap();
                let name = lines[i + 1..].iter().find_map(|l| l.strip_prefix("pub fn ")).unwrap();
                let name = name.split('(').next().unwrap().to_string();
                assert_eq!(path, format!("src/{kind}.rs"), "{name} is a {kind} stage");
                entries.push((name, path));
            }
        }
        let catalog: Vec<&str> = twinray_shared::catalog::MODULES.iter().map(|m| m.name).collect();
        let mut names: Vec<&str> = entries.iter().map(|(n, _)| n.as_str()).collect();
        names.sort();
        let mut expected = catalog.clone();
        expected.sort();
        assert_eq!(names, expected, "the starter's entry points are the catalog's modules");
        for row in README.lines().filter(|l| l.starts_with("| ") && l.contains("`src/")) {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            let file = cells[3].trim_matches('`');
            for listed in cells[2].split('`').skip(1).step_by(2) {
                assert!(
                    entries.contains(&(listed.to_string(), file)),
                    "README: {listed} is not an entry point of {file}"
                );
            }
        }
        for (name, _) in &entries {
            assert!(README.contains(&format!("`{name}`")), "README's table does not list {name}");
        }
    }

    #[test]
    fn a_starter_crate_holds_the_stages_the_contract_and_the_twins() {
        let dir = std::env::temp_dir().join(format!("twinray-starter-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let written = write(&dir, "my-stages", true).unwrap();
        let manifest = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
        assert!(manifest.contains("name = \"my-stages\"") && manifest.contains("path = \"twinray-shared\""));
        assert!(manifest.contains("crate-type = [\"dylib\"]"));
        assert!(std::fs::read_to_string(dir.join("Cargo.lock")).unwrap().contains("name = \"my-stages\""));
        for file in
            ["src/lib.rs", "src/closest_hit.rs", "twinray-shared/src/contract.rs", "glsl/raygen.rgen", "README.md"]
        {
            assert!(dir.join(file).is_file(), "{file} missing");
        }
        assert!(written.files.len() > 40);
        // Written twice, nothing is overwritten.
        let again = write(&dir, "my-stages", false).err().unwrap().to_string();
        assert!(again.contains("already holds files"), "{again}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
