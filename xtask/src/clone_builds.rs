//! The dependencies' builds a fresh clone starts from: after a passing `cargo xtask ci`, the
//! libraries, build script outputs and fingerprints of every package that is not the
//! workspace's own (the registry's crates) are kept in `$XDG_CACHE_HOME/twinray/clone-builds`,
//! and `.ci/run` copies them into a clone that has no `target/` yet. cargo then decides, by its
//! own fingerprints, what it can reuse: a registry crate of the same version, features,
//! profile and compiler; the workspace's crates are always rebuilt (a clone's files are newer
//! than anything built before it). Builds of the same sources are what a CI cache keeps.

use anyhow::{Context, Result};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Where the kept builds lie. `.ci/run` names the same folder.
pub fn dir() -> PathBuf {
    crate::process::cache_home().join("twinray/clone-builds")
}

/// The marker `.ci/run` leaves in a `target/` it seeded, so that the run's summary can tell a
/// seeded clone from one that built before.
pub const SEEDED: &str = "seeded-from-clone-builds";

/// The profile CI builds, xtask's and the tests' alike.
const PROFILES: [&str; 1] = ["release"];

/// Replaces the kept builds in `to` with the dependencies' builds in `target`, whose workspace
/// has the packages `own`; returns the bytes kept. A copy (cargo rewrites fingerprints in
/// place), written aside and then moved into place, so that a failed save leaves the last one
/// whole.
pub fn save(target: &Path, own: &BTreeSet<String>, to: &Path) -> Result<u64> {
    let partial = to.with_extension("saving");
    let _ = std::fs::remove_dir_all(&partial);
    let mut bytes = 0;
    for profile in PROFILES {
        for folder in [".fingerprint", "build", "deps"] {
            let from = target.join(profile).join(folder);
            if from.is_dir() {
                bytes += copy_dependencies(&from, &partial.join(profile).join(folder), own)?;
            }
        }
    }
    let _ = std::fs::remove_dir_all(to);
    std::fs::rename(&partial, to).with_context(|| format!("placing {}", to.display()))?;
    Ok(bytes)
}

/// Copies the entries of one of cargo's folders that belong to no package of `own`, leaving
/// out executables without an extension (test binaries, in `deps/`), with their times.
fn copy_dependencies(from: &Path, to: &Path, own: &BTreeSet<String>) -> Result<u64> {
    std::fs::create_dir_all(to)?;
    let mut bytes = 0;
    for entry in std::fs::read_dir(from)? {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if own.contains(&package_of(&name)) {
            continue;
        }
        let (path, kind) = (entry.path(), entry.file_type()?);
        if kind.is_dir() {
            bytes += copy_tree(&path, &to.join(&name))?;
        } else if kind.is_file() && path.extension().is_some() {
            bytes += copy_file(&path, &to.join(&name))?;
        }
    }
    Ok(bytes)
}

fn copy_tree(from: &Path, to: &Path) -> Result<u64> {
    std::fs::create_dir_all(to)?;
    let mut bytes = 0;
    for entry in std::fs::read_dir(from)? {
        let entry = entry?;
        let (path, kind) = (entry.path(), entry.file_type()?);
        if kind.is_dir() {
            bytes += copy_tree(&path, &to.join(entry.file_name()))?;
        } else if kind.is_file() {
            bytes += copy_file(&path, &to.join(entry.file_name()))?;
        }
    }
    Ok(bytes)
}

/// A copy with the original's modification time: cargo compares these times with each other's.
fn copy_file(from: &Path, to: &Path) -> Result<u64> {
    let bytes = std::fs::copy(from, to).with_context(|| format!("copying {}", from.display()))?;
    let modified = std::fs::metadata(from)?.modified()?;
    std::fs::File::options().write(true).open(to)?.set_modified(modified)?;
    Ok(bytes)
}

/// The package an entry of `.fingerprint/`, `build/` or `deps/` is named after, as cargo names
/// them: `NAME-HASH` (a folder), `libNAME-HASH.rlib` (a library), `NAME-HASH.d`, with `-` in
/// package names and `_` in crate names; returned with `-` for both.
fn package_of(entry: &str) -> String {
    let (stem, extension) = entry.split_once('.').unwrap_or((entry, ""));
    let name = stem.rsplit_once('-').map_or(stem, |(name, _hash)| name);
    let library = ["rlib", "rmeta", "so", "a"].contains(&extension);
    let name = if library { name.strip_prefix("lib").unwrap_or(name) } else { name };
    name.replace('_', "-")
}

/// The workspace's own packages, from `cargo metadata`.
pub fn own_packages(root: &Path) -> Result<BTreeSet<String>> {
    let out = crate::process::output(
        crate::process::cargo_command(&["metadata", "--no-deps", "--format-version", "1", "--offline"], &[])
            .current_dir(root),
    )?;
    let metadata: serde_json::Value = serde_json::from_str(&out).context("cargo metadata's JSON")?;
    let packages = metadata["packages"].as_array().context("cargo metadata lists no packages")?;
    Ok(packages.iter().filter_map(|p| Some(p["name"].as_str()?.replace('_', "-"))).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_are_named_after_their_package() {
        assert_eq!(package_of("twinray-shared-0123456789abcdef"), "twinray-shared");
        assert_eq!(package_of("libtwinray_shared-0123456789abcdef.rlib"), "twinray-shared");
        assert_eq!(package_of("serde_json-0123456789abcdef.d"), "serde-json");
        assert_eq!(package_of("libc-0123456789abcdef"), "libc");
        assert_eq!(package_of("liblibc-0123456789abcdef.rmeta"), "libc");
        assert_eq!(package_of("xtask-0123456789abcdef"), "xtask");
    }

    #[test]
    fn a_save_keeps_the_dependencies_with_their_times_and_nothing_of_the_workspace() {
        let target = tempfile::tempdir().unwrap();
        let put = |path: &str| {
            let file = target.path().join(path);
            std::fs::create_dir_all(file.parent().unwrap()).unwrap();
            std::fs::write(&file, path).unwrap();
            let then = std::time::SystemTime::UNIX_EPOCH + std::time::Duration::from_secs(1_000_000);
            std::fs::File::options().write(true).open(&file).unwrap().set_modified(then).unwrap();
        };
        let kept = [
            "release/deps/libserde-0a.rlib",
            "release/.fingerprint/serde-0a/lib-serde",
            "release/build/libc-0b/out/x.rs",
        ];
        let dropped = [
            "release/deps/libtwinray_shared-0c.rlib",
            "release/deps/integration-0d",
            "release/.fingerprint/xtask-0e/bin-xtask",
            "release/twinray",
        ];
        kept.iter().chain(&dropped).for_each(|p| put(p));
        let own = BTreeSet::from(["twinray-shared".to_string(), "xtask".to_string()]);
        let cache = tempfile::tempdir().unwrap();
        let to = cache.path().join("clone-builds");
        std::fs::create_dir_all(to.join("release/deps/old")).unwrap(); // replaced whole
        save(target.path(), &own, &to).unwrap();
        for path in kept {
            let copy = to.join(path);
            assert_eq!(std::fs::read_to_string(&copy).unwrap(), path);
            let times = |p: &Path| std::fs::metadata(p).unwrap().modified().unwrap();
            assert_eq!(times(&copy), times(&target.path().join(path)), "{path} keeps its time");
        }
        for path in dropped.iter().chain(&["release/deps/old"]) {
            assert!(!to.join(path).exists(), "{path} is not kept");
        }
    }
}
