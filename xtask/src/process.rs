//! Running external commands with their output passed through, and failing with the command
//! line when they fail.

use anyhow::{Context, Result};
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

/// The repository root (xtask lives one level below it).
pub fn repo_root() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().map(PathBuf::from).unwrap_or(manifest)
}

pub use twinray_build::{output, run};

/// `cargo ARGS` in the repository root, with extra environment variables.
pub fn cargo(args: &[&str], env: &[(&str, &str)]) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut command = Command::new(cargo);
    command.args(args).current_dir(repo_root());
    for (k, v) in env {
        command.env(k, v);
    }
    run(&mut command)
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
    println!("<== {name}: {} in {:.1} s", if result.is_ok() { "ok" } else { "FAILED" }, start.elapsed().as_secs_f64());
    result
}
