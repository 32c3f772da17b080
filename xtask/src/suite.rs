//! `cargo xtask test`: the tests `cargo test --workspace --release` runs, built once and then run
//! several test binaries at a time. On lavapipe most of a test's time is LLVM compiling a
//! pipeline on one core, so one binary at a time leaves the other cores idle; binaries are
//! separate processes, so running them side by side changes nothing a test can see but time,
//! and the GPU times it measures: the binaries that assert on those (`ALONE`) run first, alone.
//! When a binary ends, its harness's report (its stdout: `running N tests`, a line per test,
//! failures, `test result:`) is printed whole, as `cargo test` prints it, so a reader or a tool
//! that counts tests sees every one. Its stderr (what child processes and C libraries write past
//! the harness's capture) goes to `target/ci-tests/LABEL.err`, and its tail is shown when the
//! binary fails. The times of the last run (`target/ci-tests/times.tsv`) order the next one,
//! longest first.

use crate::process::repo_root;
use anyhow::{bail, Context, Result};
use std::collections::{BTreeMap, VecDeque};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// One test executable, named by its source file relative to the repository root.
#[derive(Clone, Debug)]
pub struct Binary {
    pub label: String,
    path: PathBuf,
    package_dir: PathBuf,
}

/// The slowest binaries of a CI run on 2 cores (docs/testing.md), slowest first, so that a
/// first run, with no times of its own yet (a fresh clone's), starts them first and does not
/// end on one of them alone.
const SLOW_FIRST: [&str; 6] = [
    "xtask/tests/tutorial.rs",
    "tests/integration.rs",
    "app/tests/commands.rs",
    "app/tests/bench.rs",
    "app/tests/view.rs",
    "app/tests/hostile_stages.rs",
];

/// Binaries that time GPU work and assert on the ratios: they run alone, before the rest. Beside
/// another binary, lavapipe's threads share the cores with it, and in one CI run the planted
/// twice-the-work stage of tests/timing.rs measured 0.33 of the time, not about 0.5.
const ALONE: [&str; 1] = ["tests/timing.rs"];

/// The warm-up floor of the binaries that run side by side (`TWINRAY_MIN_WARM_MS`): 20 ms of
/// GPU time before each place's timed traces, not the 1000 ms a user's commands take. The floor
/// makes a time the GPU's at its working clocks (docs/measuring.md); beside another binary on
/// lavapipe no time is that, and none of these binaries judges a time (those that do are
/// `ALONE`, and keep the floor). At 1000 ms the floor was most of their work on lavapipe:
/// `app/tests/bench.rs` took 56 s alone, 10 s at 20 ms. A floor set by the caller is kept.
const SHARED_WARM_MS: (&str, &str) = ("TWINRAY_MIN_WARM_MS", "20");

/// clippy's lints, warnings denied, on every target of the workspace, from the one release build
/// the tests need: `cargo clippy` is `cargo check` with clippy-driver as the workspace's rustc
/// wrapper and its arguments in CLIPPY_ARGS, so the same wrapper on the test build lints the
/// same targets (the workspace has no benches or examples) without building the workspace twice.
pub const CLIPPY: [(&str, &str); 2] =
    [("RUSTC_WORKSPACE_WRAPPER", "clippy-driver"), ("CLIPPY_ARGS", "-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__")];

/// Builds every test binary of the workspace (release, as CI tests), linted by clippy, and
/// lists them.
pub fn build() -> Result<Vec<Binary>> {
    let root = repo_root();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut child = Command::new(cargo)
        .args(["test", "--workspace", "--release", "--no-run", "--message-format=json-render-diagnostics"])
        .envs(CLIPPY)
        .current_dir(&root)
        .stdout(Stdio::piped())
        .spawn()
        .context("starting cargo test --no-run")?;
    let mut binaries = Vec::new();
    for line in BufReader::new(child.stdout.take().context("cargo's piped stdout")?).lines() {
        if let Some(binary) = test_binary(&root, &line?) {
            binaries.push(binary);
        }
    }
    if !child.wait()?.success() {
        bail!("cargo test --workspace --release --no-run failed");
    }
    Ok(binaries)
}

/// The test executable a line of cargo's JSON messages announces, if it announces one.
fn test_binary(root: &Path, line: &str) -> Option<Binary> {
    let message: serde_json::Value = serde_json::from_str(line).ok()?;
    let is_test = message["reason"] == "compiler-artifact" && message["profile"]["test"] == true;
    let path = PathBuf::from(message["executable"].as_str().filter(|_| is_test)?);
    let source = Path::new(message["target"]["src_path"].as_str()?);
    let package_dir = Path::new(message["manifest_path"].as_str()?).parent()?.to_path_buf();
    let label = source.strip_prefix(root).unwrap_or(source).to_string_lossy().into_owned();
    Some(Binary { label, path, package_dir })
}

/// What one binary did.
struct Outcome {
    label: String,
    passed: bool,
    took: Duration,
    /// The harness's report: its stdout.
    report: String,
}

impl Outcome {
    fn summary(&self) -> &str {
        self.report.lines().rfind(|l| l.starts_with("test result:")).unwrap_or("no test result")
    }
}

/// Runs `binaries` (those whose label contains one of `only`, or all), `jobs` at a time, and
/// fails naming every binary that failed. `after_alone` runs once the binaries that assert on
/// GPU timings are done: work that may share the cores with the rest (CI's rustdoc).
pub fn run(binaries: Vec<Binary>, jobs: usize, only: &[String], after_alone: impl FnOnce()) -> Result<()> {
    let logs = repo_root().join("target/ci-tests");
    std::fs::create_dir_all(&logs).with_context(|| format!("creating {}", logs.display()))?;
    let times = read_times(&logs.join("times.tsv"));
    let mut queue: Vec<Binary> =
        binaries.into_iter().filter(|b| only.is_empty() || only.iter().any(|o| b.label.contains(o.as_str()))).collect();
    if queue.is_empty() {
        bail!("no test binary's source matches {only:?}");
    }
    queue.sort_by(|a, b| expected(&times, &b.label).total_cmp(&expected(&times, &a.label)));
    let total = queue.len();
    let (alone, shared): (Vec<_>, Vec<_>) = queue.into_iter().partition(|b| ALONE.contains(&b.label.as_str()));
    println!(
        "tests: {total} binaries: {} alone first (they assert on GPU timings), then {jobs} at a time (logs in {})",
        alone.len(),
        logs.display()
    );
    let outcomes = Mutex::new(Vec::new());
    let started = Instant::now();
    run_pool(alone, (1, &[]), total, &logs, &outcomes);
    after_alone();
    run_pool(shared, (jobs, &shared_envs()), total, &logs, &outcomes);
    summarize(&outcomes.into_inner().unwrap(), started.elapsed(), &logs)
}

/// What the binaries that run side by side run with: [`SHARED_WARM_MS`], unless the caller set
/// a floor of their own.
pub fn shared_envs() -> Vec<(&'static str, &'static str)> {
    std::env::var_os(SHARED_WARM_MS.0).is_none().then_some(SHARED_WARM_MS).into_iter().collect()
}

/// `cargo xtask test --quick`: what catches most slips in a minute or so warm, one step after
/// another, each timed: the libraries' unit tests, the parity of both sets and three mixes on
/// the default scene, and both sets rebuilt and compared with the committed SPIR-V. Not a
/// substitute for `cargo xtask ci` before a commit lands.
pub fn quick() -> Result<()> {
    let started = Instant::now();
    crate::process::step("unit tests", || {
        crate::process::cargo(
            &["test", "--release", "-p", "twinray-shared", "-p", "twinray-host", "-p", "twinray", "--lib"],
            &[],
        )
    })?;
    crate::process::step("parity on the default scene", || {
        crate::process::cargo(
            &["test", "--release", "-p", "twinray-tests", "--test", "integration", "--", "parity::"],
            &[],
        )
    })?;
    crate::process::step("shaders --check", || crate::shaders::run(true))?;
    println!(
        "test --quick: every step passed in {:.0} s (the whole suite: cargo xtask ci)",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Runs `binaries`, `jobs` at a time with `envs` set, reporting each (of `total`) as it ends
/// into `outcomes`.
fn run_pool(
    binaries: Vec<Binary>,
    (jobs, envs): (usize, &[(&str, &str)]),
    total: usize,
    logs: &Path,
    outcomes: &Mutex<Vec<Outcome>>,
) {
    let queue = Mutex::new(VecDeque::from(binaries));
    std::thread::scope(|scope| {
        for _ in 0..jobs.max(1) {
            scope.spawn(|| {
                loop {
                    // Its own statement: a guard in the `while let` would be held through the run.
                    let Some(binary) = queue.lock().unwrap().pop_front() else { break };
                    let outcome = run_one(&binary, logs, envs);
                    let mut all = outcomes.lock().unwrap();
                    report(&outcome, all.len() + 1, total, logs);
                    all.push(outcome);
                }
            });
        }
    });
}

/// How long a binary took last time, or a rank for the slow ones when there is no last time.
fn expected(times: &BTreeMap<String, f64>, label: &str) -> f64 {
    let rank = SLOW_FIRST.iter().position(|s| *s == label).map_or(0.0, |i| (SLOW_FIRST.len() - i) as f64);
    times.get(label).copied().unwrap_or(rank)
}

fn run_one(binary: &Binary, logs: &Path, envs: &[(&str, &str)]) -> Outcome {
    let (out, err) = log_paths(logs, &binary.label);
    let start = Instant::now();
    let passed = std::fs::File::create(&out)
        .and_then(|stdout| {
            let stderr = std::fs::File::create(&err)?;
            // What cargo test sets for a test binary at run time.
            Command::new(&binary.path)
                .current_dir(&binary.package_dir)
                .env("CARGO_MANIFEST_DIR", &binary.package_dir)
                .env("CARGO", std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
                .envs(envs.iter().copied())
                .stdout(stdout)
                .stderr(stderr)
                .status()
        })
        .is_ok_and(|status| status.success());
    let report = std::fs::read_to_string(&out).unwrap_or_default();
    Outcome { label: binary.label.clone(), passed, took: start.elapsed(), report }
}

/// Where a binary's stdout and stderr go.
fn log_paths(logs: &Path, label: &str) -> (PathBuf, PathBuf) {
    let stem = label.replace('/', "_");
    (logs.join(format!("{stem}.out")), logs.join(format!("{stem}.err")))
}

fn report(outcome: &Outcome, done: usize, total: usize, logs: &Path) {
    let verdict = if outcome.passed { "ok" } else { "FAILED" };
    println!("     Running {} [{done}/{total}]", outcome.label);
    println!("{}", outcome.report.trim_end());
    println!("[{done}/{total}] {}: {verdict} in {:.1} s", outcome.label, outcome.took.as_secs_f64());
    if !outcome.passed {
        let err = log_paths(logs, &outcome.label).1;
        let text = std::fs::read_to_string(&err).unwrap_or_default();
        let lines: Vec<&str> = text.lines().collect();
        let tail = &lines[lines.len().saturating_sub(200)..];
        println!(
            "---- {} stderr (last {} lines of {}) ----\n{}",
            outcome.label,
            tail.len(),
            err.display(),
            tail.join("\n")
        );
    }
}

/// The counts of every binary's `test result:` line, added up.
fn counts(outcomes: &[Outcome]) -> [u64; 3] {
    let mut sum = [0; 3];
    for line in outcomes.iter().map(Outcome::summary) {
        for (i, word) in ["passed", "failed", "ignored"].iter().enumerate() {
            let before = line.split(&format!(" {word}")).next().unwrap_or("");
            sum[i] += before.rsplit([' ', '.']).next().and_then(|n| n.parse::<u64>().ok()).unwrap_or(0);
        }
    }
    sum
}

fn summarize(outcomes: &[Outcome], wall: Duration, logs: &Path) -> Result<()> {
    let mut sorted: Vec<&Outcome> = outcomes.iter().collect();
    sorted.sort_by_key(|o| std::cmp::Reverse(o.took));
    println!("tests: time per binary, longest first");
    for o in &sorted {
        println!("  {:>7.1} s  {}{}", o.took.as_secs_f64(), o.label, if o.passed { "" } else { "  FAILED" });
    }
    let sum: f64 = outcomes.iter().map(|o| o.took.as_secs_f64()).sum();
    println!("tests: {sum:.0} s of binaries ran in {:.0} s", wall.as_secs_f64());
    let [passed, failed, ignored] = counts(outcomes);
    println!("tests: {passed} passed, {failed} failed, {ignored} ignored in {} binaries", outcomes.len());
    let times: String = outcomes.iter().map(|o| format!("{}\t{:.1}\n", o.label, o.took.as_secs_f64())).collect();
    let _ = std::fs::write(logs.join("times.tsv"), times); // only orders the next run
    let failed: Vec<&str> = sorted.iter().filter(|o| !o.passed).map(|o| o.label.as_str()).collect();
    if !failed.is_empty() {
        bail!("{} of {} test binaries failed: {}", failed.len(), outcomes.len(), failed.join(", "));
    }
    Ok(())
}

fn read_times(path: &Path) -> BTreeMap<String, f64> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.lines()
        .filter_map(|l| l.split_once('\t'))
        .filter_map(|(label, secs)| Some((label.to_string(), secs.parse().ok()?)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_test_binary_from_cargos_messages_and_nothing_else() {
        let root = Path::new("/r");
        let test = r#"{"reason":"compiler-artifact","manifest_path":"/r/host/Cargo.toml","target":{"src_path":"/r/app/tests/cli.rs"},"profile":{"test":true},"executable":"/r/target/release/deps/cli-1"}"#;
        let binary = test_binary(root, test).unwrap();
        assert_eq!(binary.label, "app/tests/cli.rs");
        assert_eq!(binary.path, Path::new("/r/target/release/deps/cli-1"));
        assert_eq!(binary.package_dir, Path::new("/r/host"));
        let program = test.replace(r#""test":true"#, r#""test":false"#);
        assert!(test_binary(root, &program).is_none(), "a program built for the tests is not a test");
        let library = test.replace(r#""/r/target/release/deps/cli-1""#, "null");
        assert!(test_binary(root, &library).is_none());
        assert!(test_binary(root, r#"{"reason":"build-finished","success":true}"#).is_none());
        assert!(test_binary(root, "Compiling twinray").is_none());
    }

    #[test]
    fn orders_by_last_times_and_by_rank_without_them() {
        let times = BTreeMap::from([("a.rs".to_string(), 40.0)]);
        assert_eq!(expected(&times, "a.rs"), 40.0);
        assert!(expected(&times, SLOW_FIRST[0]) > expected(&times, SLOW_FIRST[1]));
        assert_eq!(expected(&times, "unknown.rs"), 0.0);
    }

    #[test]
    fn adds_up_the_harness_counts() {
        let outcome =
            |report: &str| Outcome { label: "a.rs".into(), passed: true, took: Duration::ZERO, report: report.into() };
        let ok = "running 3 tests\ntest a ... ok\n\ntest result: ok. 3 passed; 0 failed; 1 ignored; 0 measured; 0 filtered out; finished in 0.01s\n";
        let bad = "test result: FAILED. 2 passed; 1 failed; 0 ignored; 0 measured; 0 filtered out; finished in 1.00s";
        assert_eq!(counts(&[outcome(ok), outcome(bad), outcome("no harness here")]), [5, 1, 1]);
        assert_eq!(outcome("").summary(), "no test result");
    }
}
