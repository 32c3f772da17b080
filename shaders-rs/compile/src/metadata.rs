//! `cargo metadata` of a shader crate, read with the pinned nightly's cargo: its packages and
//! their dependencies, for the contract a crate depends on and the library it shares.

use crate::builder::nightly;
use crate::process::{output_within, Finished};
use anyhow::{anyhow, bail, Context, Result};
use std::path::Path;
use std::time::Duration;

/// `cargo metadata` of the package in `dir`, alone (`no_deps`) or with its resolved graph.
pub(crate) fn metadata(dir: &Path, no_deps: bool) -> Result<serde_json::Value> {
    let mut command = nightly("cargo");
    command.args(["metadata", "--format-version", "1", "--manifest-path"]).arg(dir.join("Cargo.toml"));
    if no_deps {
        command.arg("--no-deps");
    }
    let Finished { status, stdout, stderr } = output_within(&mut command, Duration::from_secs(300))?;
    if !status.is_some_and(|s| s.success()) {
        eprint!("{stderr}");
        bail!("{}: cargo cannot read the crate (cargo's errors are above)", dir.display());
    }
    serde_json::from_str(&stdout).context("reading cargo metadata")
}

/// The package whose manifest is `dir/Cargo.toml`, as `cargo metadata --no-deps` lists it.
pub(crate) fn package(dir: &Path) -> Result<serde_json::Value> {
    let manifest = dir.join("Cargo.toml").canonicalize().with_context(|| format!("{}", dir.display()))?;
    let listed = metadata(dir, true)?;
    let packages = listed["packages"].as_array().cloned().unwrap_or_default();
    packages.into_iter().find(|p| p["manifest_path"].as_str().is_some_and(|m| Path::new(m) == manifest)).ok_or_else(
        || anyhow!("{}: a workspace without a package of its own: give the shader crate's folder", dir.display()),
    )
}
