//! The tutorial, docs/tutorial.md, is a test: in a scratch copy of the repository (made afresh
//! each run at a path kept between runs, `twinray_tests::scratch::kept_copy`) its blocks
//! are followed in order, as a reader would take them (`twinray_tests::tutorial` says how
//! each kind of block is taken), commands run in the copy's root.
//!
//! The copy builds in ~/.cache/twinray/scaffold-target/tutorial, kept between runs, with release
//! builds made incrementally (`twinray_tests::scratch::cargo_envs`); the first run starts from a
//! copy of the workspace's release build and of xtask's debug build (`twinray_tests::scratch`).
//!
//! The tutorial's first step is `cargo xtask new-shape`, so the same copy also checks what
//! new-shape promises (`twinray_tests::scaffold`): right after that step, the files it touched, its
//! registry line, its CPU tests and its refusal of a taken name; after the last step, `cargo
//! xtask watch` on the new scene.

use std::time::Instant;
use twinray_tests::repo_root as repo;
use twinray_tests::scaffold::{check_new_shape, files, watch_sees_an_edit_of_the_twin};
use twinray_tests::scratch::{cargo_envs, kept_copy, lock_scaffold_target};
use twinray_tests::tutorial::{follow, said_past_capture};

#[test]
fn the_tutorial_runs_as_written() {
    let markdown = std::fs::read_to_string(repo().join("docs/tutorial.md")).expect("docs/tutorial.md");
    let _only_user = lock_scaffold_target();
    let scratch = kept_copy();
    let dir = scratch.as_path();
    let before = files(dir);
    let started = Instant::now();
    let envs = cargo_envs();
    let mut scaffolded = None;
    follow(&markdown, dir, &envs, |block, output| {
        if let Some(name) = block.text.trim().strip_prefix("cargo xtask new-shape ") {
            check_new_shape(dir, name, &before, output);
            scaffolded = Some(name.to_string());
        }
    });
    said_past_capture(&format!("tutorial: every step ran in {:.0} s", started.elapsed().as_secs_f64()));
    let name = scaffolded.expect("the tutorial starts with `cargo xtask new-shape NAME`, alone in its block");
    let watched = Instant::now();
    watch_sees_an_edit_of_the_twin(dir, &name);
    said_past_capture(&format!("tutorial: watch saw the edit in {:.0} s", watched.elapsed().as_secs_f64()));
}
