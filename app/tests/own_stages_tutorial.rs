//! docs/tutorial-own-stages.md, followed in an empty folder outside the checkout with only an
//! installed `twinray` (and rustup's toolchains) to run: what a user without a checkout has.
//!
//! The installed binary is this build's `twinray`, copied into a folder of its own, as `cargo
//! install --path app` copies the same package's release binary into `~/.cargo/bin`: the host
//! is built once for every test, where a `cargo install` here built it a second time (177 s of
//! a CI run on 2 cores). `install.rs` checks what the install carries.

use std::path::Path;
use std::time::Instant;
use twinray_tests::cli::exe;
use twinray_tests::repo_root as repo;
use twinray_tests::tutorial::{follow, run, said_past_capture};

#[test]
fn the_own_stages_tutorial_runs_outside_the_checkout() {
    let markdown = std::fs::read_to_string(repo().join("docs/tutorial-own-stages.md")).expect("the tutorial");
    let install = tempfile::tempdir().unwrap();
    let bin = install.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::copy(exe(), bin.join("twinray")).expect("installing twinray");
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    assert!(outside(dir) && outside(&bin) && std::fs::read_dir(dir).unwrap().next().is_none());
    // The installed binary first; nothing of the checkout or of cargo's test run.
    let path = std::env::var_os("PATH").unwrap_or_default();
    let kept = std::env::split_paths(&path).filter(|p| outside(p));
    let path = std::env::join_paths(std::iter::once(bin.clone()).chain(kept)).unwrap();
    let envs = [("PATH", path)];
    let which = run(dir, "command -v twinray", 0, &envs);
    assert_eq!(which.trim(), bin.join("twinray").to_string_lossy(), "the installed twinray runs the tutorial");
    let started = Instant::now();
    follow(&markdown, dir, &envs, |_, _| {});
    said_past_capture(&format!("tutorial (own stages): every step ran in {:.0} s", started.elapsed().as_secs_f64()));
}

fn outside(path: &Path) -> bool {
    !path.starts_with(repo())
}
