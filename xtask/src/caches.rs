//! The caches a CI run finds at its start, cold or warm: what its total time depends on most
//! (docs/testing.md, *CI and its time*, has the figures both ways). A cold machine builds every
//! crate, the rust-gpu builder and every lavapipe pipeline, and renders every reference.

use std::path::{Path, PathBuf};

/// One cache: what it is, where it lies, and whether it held anything at the start.
pub struct Cache {
    pub what: &'static str,
    pub path: PathBuf,
    pub warm: bool,
}

/// `$XDG_CACHE_HOME`, else `~/.cache`, as twinray, Mesa and the shader builder read it.
fn cache_home() -> PathBuf {
    std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir)
}

/// Whether `dir` holds any entry.
fn filled(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|mut entries| entries.next().is_some())
}

/// The caches of a CI run of the workspace at `root`, as they are now.
pub fn survey(root: &Path) -> Vec<Cache> {
    let target = std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| root.join("target"));
    let mesa = std::env::var_os("MESA_SHADER_CACHE_DIR").map(PathBuf::from).unwrap_or_else(cache_home);
    let twinray = cache_home().join("twinray");
    let builder = twinray_build::builder_target().join("release/twinray-shader-builder");
    // Mesa keeps one of two layouts, by version and settings.
    let mesa_warm = filled(&mesa.join("mesa_shader_cache_db")) || filled(&mesa.join("mesa_shader_cache"));
    [
        ("cargo's release build", target.join("release/.fingerprint"), None),
        ("the rust-gpu builder", builder.clone(), Some(builder.is_file())),
        ("Mesa's shader cache", mesa.join("mesa_shader_cache_db"), Some(mesa_warm)),
        ("the references", twinray.join("references"), None),
        ("the tutorial's build", twinray.join("scaffold-target"), None),
    ]
    .into_iter()
    .map(|(what, path, warm)| Cache { warm: warm.unwrap_or_else(|| filled(&path)), what, path })
    .collect()
}

/// "cold" where none was warm, "warm" where all were, else which were cold.
pub fn verdict(caches: &[Cache]) -> String {
    let cold: Vec<&str> = caches.iter().filter(|c| !c.warm).map(|c| c.what).collect();
    match cold.len() {
        0 => "warm (every cache filled)".into(),
        n if n == caches.len() => "cold (every cache empty)".into(),
        _ => format!("partly cold ({} empty)", cold.join(", ")),
    }
}
