//! The hostile-input corpus (`tests/hostile/`): scene files, OBJ files, probe cases and
//! command lines, each written to break something (overflowing values, files that never end,
//! nesting that exhausts a parser, counts that would take hours). Every one must end with
//! exit code 2 and one line on stderr that names the file, field or flag; no panic, no hang
//! (each run has a time limit), no file left behind, and memory bounded (each run under a
//! 1 GiB address-space limit). `cases.json` lists them with why each is there.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;
use twinray_tests::cli::wait_within;
use twinray_tests::repo_root as repo;

/// Wall-clock limit of one run: parsing fails in milliseconds, a Vulkan start takes a second.
const TIME_LIMIT: Duration = Duration::from_secs(60);
/// Address-space limit of one run, in KiB (`ulimit -v`): 1 GiB, in which a lavapipe render fits.
const MEMORY_LIMIT_KIB: u64 = 1 << 20;

#[derive(serde::Deserialize)]
struct Case {
    name: String,
    why: String,
    args: Vec<String>,
    expect: Vec<String>,
    #[serde(default)]
    env: std::collections::BTreeMap<String, String>,
}

/// The corpus copied into a scratch folder, with what git cannot hold: FIFOs.
fn scratch_corpus() -> tempfile::TempDir {
    let scratch = tempfile::tempdir().unwrap();
    copy_dir(&repo().join("tests/hostile"), scratch.path());
    for fifo in ["scenes/fifo.obj", "probes/fifo.toml"] {
        let path = scratch.path().join(fifo);
        let made = Command::new("mkfifo").arg(&path).status().expect("mkfifo");
        assert!(made.success(), "mkfifo {}", path.display());
    }
    scratch
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

/// A folder references cannot be written into. Root ignores permission bits, so then a path
/// under /sys, where even root cannot create folders.
fn read_only_folder(scratch: &Path) -> PathBuf {
    let running_as_root = Command::new("id").arg("-u").output().is_ok_and(|o| o.stdout.starts_with(b"0\n"));
    if running_as_root {
        return PathBuf::from("/sys/twinray-cache");
    }
    let dir = scratch.join("read-only-cache");
    std::fs::create_dir(&dir).unwrap();
    let status = Command::new("chmod").arg("555").arg(&dir).status().unwrap();
    assert!(status.success());
    dir
}

/// Runs one case in an empty folder; `Err` says what it did wrong.
fn run(case: &Case, places: &[(&str, String)]) -> Result<(), String> {
    let cwd = tempfile::tempdir().unwrap();
    let fill = |s: &str| places.iter().fold(s.to_string(), |s, (key, value)| s.replace(key, value));
    let args: Vec<String> = case.args.iter().map(|a| fill(a)).collect();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {MEMORY_LIMIT_KIB}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_twinray"))
        .args(&args)
        .envs(&case.env)
        .current_dir(cwd.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let status = wait_within(&mut child, TIME_LIMIT)?;
    let mut stderr = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut stderr).unwrap();
    let stderr = stderr.trim();
    if stderr.contains("panicked") {
        return Err(format!("panicked: {stderr}"));
    }
    if status.code() != Some(2) {
        return Err(format!("exit {status}, not 2: {stderr}"));
    }
    if stderr.lines().count() != 1 {
        return Err(format!("{} lines on stderr, not one: {stderr}", stderr.lines().count()));
    }
    if stderr.len() > 2100 {
        return Err(format!("a {}-character error line", stderr.len()));
    }
    let missing: Vec<&String> = case.expect.iter().filter(|n| !stderr.contains(&fill(n))).collect();
    if !missing.is_empty() {
        return Err(format!("{stderr:?} does not mention {missing:?}"));
    }
    let left: Vec<_> = std::fs::read_dir(cwd.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    if !left.is_empty() {
        return Err(format!("left {left:?} behind"));
    }
    Ok(())
}

#[test]
fn every_hostile_input_ends_in_one_line_and_exit_code_2() {
    let text = std::fs::read_to_string(repo().join("tests/hostile/cases.json")).unwrap();
    let cases: Vec<Case> = serde_json::from_str(&text).unwrap();
    assert!(cases.len() >= 60, "the corpus has {} inputs, the issue asks for 60", cases.len());
    let scratch = scratch_corpus();
    let places = [
        ("{corpus}", scratch.path().display().to_string()),
        ("{repo}", repo().display().to_string()),
        ("{readonly}", read_only_folder(scratch.path()).display().to_string()),
    ];
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|case| run(case, &places).err().map(|e| format!("{} ({}): {e}", case.name, case.why)))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} hostile inputs misbehaved:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}
