//! `cargo xtask watch [SCENE]`: the edit loop. Builds the host once and both shader sets into
//! `target/watch/`, then on every save under `shaders-rs/` or `shaders-glsl/` rebuilds only the
//! set whose sources changed, runs `twinray compare` on the fresh modules from disk, and prints
//! the verdict with the time from the save to it. The compare runs in a process of its own,
//! under a GPU deadline: a save whose stage never returns, crashes the driver or fails
//! validation is a verdict line, and the next save is compared as usual.

use crate::process::{cargo, repo_root};
use anyhow::{Context, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant, SystemTime};
use twinray_compile::{build_set, exit_words, require_tools, sets_for, sources, Output, GENERATORS};
use twinray_shared::catalog::Language;

pub struct WatchArgs {
    pub scene: Option<String>,
    pub poll: Duration,
    /// Stop after this many rebuilds (tests); watch until interrupted when `None`.
    pub changes: Option<u32>,
    /// More `twinray compare` arguments, after the defaults (`--runs 1 --warmup 0 --placements
    /// 1`), which they override.
    pub compare_args: Vec<String>,
}

pub fn run(args: &WatchArgs) -> Result<()> {
    let root = repo_root();
    require_tools()?;
    println!("watch: building the host (release)");
    // With cargo's progress: minutes on a fresh machine.
    cargo(&["build", "--release", "-p", "twinray"], &[])?;
    let twinray = crate::process::target_dir(&root).join("release/twinray");
    let out = root.join("target/watch");
    let mut seen = snapshot(&root);
    for language in Language::ALL {
        rebuild(&root, &out, language)?;
    }
    compare(&twinray, &out, args)?;
    let watched: Vec<&str> = Language::ALL.into_iter().flat_map(sources).copied().collect();
    println!("watch: watching {} (Ctrl-C to stop)", watched.join(", "));
    let mut rebuilds = 0;
    while args.changes.is_none_or(|n| rebuilds < n) {
        std::thread::sleep(args.poll);
        let now = snapshot(&root);
        let changed = changed_files(&seen, &now);
        if changed.is_empty() {
            continue;
        }
        seen = now;
        rebuilds += 1;
        cycle(&root, &twinray, &out, args, &changed);
    }
    Ok(())
}

/// One save: rebuild what changed, compare, and say how long it took from the save.
fn cycle(root: &Path, twinray: &Path, out: &Path, args: &WatchArgs, changed: &[(PathBuf, SystemTime)]) {
    let saved = changed.iter().map(|(_, t)| *t).max().unwrap_or_else(SystemTime::now);
    let names: Vec<String> = changed.iter().map(|(p, _)| p.display().to_string()).collect();
    println!("\nwatch: changed {}", names.join(", "));
    if changed.iter().any(|(p, _)| GENERATORS.iter().any(|g| p.ends_with(g))) {
        println!("watch: a layout, binding, catalog or registry file changed: run `cargo xtask shaders` and restart");
    }
    let start = Instant::now();
    let mut built = Vec::new();
    for language in sets_for(changed.iter().map(|(p, _)| p.as_path())) {
        if let Err(e) = rebuild(root, out, language) {
            println!("watch: the {} set does not build: {e:#}", language.name());
            return;
        }
        built.push(language.name());
    }
    let rebuilt = start.elapsed();
    let compared = Instant::now();
    if let Err(e) = compare(twinray, out, args) {
        println!("watch: {e:#}");
    }
    let to_verdict = SystemTime::now().duration_since(saved).unwrap_or_default();
    println!(
        "watch: save to verdict {:.1} s (rebuilt {} in {:.1} s, compared in {:.1} s)",
        to_verdict.as_secs_f64(),
        built.join(" and "),
        rebuilt.as_secs_f64(),
        compared.elapsed().as_secs_f64()
    );
}

fn rebuild(root: &Path, out: &Path, language: Language) -> Result<()> {
    let start = Instant::now();
    build_set(root, language, &out.join(language.name()), Output::OnFailure)?;
    println!("watch: built the {} set in {:.1} s", language.name(), start.elapsed().as_secs_f64());
    Ok(())
}

/// GPU deadline of watch's compares unless the arguments after `--` give one: a stage that
/// never returns should cost a save seconds, not twinray's default of two minutes.
const WATCH_GPU_TIMEOUT: &str = "20";

/// `twinray compare` of the two fresh sets; its own output is the verdict. A failed parity
/// (exit code 1) is a verdict, and so is a stage that does not finish or a crash: each gets a
/// line, and the loop goes on.
fn compare(twinray: &Path, out: &Path, args: &WatchArgs) -> Result<()> {
    let mut command = Command::new(twinray);
    command.arg("compare");
    command.args(args.scene.as_deref());
    command.arg("--a").arg(out.join("rust")).arg("--b").arg(out.join("glsl"));
    command.arg("--out-dir").arg(out.join("compare")).args(["--runs", "1", "--warmup", "0", "--placements", "1"]);
    let timeout = match args.compare_args.iter().position(|a| a.starts_with("--gpu-timeout")) {
        Some(_) => None,
        None => Some(WATCH_GPU_TIMEOUT),
    };
    command.args(timeout.map(|t| format!("--gpu-timeout={t}")));
    command.args(&args.compare_args);
    // Its error lines go where its verdicts go, in order.
    use std::os::fd::AsFd;
    command.stderr(std::process::Stdio::from(std::io::stdout().as_fd().try_clone_to_owned()?));
    let mut child = command.spawn().with_context(|| format!("starting {}", twinray.display()))?;
    // twinray keeps its own deadline; this one only catches a twinray that cannot.
    let backstop = Duration::from_secs(600);
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break status;
        }
        if start.elapsed() > backstop {
            let _ = child.kill();
            let _ = child.wait();
            println!("watch: verdict: twinray compare still ran after {} s and was stopped", backstop.as_secs());
            return Ok(());
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    if args.compare_args.is_empty() {
        println!(
            "watch: GPU times above are one cold trace per set; for a ratio with its interval, add -- --runs 10 --warmup 2 --placements 6"
        );
    }
    if let Some(line) = exit_words(status) {
        println!("watch: verdict: {line}");
    }
    Ok(())
}

/// Modification time and size of every file of both sets' sources, by path from the root.
fn snapshot(root: &Path) -> BTreeMap<PathBuf, (SystemTime, u64)> {
    let mut files = BTreeMap::new();
    let mut stack: Vec<PathBuf> = Language::ALL.into_iter().flat_map(sources).map(|d| root.join(d)).collect();
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for entry in entries.flatten() {
            let path = entry.path();
            let Ok(meta) = entry.metadata() else { continue };
            if meta.is_dir() {
                stack.push(path);
            } else if let (Ok(modified), Ok(relative)) = (meta.modified(), path.strip_prefix(root)) {
                files.insert(relative.to_path_buf(), (modified, meta.len()));
            }
        }
    }
    files
}

/// Files added, changed or removed between two snapshots, with when (removed: now).
fn changed_files(
    before: &BTreeMap<PathBuf, (SystemTime, u64)>,
    after: &BTreeMap<PathBuf, (SystemTime, u64)>,
) -> Vec<(PathBuf, SystemTime)> {
    let mut changed: Vec<_> =
        after.iter().filter(|(p, v)| before.get(*p) != Some(v)).map(|(p, (t, _))| (p.clone(), *t)).collect();
    changed.extend(before.keys().filter(|p| !after.contains_key(*p)).map(|p| (p.clone(), SystemTime::now())));
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snapshots_see_edits_additions_and_removals() {
        let dir = std::env::temp_dir().join(format!("twinray-watch-test-{}", std::process::id()));
        let glsl = dir.join("shaders-glsl");
        std::fs::create_dir_all(&glsl).unwrap();
        std::fs::write(glsl.join("a.glsl"), "x").unwrap();
        let first = snapshot(&dir);
        assert!(changed_files(&first, &snapshot(&dir)).is_empty());
        std::fs::write(glsl.join("a.glsl"), "xy").unwrap();
        std::fs::write(glsl.join("b.glsl"), "z").unwrap();
        let second = snapshot(&dir);
        let names: Vec<_> = changed_files(&first, &second).into_iter().map(|(p, _)| p).collect();
        assert_eq!(names, [PathBuf::from("shaders-glsl/a.glsl"), PathBuf::from("shaders-glsl/b.glsl")]);
        std::fs::remove_file(glsl.join("b.glsl")).unwrap();
        let removed: Vec<_> = changed_files(&second, &snapshot(&dir)).into_iter().map(|(p, _)| p).collect();
        assert_eq!(removed, [PathBuf::from("shaders-glsl/b.glsl")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
