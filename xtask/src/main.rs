//! `cargo xtask <task>`: set-up, shader builds, golden images, the demo and CI.

mod bundle;
mod process;
mod setup;
mod shaders;

use anyhow::Result;
use clap::{Parser, Subcommand};
use process::{cargo, repo_root};
use setup::Scope;

#[derive(Parser)]
#[command(name = "cargo xtask", about = "twinray's build tasks")]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

#[derive(Subcommand)]
enum Task {
    /// Install what is missing (idempotent): the pinned nightly for rust-gpu, and, as root with
    /// apt, Mesa lavapipe, glslang, SPIRV-Tools and the validation layer. Otherwise prints the
    /// commands to run.
    Setup {
        /// Only the Vulkan loader and driver (what rendering needs), not the shader toolchain.
        #[arg(long)]
        vulkan_only: bool,
    },
    /// Build both shader sets into spirv/, validate every module and check its entry points.
    Shaders {
        /// Build into a scratch folder and fail if a committed module is stale.
        #[arg(long)]
        check: bool,
    },
    /// Re-render the golden images of tests/golden/ from the current shaders.
    Golden,
    /// Render the default scene with both shader sets and print the comparison.
    Demo,
    /// What CI runs: setup, fmt check, clippy (warnings denied), shaders --check, all tests.
    Ci,
    /// One folder (and .tar.gz) that runs the whole bench on an NVIDIA machine without
    /// network: the release build, the Vulkan loader and GL dispatch libraries, run.sh.
    Bundle {
        /// Where to put it.
        #[arg(long, default_value = "target/twinray-bench")]
        out: std::path::PathBuf,
    },
}

fn main() -> Result<()> {
    match Cli::parse().task {
        Task::Setup { vulkan_only } => setup::run(if vulkan_only { Scope::Vulkan } else { Scope::Full }),
        Task::Shaders { check } => shaders::run(check),
        Task::Golden => golden(),
        Task::Demo => demo(),
        Task::Ci => ci(),
        Task::Bundle { out } => bundle::run_bundle(&repo_root().join(out)),
    }
}

fn golden() -> Result<()> {
    cargo(&["test", "--release", "-p", "twinray-tests", "--test", "golden"], &[("TWINRAY_REFRESH_GOLDEN", "1")])?;
    println!("golden images rewritten in tests/golden/; review them with git diff before committing");
    Ok(())
}

fn demo() -> Result<()> {
    setup::run(Scope::Vulkan)?;
    let out = repo_root().join("target/demo");
    let out = out.to_string_lossy();
    cargo(&["run", "--release", "--quiet", "-p", "twinray", "--", "compare", "--out-dir", &out], &[])
}

fn ci() -> Result<()> {
    setup::run(Scope::Full)?;
    process::step("rustfmt", || {
        cargo(&["fmt", "--all", "--", "--check"], &[])?;
        process::run_tool(
            "rustfmt",
            &["--check", "--edition", "2021", "shaders-rs/shaders/src/lib.rs", "shaders-rs/builder/src/main.rs"],
        )
    })?;
    process::step("clippy", || cargo(&["clippy", "--workspace", "--all-targets", "--", "-D", "warnings"], &[]))?;
    process::step("shaders --check", || shaders::run(true))?;
    process::step("tests", || cargo(&["test", "--workspace", "--release"], &[]))
}
