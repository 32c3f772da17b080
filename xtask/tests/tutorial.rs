//! The tutorial, docs/tutorial.md, is a test: in a scratch copy of the repository its steps
//! run in order, as a reader would take them. Every fenced block is one of
//!
//! - ```` ```sh ````: commands, run with bash in the copy's root; they must succeed;
//! - ```` ```text ````: right after a `sh` block, lines its output must contain (`...`
//!   stands for any text within a line; leading spaces do not count);
//! - ```` ```LANG file=PATH ````: the whole new text of PATH; with `replace="TEXT"` it
//!   replaces the first line containing TEXT, with `after="TEXT"` it goes after it.
//!
//! A block of any other kind fails the test, so nothing the reader is told to do is skipped.
//! The copy builds in ~/.cache/twinray/scaffold-target/tutorial, kept between runs; the first
//! run starts from a copy of the workspace's release build and of xtask's debug build
//! (`twinray_tests::scratch`).
//!
//! The tutorial's first step is `cargo xtask new-shape`, so the same copy also checks what
//! new-shape promises (`twinray_tests::scaffold`): right after that step, the files it touched, its
//! registry line, its CPU tests and its refusal of a taken name; after the last step, `cargo
//! xtask watch` on the new scene.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;
use twinray_tests::docs::{fenced, Block};
use twinray_tests::repo_root as repo;
use twinray_tests::scaffold::{check_new_shape, files, watch_sees_an_edit_of_the_twin};
use twinray_tests::scratch::{copy_repo, lock_scaffold_target, scaffold_target};

/// The words of an info string, with `key="quoted text"` kept whole and unquoted.
fn words(info: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut rest = info.trim();
    while !rest.is_empty() {
        let end = rest.find([' ', '=']).unwrap_or(rest.len());
        let key = rest[..end].to_string();
        rest = &rest[end..];
        let value = if let Some(after) = rest.strip_prefix("=\"") {
            let close = after.find('"').expect("a closing quote in the info string");
            rest = &after[close + 1..];
            after[..close].to_string()
        } else if let Some(after) = rest.strip_prefix('=') {
            let end = after.find(' ').unwrap_or(after.len());
            rest = &after[end..];
            after[..end].to_string()
        } else {
            String::new()
        };
        out.push((key, value));
        rest = rest.trim_start();
    }
    out
}

/// Whether `pattern` (with `...` for any text) matches within some line of `output`.
fn said(output: &str, pattern: &str) -> bool {
    let pieces: Vec<&str> = pattern.split("...").map(str::trim).filter(|p| !p.is_empty()).collect();
    output.lines().any(|line| {
        let mut rest = line;
        pieces.iter().all(|piece| match rest.find(piece) {
            Some(i) => {
                rest = &rest[i + piece.len()..];
                true
            }
            None => false,
        })
    })
}

fn apply(dir: &Path, block: &Block, path: &str, how: Option<(&str, &str)>) {
    let file = dir.join(path);
    let text = match how {
        None => block.text.clone(),
        Some((edit, needle)) => {
            let old = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("line {}: {path}: {e}", block.line));
            let at = old.lines().position(|l| l.contains(needle));
            let at = at.unwrap_or_else(|| panic!("line {}: no line of {path} contains {needle:?}", block.line));
            let mut lines: Vec<String> = old.lines().map(str::to_string).collect();
            let new = block.text.lines().map(str::to_string);
            match edit {
                "replace" => drop(lines.splice(at..=at, new)),
                _ => drop(lines.splice(at + 1..at + 1, new)),
            }
            lines.join("\n") + "\n"
        }
    };
    std::fs::create_dir_all(file.parent().unwrap()).unwrap();
    std::fs::write(&file, text).unwrap();
}

/// Runs a `sh` block with bash in `dir`, with `envs` set.
fn run(dir: &Path, block: &Block, envs: &[(&str, OsString)]) -> String {
    let started = Instant::now();
    let out = Command::new("bash")
        .args(["-c", &format!("set -euo pipefail\n{}", block.text)])
        .current_dir(dir)
        .envs(envs.iter().map(|(k, v)| (k, v)))
        .output()
        .expect("running bash");
    let output = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "line {}: {} failed:\n{output}", block.line, block.text.trim());
    let first = block.text.trim().lines().next().unwrap_or_default();
    said_past_capture(&format!("tutorial: line {} took {:.0} s: {first}", block.line, started.elapsed().as_secs_f64()));
    output
}

/// `line` on the process's stderr, past the harness's capture: where the tutorial's time goes
/// stays readable in a passing run (`cargo xtask test` keeps it in
/// `target/ci-tests/xtask_tests_tutorial.rs.err`).
fn said_past_capture(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

#[test]
fn the_tutorial_runs_as_written() {
    let markdown = std::fs::read_to_string(repo().join("docs/tutorial.md")).expect("docs/tutorial.md");
    let _only_user = lock_scaffold_target();
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    copy_repo(dir);
    let before = files(dir);
    let started = Instant::now();
    let envs = [("CARGO_TARGET_DIR", scaffold_target().into_os_string())];
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

/// Takes every block of `markdown` in order in `dir` (commands run with `envs`), calling
/// `after_command` with each command block and its output.
fn follow(markdown: &str, dir: &Path, envs: &[(&str, OsString)], mut after_command: impl FnMut(&Block, &str)) {
    let mut last_output: Option<String> = None;
    for block in fenced(markdown).0 {
        let words = words(&block.info);
        let get = |key: &str| words.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str());
        let language = words.first().map_or("", |(k, _)| k.as_str());
        if language == "sh" {
            let output = run(dir, &block, envs);
            after_command(&block, &output);
            last_output = Some(output);
        } else if language == "text" {
            let output =
                last_output.take().unwrap_or_else(|| panic!("line {}: output quoted after no command", block.line));
            for pattern in block.text.lines().filter(|l| !l.trim().is_empty()) {
                assert!(
                    said(&output, pattern),
                    "line {}: the command did not print {pattern:?}:\n{output}",
                    block.line
                );
            }
        } else if let Some(path) = get("file") {
            let how = get("replace").map(|t| ("replace", t)).or_else(|| get("after").map(|t| ("after", t)));
            apply(dir, &block, path, how);
            last_output = None;
        } else {
            panic!("line {}: a ```{} block is neither a command, its output, nor a file", block.line, block.info);
        }
    }
}

/// `cargo install --path host` into `root`, building in the scaffold target (seeded from the
/// tests' own release build, kept between runs), as a user installs twinray.
fn install_twinray(root: &Path) -> PathBuf {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let started = Instant::now();
    let out = Command::new(cargo)
        .args(["install", "--locked", "--offline", "--path"])
        .arg(repo().join("host"))
        .arg("--root")
        .arg(root)
        .arg("--target-dir")
        .arg(scaffold_target().join("install"))
        .env_remove("RUSTC_WORKSPACE_WRAPPER")
        .output()
        .expect("running cargo install");
    let said = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "cargo install --path host failed:\n{said}");
    said_past_capture(&format!("tutorial: cargo install --path host took {:.0} s", started.elapsed().as_secs_f64()));
    root.join("bin")
}

/// docs/tutorial-own-stages.md, in an empty folder outside the checkout, with only the
/// installed `twinray` (and rustup's toolchains) to run: what a user without a checkout has.
#[test]
fn the_own_stages_tutorial_runs_outside_the_checkout() {
    let markdown = std::fs::read_to_string(repo().join("docs/tutorial-own-stages.md")).expect("the tutorial");
    let _only_user = lock_scaffold_target();
    let install = tempfile::tempdir().unwrap();
    let bin = install_twinray(install.path());
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    assert!(!dir.starts_with(repo()) && std::fs::read_dir(dir).unwrap().next().is_none());
    // The installed binary first; nothing of the checkout or of cargo's test run.
    let path = std::env::var_os("PATH").unwrap_or_default();
    let kept = std::env::split_paths(&path).filter(|p| !p.starts_with(repo()));
    let path = std::env::join_paths(std::iter::once(bin.clone()).chain(kept)).unwrap();
    let envs = [("PATH", path)];
    let which = run(dir, &Block { info: "sh".into(), text: "command -v twinray".into(), line: 0 }, &envs);
    assert_eq!(which.trim(), bin.join("twinray").to_string_lossy(), "the installed twinray runs the tutorial");
    let started = Instant::now();
    follow(&markdown, dir, &envs, |_, _| {});
    said_past_capture(&format!("tutorial (own stages): every step ran in {:.0} s", started.elapsed().as_secs_f64()));
}

#[test]
fn patterns_match_within_a_line_in_order() {
    assert!(said("  a = rust  GPU 5 ms\n", "a = rust ..."));
    assert!(said("scene capsule 400x300 on llvmpipe\n", "scene capsule ... on ..."));
    assert!(!said("scene capsule\n400x300\n", "scene ... 400x300"));
    assert!(!said("on llvmpipe scene capsule\n", "scene capsule ... on"));
    assert_eq!(
        words(r#"rust file=a/b.rs after="pub const X: &[T] = &[""#),
        [
            ("rust".into(), "".into()),
            ("file".into(), "a/b.rs".into()),
            ("after".into(), "pub const X: &[T] = &[".into())
        ]
    );
}
