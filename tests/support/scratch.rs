//! What the tests that work in a scratch copy of the repository share: the copy itself, and
//! cargo run in it with a target folder kept between runs.

use crate::repo_root as repo;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The target folder of this test binary's scratch copies, kept between runs: one per test
/// binary, so that `cargo xtask test` can run two such binaries side by side.
pub fn scaffold_target() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let stem = exe.file_stem().unwrap_or_default().to_string_lossy().into_owned();
    let test = stem.split('-').next().unwrap_or("scratch").to_string();
    twinray_compile::builder::cache_dir().join("scaffold-target").join(test)
}

/// The scaffold target for this test alone, until the returned file is dropped, seeded if it is
/// new. Two scratch copies building in one target at once would run each other's `cargo xtask`:
/// cargo puts the binary of every copy's xtask at the same path.
pub fn lock_scaffold_target() -> std::fs::File {
    let dir = scaffold_target();
    std::fs::create_dir_all(&dir).unwrap();
    let file = std::fs::File::create(dir.join("twinray-test.lock")).expect("creating the scaffold target's lock");
    file.lock().expect("locking the scaffold target");
    seed(&dir, "release");
    file
}

/// Fills an empty scaffold target's `profile` folder with a copy of the libraries, build script
/// outputs and fingerprints of that profile in the target this test was built in: the release
/// build the tests belong to, which also holds the build of xtask that runs them (`cargo xtask`
/// builds it in the release profile too). The
/// scratch copy's dependencies are the same crates in the same profile, so cargo reuses those
/// its fingerprints find unchanged and builds the rest (the copy's own crates at least): on a
/// cold machine that saves building every dependency of the host and of xtask a second time
/// (xtask's: 56 s on 2 cores). A copy, not links: cargo rewrites fingerprint files in place.
fn seed(dir: &Path, profile: &str) {
    let to = dir.join(profile);
    let target = std::env::current_exe().ok().and_then(|exe| Some(exe.parent()?.parent()?.parent()?.to_path_buf()));
    let Some(from) = target.map(|t| t.join(profile)) else {
        return;
    };
    if to.exists() || !from.join(".fingerprint").is_dir() {
        return;
    }
    let partial = to.with_extension("seeding");
    let _ = std::fs::remove_dir_all(&partial);
    for folder in [".fingerprint", "build", "deps"] {
        copy_tree(&from.join(folder), &partial.join(folder));
    }
    std::fs::rename(&partial, to).expect("placing the seeded scaffold target");
}

/// Copies a folder, leaving out executables without an extension (the test binaries in deps/).
/// A file that vanishes while it is copied is left out too: CI builds the docs in the same
/// target beside the tests, and rustdoc's temporary files come and go; the copy only seeds a
/// cache, and cargo rebuilds whatever it lacks.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    let gone = |e: &std::io::Error| e.kind() == std::io::ErrorKind::NotFound;
    let entries = match std::fs::read_dir(from) {
        Err(e) if gone(&e) => return,
        entries => entries.unwrap_or_else(|e| panic!("listing {}: {e}", from.display())),
    };
    for entry in entries {
        let copied = entry.and_then(|entry| {
            let (path, kind) = (entry.path(), entry.file_type()?);
            let target = to.join(entry.file_name());
            if kind.is_dir() {
                copy_tree(&path, &target);
            } else if kind.is_file() && !(from.ends_with("deps") && path.extension().is_none()) {
                // cargo compares these times with each other's.
                let modified = entry.metadata()?.modified()?;
                std::fs::copy(&path, &target)?;
                std::fs::File::options().write(true).open(&target)?.set_modified(modified)?;
            }
            Ok(())
        });
        match copied {
            Err(e) if !gone(&e) => panic!("copying from {}: {e}", from.display()),
            _ => {}
        }
    }
}

/// Seeds the cargo target of the shader crate `krate` (`target/twinray/cargo`, where `twinray
/// build` builds it) with the dependencies' builds of a starter crate (`twinray new`), built
/// once per machine in the cache and found up to date after that: the crate then builds only
/// its own code and twinray-shared. Each crate of the own-stages tests built core, spirv-std and
/// glam for the SPIR-V target from nothing (about 13 core-seconds each on 2 cores); a build from
/// nothing is what the own-stages tutorial's test does, with only the installed binary.
pub fn seed_crate_target(krate: &Path) {
    static SEED: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    let seed = SEED.get_or_init(|| {
        let dir = twinray_compile::builder::cache_dir().join("own-stages-seed");
        let (kept, fresh) = (dir.join("starter"), dir.join("fresh"));
        let _ = std::fs::remove_dir_all(&fresh);
        std::fs::create_dir_all(&fresh).unwrap();
        let made = crate::cli::twinray(&["new", "starter"], &fresh);
        assert!(made.status.success(), "twinray new: {}", text(&made));
        // The kept starter serves while this twinray writes the same dependencies; else (none
        // yet, another version's, one a stopped run left half made) the fresh one replaces it.
        let lock = |krate: &Path| std::fs::read(krate.join("Cargo.lock")).ok();
        if lock(&kept).is_none() || lock(&kept) != lock(&fresh.join("starter")) {
            let _ = std::fs::remove_dir_all(&kept);
            std::fs::rename(fresh.join("starter"), &kept).unwrap();
        }
        let _ = std::fs::remove_dir_all(&fresh);
        let out = crate::cli::twinray(&["build", "starter"], &dir);
        assert!(out.status.success(), "the seed crate's build: {}", text(&out));
        kept.join("target/twinray/cargo")
    });
    copy_tree(seed, &krate.join("target/twinray/cargo"));
}

/// A fresh copy of the repository (`copy_repo`) for the test that holds the scaffold target's
/// lock, at a path kept between runs beside that target (the last run's copy removed first).
/// At one path the copy's crates are the same packages to cargo run after run, so the
/// incremental data of the last run's builds serves this run's (`cargo_envs`); a new temporary
/// folder each run made them new packages, built from scratch.
pub fn kept_copy() -> PathBuf {
    let dir = scaffold_target().with_extension("copy");
    if dir.exists() {
        std::fs::remove_dir_all(&dir).unwrap_or_else(|e| panic!("removing the last copy {}: {e}", dir.display()));
    }
    copy_repo(&dir);
    dir
}

/// The repository's files as a checkout has them (tracked, and new files not ignored).
pub fn copy_repo(to: &Path) {
    let out = Command::new("git")
        .args(["ls-files", "-z", "--cached", "--others", "--exclude-standard"])
        .current_dir(repo())
        .output()
        .expect("git lists the repository's files");
    assert!(out.status.success(), "git ls-files: {}", String::from_utf8_lossy(&out.stderr));
    for name in out.stdout.split(|b| *b == 0).filter(|n| !n.is_empty()) {
        let name = String::from_utf8_lossy(name).into_owned();
        let (from, dest) = (repo().join(&name), to.join(&name));
        if let Ok(target) = std::fs::read_link(&from) {
            // host/spirv, host/scenes and host/probes: the links the host's package reads through.
            std::fs::create_dir_all(dest.parent().unwrap()).unwrap();
            std::os::unix::fs::symlink(target, &dest).unwrap_or_else(|e| panic!("linking {name}: {e}"));
            continue;
        }
        if !from.is_file() {
            continue; // deleted in the work tree, not yet in the index
        }
        std::fs::create_dir_all(dest.parent().unwrap()).unwrap();
        std::fs::copy(&from, &dest).unwrap_or_else(|e| panic!("copying {name}: {e}"));
    }
}

/// The environment cargo runs with in a scratch copy: the kept target, and release builds made
/// incrementally. Each step of a copy changes a few files and builds the host again in release
/// (new-shape, the tutorial's section 5, watch): 46 s each from scratch on 2 cores, a few
/// seconds incrementally. The binaries are as correct and a little slower; nothing a copy runs
/// is judged on its speed.
pub fn cargo_envs() -> [(&'static str, OsString); 2] {
    [("CARGO_TARGET_DIR", scaffold_target().into_os_string()), ("CARGO_PROFILE_RELEASE_INCREMENTAL", "true".into())]
}

pub fn cargo(args: &[&str], dir: &Path) -> Output {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    Command::new(cargo).args(args).current_dir(dir).envs(cargo_envs()).output().expect("running cargo")
}

pub fn text(out: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr))
}
