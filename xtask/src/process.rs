//! Running external commands with their output passed through, and failing with the command
//! line when they fail.

use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// `$XDG_CACHE_HOME`, else `~/.cache`, as twinray, Mesa and the shader builder read it.
pub fn cache_home() -> PathBuf {
    std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir)
}

/// The repository root (xtask lives one level below it).
pub fn repo_root() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().map(PathBuf::from).unwrap_or(manifest)
}

pub use twinray_compile::{output, run};

/// Where cargo puts the builds of the workspace at `root`: `CARGO_TARGET_DIR`, or its `target/`.
pub fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| root.join("target"))
}

/// `cargo ARGS` in the repository root, with extra environment variables.
pub fn cargo(args: &[&str], env: &[(&str, &str)]) -> Result<()> {
    run(&mut cargo_command(args, env))
}

/// The command `cargo` runs.
pub fn cargo_command(args: &[&str], env: &[(&str, &str)]) -> Command {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut command = Command::new(cargo);
    command.args(args).current_dir(repo_root()).envs(env.iter().copied());
    command
}

/// `cargo xtask ARGS` as this very program, so that no cargo lock is taken to start it.
pub fn xtask_command(args: &[&str]) -> Result<Command> {
    let mut command = Command::new(std::env::current_exe()?);
    command.args(args).current_dir(repo_root());
    Ok(command)
}

/// A tool on PATH, run in the repository root.
pub fn run_tool(tool: &str, args: &[&str]) -> Result<()> {
    run(Command::new(tool).args(args).current_dir(repo_root()))
}

/// Runs one named CI step, printing its name and duration.
pub fn step(name: &str, body: impl FnOnce() -> Result<()>) -> Result<()> {
    println!("==> {name}");
    let start = Instant::now();
    let result = body().with_context(|| format!("CI step '{name}' failed"));
    let took = start.elapsed().as_secs_f64();
    println!("<== {name}: {} in {took:.1} s", if result.is_ok() { "ok" } else { "FAILED" });
    record(name, took);
    result
}

/// Each step's name and seconds, in the order they ended: what `cargo xtask ci` sums up.
static STEPS: std::sync::Mutex<Vec<(String, f64)>> = std::sync::Mutex::new(Vec::new());

fn record(name: &str, seconds: f64) {
    STEPS.lock().unwrap_or_else(|e| e.into_inner()).push((name.to_string(), seconds));
}

/// The steps run so far, each with its seconds.
pub fn steps() -> Vec<(String, f64)> {
    STEPS.lock().unwrap_or_else(|e| e.into_inner()).clone()
}

/// A CI step run by this same program in a child process beside the others, its output kept
/// in `target/ci-tests/` and shown, with its time, when it is waited for.
pub struct Background {
    name: String,
    log: PathBuf,
    /// The step's exit status and time, from a thread that waits for it.
    ended: std::thread::JoinHandle<std::io::Result<(std::process::ExitStatus, f64)>>,
}

impl Background {
    /// Starts `command` as step `name`.
    pub fn start(name: &str, mut command: Command) -> Result<Background> {
        let dir = repo_root().join("target/ci-tests");
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        let log = dir.join(format!("{}.log", name.replace(|c: char| !c.is_ascii_alphanumeric(), "-")));
        let file = std::fs::File::create(&log).with_context(|| format!("creating {}", log.display()))?;
        let start = Instant::now();
        let mut child = command
            .stdout(file.try_clone()?)
            .stderr(file)
            .spawn()
            .with_context(|| format!("starting step '{name}'"))?;
        let ended = std::thread::spawn(move || Ok((child.wait()?, start.elapsed().as_secs_f64())));
        println!("==> {name} (beside the next steps, output in {})", log.display());
        Ok(Background { name: name.to_string(), log, ended })
    }

    /// Waits for the step, prints its output and time, and fails if it failed.
    pub fn wait(self) -> Result<()> {
        let (status, took) = self.ended.join().map_err(|_| anyhow::anyhow!("waiting for step '{}'", self.name))??;
        println!("==> {} (output)\n{}", self.name, std::fs::read_to_string(&self.log).unwrap_or_default().trim_end());
        let verdict = if status.success() { "ok" } else { "FAILED" };
        println!("<== {}: {verdict} in {took:.1} s", self.name);
        record(&format!("{} (beside)", self.name), took);
        if !status.success() {
            anyhow::bail!("CI step '{}' failed with {status}", self.name);
        }
        Ok(())
    }
}
