//! Hostile stages (`tests/hostile/stages/`, cases in `tests/hostile/stages.json`): a user's
//! module that writes nothing or half the image, loops forever, reads a wild address, traces
//! with the wrong payload or past the recursion depth, returns NaN, reports t out of range,
//! reads out of bounds. Each is compiled here by glslang and handed to twinray from disk; each
//! must end within its deadline with the exit code and the words its case gives, and never
//! hang, panic or die silently. Then damaged copies of committed modules: each ends in a
//! verdict, a refusal or a one-line report, never in a silent crash or a hang.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use twinray_tests::cli::wait_within;
use twinray_tests::repo_root as repo;

/// Wall-clock limit of one run: the deadline cases wait 3 s of GPU time.
const TIME_LIMIT: Duration = Duration::from_secs(90);

#[derive(serde::Deserialize)]
struct Case {
    name: String,
    why: String,
    stage: String,
    args: Vec<String>,
    exit: Vec<i32>,
    expect: Vec<String>,
    #[serde(default)]
    refuse: Vec<String>,
    /// A file the run must not leave (nothing partial is written).
    #[serde(default)]
    no_output: Option<String>,
}

/// Compiles `file` (a stage of `tests/hostile/stages/`, or any GLSL stage) with the twinray
/// include path into `dir`.
fn compile(file: &Path, dir: &Path) -> PathBuf {
    let spv = dir.join(format!("{}.spv", file.file_name().unwrap().to_string_lossy()));
    let out = Command::new("glslangValidator")
        .args(["-V", "--target-env", "spirv1.4"])
        .arg(format!("-I{}", repo().join("shaders-glsl").display()))
        .arg("-o")
        .args([&spv, file])
        .output()
        .expect("glslangValidator (cargo xtask setup installs it)");
    assert!(out.status.success(), "{}: {}", file.display(), String::from_utf8_lossy(&out.stdout));
    spv
}

/// What one run did: exit code (`None`: killed by a signal), its output, its time.
struct Ran {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    took: Duration,
}

/// Runs twinray with `args` in `cwd`, killing it past `TIME_LIMIT`.
fn run(args: &[String], cwd: &Path) -> Result<Ran, String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_twinray"))
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = wait_within(&mut child, TIME_LIMIT)?;
    let read = |pipe: Option<&mut dyn std::io::Read>| {
        let mut text = String::new();
        if let Some(p) = pipe {
            p.read_to_string(&mut text).unwrap();
        }
        text
    };
    let stdout = read(child.stdout.as_mut().map(|p| p as &mut dyn std::io::Read));
    let stderr = read(child.stderr.as_mut().map(|p| p as &mut dyn std::io::Read));
    Ok(Ran { code: status.code(), stdout, stderr, took: start.elapsed() })
}

fn check(case: &Case, stages: &Path, scratch: &Path) -> Result<(), String> {
    let spv = compile(&repo().join("tests/hostile/stages").join(&case.stage), stages);
    let out = scratch.join(case.name.replace(|c: char| !c.is_ascii_alphanumeric(), "-"));
    std::fs::create_dir_all(&out).unwrap();
    let fill = |s: &str| {
        s.replace("{stage}", &spv.to_string_lossy())
            .replace("{out}", &out.to_string_lossy())
            .replace("{repo}", &repo().to_string_lossy())
    };
    let args: Vec<String> = case.args.iter().map(|a| fill(a)).collect();
    let cwd = tempfile::tempdir().unwrap();
    let ran = run(&args, cwd.path())?;
    let text = format!("{}{}", ran.stdout, ran.stderr);
    if text.contains("panicked") {
        return Err(format!("panicked: {text}"));
    }
    if !ran.code.is_some_and(|c| case.exit.contains(&c)) {
        return Err(format!("exit {:?}, not one of {:?}: {text}", ran.code, case.exit));
    }
    if ran.code.is_some_and(|c| c >= 2) && ran.stderr.trim().lines().count() != 1 {
        return Err(format!("not one line on stderr: {}", ran.stderr));
    }
    let missing: Vec<&String> = case.expect.iter().filter(|n| !text.contains(n.as_str())).collect();
    if !missing.is_empty() {
        return Err(format!("does not say {missing:?}: {text}"));
    }
    if let Some(said) = case.refuse.iter().find(|n| text.contains(n.as_str())) {
        return Err(format!("says {said:?}: {text}"));
    }
    if let Some(file) = case.no_output.as_deref().map(|f| PathBuf::from(fill(f))) {
        if file.exists() {
            return Err(format!("left {} behind", file.display()));
        }
    }
    let left: Vec<_> = std::fs::read_dir(cwd.path()).unwrap().collect();
    if !left.is_empty() {
        return Err(format!("left {left:?} in its working folder"));
    }
    eprintln!("{}: exit {:?} in {:.1} s", case.name, ran.code, ran.took.as_secs_f64());
    Ok(())
}

#[test]
fn every_hostile_stage_ends_with_its_exit_code_and_cause() {
    let text = std::fs::read_to_string(repo().join("tests/hostile/stages.json")).unwrap();
    let cases: Vec<Case> = serde_json::from_str(&text).unwrap();
    let (stages, scratch) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|c| check(c, stages.path(), scratch.path()).err().map(|e| format!("{} ({}): {e}", c.name, c.why)))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} hostile stages misbehaved:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// A small deterministic generator (xorshift64*), so the damaged modules are the same on
/// every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// `bytes` with 1 to 3 of its words (after the header) replaced: by a random word, or by a
/// small number (ids, operand counts and enum values are small, so damage stays plausible).
fn damage(bytes: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut out = bytes.to_vec();
    let words = out.len() / 4;
    for _ in 0..1 + rng.below(3) {
        let at = 5 + rng.below(words - 5);
        let word = if rng.below(2) == 0 { rng.next() as u32 } else { rng.below(64) as u32 };
        out[4 * at..4 * at + 4].copy_from_slice(&word.to_le_bytes());
    }
    out
}

/// How a run with a damaged module ended, or why that is not acceptable.
fn judge(ran: &Ran) -> Result<&'static str, String> {
    let line = ran.stderr.trim();
    let one_line = line.lines().count() == 1 && line.starts_with("error: ");
    if line.contains("panicked") {
        return Err(format!("panicked: {line}"));
    }
    match ran.code {
        None => Err(format!("killed by a signal with no report: {line}")),
        Some(0) => Ok("0: rendered"),
        Some(1) if ran.stdout.contains("FAIL: ") => Ok("1: rendered, outputs failed"),
        Some(1) if one_line && line.contains("creating the pipeline of") => Ok("1: failed at the driver, named"),
        Some(2) if one_line && line.contains("spirv-val") => Ok("2: refused by spirv-val"),
        Some(2) if one_line => Ok("2: refused by twinray's checks"),
        Some(3) if one_line => Ok("3: deadline or device lost, reported"),
        Some(4) if one_line && line.contains("crashed") => Ok("4: driver crash, reported"),
        Some(code) => Err(format!("exit {code}: {line}")),
    }
}

/// Damaged copies of four committed GLSL modules, each rendered in place of its original:
/// every run ends within the time limit, by an exit code (never by a signal that no handler
/// reported), with one line on stderr when it fails.
#[test]
fn damaged_modules_end_in_a_verdict_a_refusal_or_a_report() {
    let modules = ["sphere_intersection", "procedural_closest_hit", "miss", "raygen"];
    // TWINRAY_DAMAGED_PER_MODULE=50 repeats the sweep of 200.
    let per_module: usize = std::env::var("TWINRAY_DAMAGED_PER_MODULE").ok().and_then(|v| v.parse().ok()).unwrap_or(15);
    let dir = tempfile::tempdir().unwrap();
    let mut rng = Rng(0x7fa5_dead_2025);
    let mut tally = std::collections::BTreeMap::<String, usize>::new();
    let mut failures = Vec::new();
    for module in modules {
        let original = std::fs::read(repo().join(format!("spirv/glsl/{module}.spv"))).unwrap();
        for k in 0..per_module {
            let file = dir.path().join(format!("{module}-{k}.spv"));
            std::fs::write(&file, damage(&original, &mut rng)).unwrap();
            let args: Vec<String> = ["render", "sphere", "--width", "32", "--height", "24", "--gpu-timeout", "10"]
                .iter()
                .map(|s| s.to_string())
                .chain(["--shaders".into(), format!("glsl,{module}={}", file.display())])
                .chain(["--out".into(), dir.path().join("r.png").display().to_string()])
                .collect();
            let label = format!("{module} #{k}");
            match run(&args, dir.path()) {
                Err(e) => failures.push(format!("{label}: {e}")),
                Ok(ran) => match judge(&ran) {
                    Ok(how) => *tally.entry(how.to_string()).or_default() += 1,
                    Err(e) => failures.push(format!("{label}: {e}")),
                },
            }
        }
    }
    eprintln!("{} damaged modules: {tally:?}", modules.len() * per_module);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(tally.keys().any(|k| k.contains("spirv-val")), "the validator refuses some: {tally:?}");
}

/// Runs this test binary again as a child that does `role` (see `child_roles`): the exit
/// code and stderr of a process that a watchdog or the crash handler ended.
fn run_child(role: &str) -> (Option<i32>, String) {
    let out = Command::new(std::env::current_exe().unwrap())
        .args(["child_roles", "--exact", "--nocapture", "--test-threads", "1"])
        .env("TWINRAY_TEST_CHILD", role)
        .output()
        .unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// Not a test of its own: what `run_child` asks of the child process (nothing otherwise).
#[test]
fn child_roles() {
    use twinray_host::util::{activity, crash, watchdog};
    match std::env::var("TWINRAY_TEST_CHILD").as_deref() {
        Ok("stall") => {
            let _doing = activity::doing("a driver call that never returns");
            let _deadline = watchdog::arm(Duration::from_millis(50));
            std::thread::sleep(Duration::from_secs(30));
            std::process::exit(0);
        }
        Ok("crash") => {
            crash::report_crashes();
            let _doing = activity::doing("running a stage that faults");
            // SAFETY: raising a signal; the handler ends the process.
            unsafe { libc::raise(libc::SIGSEGV) };
            std::process::exit(0);
        }
        _ => {}
    }
}

/// A call that never returns under a watchdog ends the process at its deadline with one line
/// naming what was being done and exit code 3; a fatal signal with the crash report's line and
/// exit code 4 (the paths a hung or crashing driver takes, made deterministic).
#[test]
fn a_stalled_call_and_a_crash_end_in_one_line_and_their_codes() {
    let start = Instant::now();
    let (code, stderr) = run_child("stall");
    assert_eq!(code, Some(twinray_host::util::watchdog::EXIT_STALLED), "{stderr}");
    assert!(stderr.contains("error: a driver call that never returns did not finish in 0.05 s"), "{stderr}");
    assert!(start.elapsed() < Duration::from_secs(20), "the deadline ended it, not the sleep");
    let (code, stderr) = run_child("crash");
    assert_eq!(code, Some(twinray_host::util::crash::EXIT_CRASHED), "{stderr}");
    assert!(stderr.contains("error: twinray crashed (SIGSEGV) while running a stage that faults"), "{stderr}");
}
