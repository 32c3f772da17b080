//! Comments and docs say why, not when: no figure or choice is dated by the sitting that made
//! it (an ordinal before "session") and no issue number stands as a reason ("issue 40",
//! "runs/issue53-...") in code or docs. The measurements keep their history in bench/reports,
//! whose folders are named by the question they answer and which the docs link by that name;
//! an upstream project's issue is cited as `owner/repo#N`.

use std::path::Path;
use twinray_tests::repo_root as repo;

const ORDINALS: &[&str] = &[
    "first",
    "second",
    "third",
    "fourth",
    "fifth",
    "sixth",
    "seventh",
    "eighth",
    "ninth",
    "tenth",
    "eleventh",
    "twelfth",
    "thirteenth",
    "fourteenth",
    "fifteenth",
    "sixteenth",
    "seventeenth",
    "eighteenth",
    "nineteenth",
    "twentieth",
];

/// What dates or numbers a line by its history, if anything.
fn dated(line: &str) -> Option<String> {
    let lower = line.to_ascii_lowercase();
    for (i, _) in lower.match_indices("issue") {
        let rest = &lower[i + 5..];
        let rest = rest.strip_prefix('s').unwrap_or(rest);
        let rest = rest.strip_prefix(' ').unwrap_or(rest);
        let rest = rest.strip_prefix('#').unwrap_or(rest);
        let before = lower[..i].chars().next_back();
        if rest.starts_with(|c: char| c.is_ascii_digit()) && !before.is_some_and(|c| c.is_ascii_alphanumeric()) {
            return Some(format!("an issue number: {:?}", &line[i..(i + 9).min(line.len())]));
        }
    }
    for word in ["session", "sitting"] {
        for (i, _) in lower.match_indices(word) {
            let before = lower[..i].trim_end();
            if let Some(ordinal) = ORDINALS.iter().find(|o| before.ends_with(*o)) {
                return Some(format!("dated by a {word}: \"{ordinal} {word}\""));
            }
            let after = lower[i + word.len()..].trim_start_matches('s').trim_start();
            if after.starts_with(|c: char| c.is_ascii_digit()) {
                return Some(format!("dated by a numbered {word}"));
            }
        }
    }
    None
}

/// Files of the repository that hold prose or code, outside the folders that keep history.
fn texts(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        let relative = path.strip_prefix(repo()).unwrap().to_string_lossy().replace('\\', "/");
        if path.is_dir() {
            let kept = ["bench/reports", "fuzz/corpus", "target"];
            if !name.starts_with('.') && !kept.contains(&relative.as_str()) && name != "target" {
                texts(&path, out);
            }
        } else if [
            ".rs", ".md", ".toml", ".glsl", ".sh", ".py", ".patch", ".rgen", ".rchit", ".rmiss", ".rint", ".rahit",
            ".rcall", ".comp", ".html", ".js", ".css", ".yml",
        ]
        .iter()
        .any(|e| name.ends_with(e))
            || name == "run"
        {
            out.push(path);
        }
    }
}

#[test]
fn nothing_is_dated_by_a_sitting_or_numbered_by_an_issue() {
    let mut files = Vec::new();
    texts(&repo(), &mut files);
    assert!(files.len() > 300, "only {} files found", files.len());
    let mut found = Vec::new();
    // This file names what it looks for.
    let own = repo().join("app/tests/history_words.rs");
    for file in files.iter().filter(|f| **f != own) {
        let Ok(text) = std::fs::read_to_string(file) else { continue };
        for (n, line) in text.lines().enumerate() {
            if let Some(what) = dated(line) {
                let relative = file.strip_prefix(repo()).unwrap().display();
                found.push(format!("{relative}:{}: {what}", n + 1));
            }
        }
    }
    assert!(found.is_empty(), "say why, not when (bench/reports keeps the history):\n{}", found.join("\n"));
}

#[test]
fn the_check_finds_what_it_is_for() {
    for bad in [
        "kept since issue 40",
        "(Issue 78 taught the mutator)",
        "runs/issue53-any-hit.tar.xz",
        concat!("measured in the fourteenth", " session"),
        "the seventeenth sitting",
        "sessions 4 to 18",
        "issues 11 and 22",
        "issue #12",
    ] {
        assert!(dated(bad).is_some(), "{bad}");
    }
    for good in ["KhronosGroup/Vulkan-Docs#2681", "a known issue", "tissue 4", "the session's runs", "issues"] {
        assert_eq!(dated(good), None, "{good}");
    }
}
