//! What the tests that work in a scratch copy of the repository share: the copy itself, and
//! cargo run in it with a target folder kept between runs.
#![allow(dead_code)] // each test crate that includes this module uses a part of it

pub mod docs;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

pub fn scaffold_target() -> PathBuf {
    let cache = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(|| repo().join("target"));
    cache.join("twinray/scaffold-target")
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
            // host/spirv and host/scenes: the links the host's package reads through.
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

pub fn cargo(args: &[&str], dir: &Path) -> Output {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    Command::new(cargo)
        .args(args)
        .current_dir(dir)
        .env("CARGO_TARGET_DIR", scaffold_target())
        .output()
        .expect("running cargo")
}

pub fn text(out: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr))
}
