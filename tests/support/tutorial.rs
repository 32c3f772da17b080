//! Following a tutorial as a reader would: every fenced block of its markdown, in order, is one of
//!
//! - ```` ```sh ````: commands, run with bash in the tutorial's folder; they must succeed;
//! - ```` ```text ````: right after a `sh` block, lines its output must contain (`...`
//!   stands for any text within a line; leading spaces do not count);
//! - ```` ```LANG file=PATH ````: the whole new text of PATH; with `replace="TEXT"` it
//!   replaces the first line containing TEXT, with `after="TEXT"` it goes after it.
//!
//! A block of any other kind fails the test, so nothing the reader is told to do is skipped.
//! `xtask/tests/tutorial.rs` follows docs/tutorial.md in a scratch copy of the repository;
//! `app/tests/own_stages_tutorial.rs` follows docs/tutorial-own-stages.md outside it.

use crate::docs::{fenced, Block};
use std::ffi::OsString;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

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

/// Runs `commands` with bash in `dir`, with `envs` set; they must succeed. Returns what they
/// printed, stdout then stderr. `line` is where they stand in the markdown, for the messages.
pub fn run(dir: &Path, commands: &str, line: usize, envs: &[(&str, OsString)]) -> String {
    let started = Instant::now();
    let out = Command::new("bash")
        .args(["-c", &format!("set -euo pipefail\n{commands}")])
        .current_dir(dir)
        .envs(envs.iter().map(|(k, v)| (k, v)))
        .output()
        .expect("running bash");
    let output = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "line {line}: {} failed:\n{output}", commands.trim());
    let first = commands.trim().lines().next().unwrap_or_default();
    said_past_capture(&format!("tutorial: line {line} took {:.0} s: {first}", started.elapsed().as_secs_f64()));
    output
}

/// `line` on the process's stderr, past the harness's capture: where a tutorial's time goes
/// stays readable in a passing run (`cargo xtask test` keeps it in `target/ci-tests/LABEL.err`).
pub fn said_past_capture(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Takes every block of `markdown` in order in `dir` (commands run with `envs`), calling
/// `after_command` with each command block and its output.
pub fn follow(markdown: &str, dir: &Path, envs: &[(&str, OsString)], mut after_command: impl FnMut(&Block, &str)) {
    let mut last_output: Option<String> = None;
    for block in fenced(markdown).0 {
        let words = words(&block.info);
        let get = |key: &str| words.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str());
        let language = words.first().map_or("", |(k, _)| k.as_str());
        if language == "sh" {
            let output = run(dir, &block.text, block.line, envs);
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
