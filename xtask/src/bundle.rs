//! `cargo xtask bundle`: one folder that runs the whole bench on a Linux machine with an
//! NVIDIA GPU and no network: the release build (shaders inside), the Vulkan loader and the
//! GL dispatch libraries the NVIDIA Vulkan ICD loads (from Debian packages), SPIRV-Tools'
//! validator beside the binary (modules from disk pass it before a driver sees them), the
//! probe cases, and bench/nvidia-run.sh as run.sh.

use crate::process::{cargo, repo_root, run};
use anyhow::{bail, Context, Result};
use std::path::Path;
use std::process::Command;

/// The loader, and what NVIDIA's ICD (libGLX_nvidia) links against: without these the loader
/// finds no driver on a machine that has only the kernel driver and the ICD.
const PACKAGES: [&str; 7] = ["libvulkan1", "libglvnd0", "libglx0", "libegl1", "libopengl0", "libgl1", "libgles2"];
/// The package of `spirv-val`, which links only the C++ runtime.
const VALIDATOR: &str = "spirv-tools";

pub fn run_bundle(out: &Path) -> Result<()> {
    let root = repo_root();
    cargo(&["build", "--release", "-p", "twinray"], &[])?;
    if out.exists() {
        std::fs::remove_dir_all(out).with_context(|| format!("removing {}", out.display()))?;
    }
    for dir in ["bin", "lib", "probes"] {
        std::fs::create_dir_all(out.join(dir))?;
    }
    std::fs::copy(root.join("target/release/twinray"), out.join("bin/twinray"))?;
    std::fs::copy(root.join("bench/nvidia-run.sh"), out.join("run.sh"))?;
    run(Command::new("cp").arg("-r").arg(root.join("probes/stability")).arg(out.join("probes/")))?;
    libraries(out)?;
    run(Command::new("tar")
        .arg("czf")
        .arg(out.with_extension("tar.gz"))
        .arg("-C")
        .arg(out.parent().unwrap_or(out))
        .arg(out.file_name().context("bundle folder has no name")?))?;
    println!("bundle: {} (and {}.tar.gz); on the GPU machine: sh run.sh", out.display(), out.display());
    Ok(())
}

/// The shared libraries of `PACKAGES` into `out/lib`, and `spirv-val` into `out/bin`, downloaded
/// with apt-get and unpacked.
fn libraries(out: &Path) -> Result<()> {
    let lib = out.join("lib");
    let scratch = tempfile_dir()?;
    let status =
        Command::new("apt-get").arg("download").args(PACKAGES).arg(VALIDATOR).current_dir(&scratch).status()?;
    if !status.success() {
        bail!(
            "apt-get download {} {VALIDATOR} failed: the package lists may be missing (apt-get update)",
            PACKAGES.join(" ")
        );
    }
    for deb in std::fs::read_dir(&scratch)?.filter_map(|e| e.ok()).map(|e| e.path()) {
        if deb.extension().is_some_and(|e| e == "deb") {
            run(Command::new("dpkg-deb").arg("-x").arg(&deb).arg(scratch.join("root")))?;
        }
    }
    // -a keeps the soname links (libvulkan.so.1 -> libvulkan.so.1.3.x).
    let libs = scratch.join("root/usr/lib/x86_64-linux-gnu");
    let files: Vec<_> = std::fs::read_dir(&libs)?.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    run(Command::new("cp").arg("-a").args(&files).arg(&lib))?;
    std::fs::copy(scratch.join("root/usr/bin/spirv-val"), out.join("bin/spirv-val"))?;
    std::fs::remove_dir_all(&scratch)?;
    Ok(())
}

fn tempfile_dir() -> Result<std::path::PathBuf> {
    let dir = std::env::temp_dir().join(format!("twinray-bundle-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}
