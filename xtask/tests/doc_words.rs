//! No stale `cargo xtask` words in the docs (README.md, CONTRIBUTING.md, docs/*.md): every
//! task they name exists, and every flag they give it is in that task's `--help`. app/tests/doc_words.rs
//! checks the rest (links, paths, `twinray` commands, quoted code).

use std::process::Command;
use twinray_tests::docs::docs;
use twinray_tests::repo_root as repo;

fn help(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_xtask")).args(args).arg("--help").output().unwrap();
    assert!(out.status.success(), "xtask {args:?} --help: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn every_xtask_and_flag_the_docs_name_exists() {
    let top = help(&[]);
    let tasks: Vec<&str> = top
        .split("Commands:\n")
        .nth(1)
        .unwrap_or("")
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    let (mut stale, mut checked) = (Vec::new(), 0);
    for (name, text) in docs(&repo()) {
        for part in text.split("cargo xtask ").skip(1) {
            let end = part.find(['`', '|', ';', '#', ')', '\n']).unwrap_or(part.len());
            let words: Vec<&str> = part[..end].split_whitespace().collect();
            let Some(task) = words.first().map(|w| w.trim_end_matches([',', '.', ':'])) else { continue };
            checked += 1;
            if !tasks.contains(&task) {
                stale.push(format!("{name}: `cargo xtask {task}`: no such task"));
                continue;
            }
            let text = help(&[task]);
            // Flags after a `--` go to another command (watch passes them to compare).
            for flag in words.iter().take_while(|w| **w != "--").filter(|w| w.starts_with("--") && w.len() > 2) {
                let flag = flag.split(['=', '[']).next().unwrap_or(flag);
                if !text.contains(&format!("{flag} ")) && !text.contains(&format!("{flag}\n")) {
                    stale.push(format!("{name}: `cargo xtask {}`: {flag} is not in its --help", words.join(" ")));
                }
            }
        }
    }
    assert!(stale.is_empty(), "{}", stale.join("\n"));
    assert!(checked >= 20, "only {checked} `cargo xtask` words found: is the scan still right?");
}
