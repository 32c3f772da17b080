//! The caches a CI run finds at its start, cold or warm: what its total time depends on most
//! (docs/testing.md, *CI and its time*, has the figures both ways). A cold machine builds the
//! rust-gpu builder, the tutorial's scratch copy, the own-stages tests' starter crate, every
//! lavapipe pipeline and every dependency; a fresh clone builds the workspace's own crates
//! whatever the machine holds.

use crate::process::cache_home;
use std::path::{Path, PathBuf};

/// One cache: what it is, where it lies, whether it held anything at the start, and whether it
/// outlives a fresh clone (the clone's own build does not).
pub struct Cache {
    pub what: &'static str,
    pub path: PathBuf,
    pub warm: bool,
    pub machine: bool,
}

/// Whether `dir` holds any entry.
fn filled(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|mut entries| entries.next().is_some())
}

/// The caches of a CI run of the workspace at `root`, as they are now.
pub fn survey(root: &Path) -> Vec<Cache> {
    let target = crate::process::target_dir(root);
    let mesa = std::env::var_os("MESA_SHADER_CACHE_DIR").map(PathBuf::from).unwrap_or_else(cache_home);
    let twinray = cache_home().join("twinray");
    let builder = twinray_compile::builder_target().join("release/twinray-shader-builder");
    // Mesa keeps one of two layouts, by version and settings.
    let mesa_warm = filled(&mesa.join("mesa_shader_cache_db")) || filled(&mesa.join("mesa_shader_cache"));
    let clone = target.join("release/.fingerprint");
    // A clone that `.ci/run` seeded holds the dependencies' builds, not a build of its own.
    let built = filled(&clone) && !target.join(crate::clone_builds::SEEDED).exists();
    let kept = crate::clone_builds::dir();
    let seed = twinray.join("own-stages-seed/starter");
    [
        ("cargo's release build", built, clone, false),
        ("the dependencies' builds", filled(&kept.join("release/deps")), kept, true),
        ("the rust-gpu builder", builder.is_file(), builder, true),
        ("Mesa's shader cache", mesa_warm, mesa.join("mesa_shader_cache_db"), true),
        ("the tutorial's build", filled(&twinray.join("scaffold-target")), twinray.join("scaffold-target"), true),
        // twinray_tests::scratch::seed_crate_target: the own-stages tests' crates start from it.
        ("the own-stages tests' starter", filled(&seed.join("target")), seed, true),
    ]
    .into_iter()
    .map(|(what, warm, path, machine)| Cache { what, path, warm, machine })
    .collect()
}

/// Of the machine's caches: "cold" where none was warm, "warm" where all were, else which were
/// cold; and whether the clone's own build was there.
pub fn verdict(caches: &[Cache]) -> String {
    let machine: Vec<&Cache> = caches.iter().filter(|c| c.machine).collect();
    let cold: Vec<&str> = machine.iter().filter(|c| !c.warm).map(|c| c.what).collect();
    let how = match cold.len() {
        0 => "warm (the machine's caches filled)".to_string(),
        n if n == machine.len() => "cold (the machine's caches empty)".to_string(),
        _ => format!("partly cold ({} empty)", cold.join(", ")),
    };
    let built = caches.iter().any(|c| !c.machine && c.warm);
    format!("{how}, {}", if built { "the clone built before" } else { "the clone built afresh" })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cache(what: &'static str, warm: bool, machine: bool) -> Cache {
        Cache { what, path: PathBuf::new(), warm, machine }
    }

    #[test]
    fn the_verdict_names_the_empty_caches_of_the_machine() {
        let all = |warm| vec![cache("clone", false, false), cache("a", warm, true), cache("b", warm, true)];
        assert_eq!(verdict(&all(true)), "warm (the machine's caches filled), the clone built afresh");
        assert_eq!(verdict(&all(false)), "cold (the machine's caches empty), the clone built afresh");
        let mixed = [cache("clone", true, false), cache("a", true, true), cache("b", false, true)];
        assert_eq!(verdict(&mixed), "partly cold (b empty), the clone built before");
    }
}
