//! `cargo xtask planted [NAMES...]`: the defects that tests made lighter must still catch.
//! Each `tests/planted/NAME.patch` breaks what one test exists to check; its first lines name
//! the test (`# test: ARGS`, the arguments of `cargo test` after `cargo test --release`) and
//! say why (`# why: ...`); `git apply` skips such lines before the diff. Each patch is applied
//! to a tree with no tracked change, its test run, and the patch reverted whatever happened;
//! the task fails unless every test ran and failed with its patch in. A patch's `# expect: TEXT`
//! lines, if it has any, are what the failing test must say: a failure without them is the
//! patch breaking something else (a build, another assertion), not a catch. Tests run with the
//! environment CI gives the binaries that share the cores (`suite::shared_envs`).

use crate::process::repo_root;
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// One planted defect: its patch and the `cargo test` arguments of the test that must fail.
struct Planted {
    name: String,
    patch: PathBuf,
    test: Vec<String>,
    /// Words the failing test's output must hold for the failure to be this defect's.
    expect: Vec<String>,
}

pub fn run(names: &[String]) -> Result<()> {
    let root = repo_root();
    let planted = read(&root.join("tests/planted"))?;
    let chosen: Vec<&Planted> = planted.iter().filter(|p| names.is_empty() || names.contains(&p.name)).collect();
    if chosen.is_empty() {
        bail!("no planted defect named {names:?} in tests/planted/");
    }
    let dirty = git(&root, &["status", "--porcelain", "--untracked-files=no"])?;
    if !dirty.trim().is_empty() {
        bail!(
            "tracked files have changes; commit or stash them first (a patch is applied and reverted here):\n{dirty}"
        );
    }
    let mut missed = Vec::new();
    for p in chosen {
        println!("==> {}: cargo test --release {}", p.name, p.test.join(" "));
        let caught = with_patch(&root, &p.patch, || test_fails(&root, &p.test, &p.expect))?;
        println!("<== {}: {}", p.name, if caught { "caught" } else { "NOT CAUGHT" });
        if !caught {
            missed.push(p.name.clone());
        }
    }
    if !missed.is_empty() {
        bail!("planted defects their tests did not catch: {}", missed.join(", "));
    }
    println!("planted: every defect was caught");
    Ok(())
}

/// Every patch of `dir`, by name, with the test its `# test:` line names.
fn read(dir: &Path) -> Result<Vec<Planted>> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
        let patch = entry?.path();
        if patch.extension().is_none_or(|e| e != "patch") {
            continue;
        }
        let text = std::fs::read_to_string(&patch).with_context(|| format!("reading {}", patch.display()))?;
        let Some(test) = text.lines().find_map(|l| l.strip_prefix("# test: ")) else {
            bail!("{}: no `# test: ARGS` line", patch.display());
        };
        let name = patch.file_stem().unwrap_or_default().to_string_lossy().into_owned();
        let test = test.split_whitespace().map(String::from).collect();
        let expect = text.lines().filter_map(|l| l.strip_prefix("# expect: ")).map(String::from).collect();
        out.push(Planted { name, test, expect, patch });
    }
    out.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(out)
}

/// Runs `body` with `patch` applied, reverting it afterwards even when `body` fails.
fn with_patch(root: &Path, patch: &Path, body: impl FnOnce() -> Result<bool>) -> Result<bool> {
    let patch = patch.to_string_lossy();
    git(root, &["apply", "--check", &patch]).with_context(|| format!("{patch} no longer applies"))?;
    git(root, &["apply", &patch])?;
    let result = body();
    git(root, &["apply", "-R", &patch]).with_context(|| format!("reverting {patch}: revert it by hand"))?;
    result
}

/// Whether the test ran and failed saying each of `expect` (a failure without those words is
/// not a catch; a build that fails is an error). It runs as CI runs the binaries that share
/// the cores (`suite::shared_envs`: the short warm-up floor), the lighter way.
fn test_fails(root: &Path, args: &[String], expect: &[String]) -> Result<bool> {
    let out = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .args(["test", "--release"])
        .args(args)
        .envs(crate::suite::shared_envs())
        .current_dir(root)
        .output()
        .context("running cargo test")?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    if stdout.contains("test result: FAILED") {
        let said = format!("{stdout}{}", String::from_utf8_lossy(&out.stderr));
        let missing = expect.iter().find(|e| !said.contains(e.as_str()));
        if let Some(missing) = missing {
            println!("the test failed without saying {missing:?}:\n{}", tail(&stdout, 20));
        }
        return Ok(missing.is_none());
    }
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        bail!("the test did not run to a verdict:\n{}", tail(&stderr, 20));
    }
    if !stdout.contains("test result: ok. ") || stdout.contains("test result: ok. 0 passed") {
        bail!("the test filter matched no test:\n{}", tail(&stdout, 10));
    }
    Ok(false)
}

fn tail(text: &str, lines: usize) -> String {
    let all: Vec<&str> = text.lines().collect();
    all[all.len().saturating_sub(lines)..].join("\n")
}

fn git(root: &Path, args: &[&str]) -> Result<String> {
    let out = Command::new("git").args(args).current_dir(root).output().context("running git")?;
    if !out.status.success() {
        bail!("git {}: {}", args.join(" "), String::from_utf8_lossy(&out.stderr).trim());
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_patchs_test_and_expected_words() {
        let dir = tempfile::tempdir().unwrap();
        let patch = "# test: -p twinray --test commands -- a::b\n# why: because\n# expect: hit mismatches\n# expect: PASS\ndiff --git a/x b/x\n";
        std::fs::write(dir.path().join("wrong-tie.patch"), patch).unwrap();
        std::fs::write(dir.path().join("notes.txt"), "# test: not a patch").unwrap();
        std::fs::write(dir.path().join("bare.patch"), "# test: -p x\ndiff\n").unwrap();
        let found = read(dir.path()).unwrap();
        let names: Vec<&str> = found.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["bare", "wrong-tie"]);
        assert!(found[0].expect.is_empty());
        assert_eq!(found[1].test, ["-p", "twinray", "--test", "commands", "--", "a::b"]);
        assert_eq!(found[1].expect, ["hit mismatches", "PASS"]);
        std::fs::write(dir.path().join("untested.patch"), "diff\n").unwrap();
        assert!(read(dir.path()).is_err(), "a patch without a `# test:` line is refused");
    }
}
