//! Running the build's tools, failing with the command line and what the tool said.

use anyhow::{bail, Context, Result};
use std::process::Command;

/// Runs `command` with its output passed through, failing with its command line and exit
/// status if it fails.
pub fn run(command: &mut Command) -> Result<()> {
    let line = format!("{command:?}");
    let status = command.status().with_context(|| format!("starting {line}"))?;
    if !status.success() {
        bail!("{line} failed with {status}");
    }
    Ok(())
}

/// Runs `command` and returns its standard output; when it fails, the error holds both streams.
pub fn output(command: &mut Command) -> Result<String> {
    let line = format!("{command:?}");
    let out = command.output().with_context(|| format!("starting {line}"))?;
    if !out.status.success() {
        // Both streams: glslang reports errors on stdout, cargo and rustc on stderr.
        let said =
            format!("{}\n{}", String::from_utf8_lossy(&out.stdout).trim(), String::from_utf8_lossy(&out.stderr).trim());
        bail!("{line} failed with {}:\n{}", out.status, said.trim());
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Whether `tool` can be started.
pub fn have(tool: &str) -> bool {
    Command::new(tool).arg("--version").output().is_ok_and(|o| o.status.success())
}
