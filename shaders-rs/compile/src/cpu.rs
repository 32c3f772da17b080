//! The CPU side of a shader crate: its `shared/` library (the code its stages and the CPU
//! share, where its own shapes and materials are listed) built for the CPU inside a small
//! library twinray writes around it (`cpu/lib.rs`: the C functions of
//! `twinray_shared::custom::abi`), so that the host learns the crate's shapes, their f64
//! definitions and its materials from the crate itself. The library lands in the set's folder
//! as [`LIBRARY`]; a crate without `shared/` has none.

use crate::builder::nightly;
use crate::metadata::package;
use crate::process::{output_within, Finished};
use anyhow::{anyhow, bail, Context, Result};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Where a crate keeps the library its stages and the CPU share.
pub const SHARED_DIR: &str = "shared";
/// The CPU library's file in a built set's folder.
pub const LIBRARY: &str = "cpu.so";

const WRAPPER: &str = include_str!("../cpu/lib.rs");

/// Whether the crate in `dir` has a library of its own for the CPU to build.
pub fn has_shared(dir: &Path) -> bool {
    dir.join(SHARED_DIR).join("Cargo.toml").is_file()
}

/// Builds the CPU library of the crate in `dir` (which [`has_shared`]) into `out`/[`LIBRARY`],
/// under `timeout`; the compiler's errors are printed as cargo wrote them.
pub fn build(dir: &Path, out: &Path, timeout: Duration) -> Result<PathBuf> {
    let shared = std::path::absolute(dir.join(SHARED_DIR))?;
    let own = package(&shared)?;
    let name = own["name"].as_str().ok_or_else(|| anyhow!("{}: cargo names no package", shared.display()))?;
    let dependencies = own["dependencies"].as_array().cloned().unwrap_or_default();
    let contract = dependencies.iter().find(|d| d["name"] == "twinray-shared").and_then(|d| d["path"].as_str());
    let Some(contract) = contract else {
        bail!("{}: the library does not depend on twinray-shared by path, where its shapes' type is", shared.display());
    };
    let wrapper = std::path::absolute(dir.join("target/twinray/cpu"))?;
    std::fs::create_dir_all(wrapper.join("src"))?;
    let manifest = format!(
        "[package]\nname = \"twinray-cpu\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
         [lib]\ncrate-type = [\"cdylib\"]\n\n[dependencies]\nown = {{ package = {name:?}, path = {:?} }}\n\
         twinray-shared = {{ path = {contract:?} }}\n\n[workspace]\n\n[profile.release]\npanic = \"unwind\"\n",
        shared.display().to_string(),
    );
    write_if_changed(&wrapper.join("Cargo.toml"), manifest.as_bytes())?;
    write_if_changed(&wrapper.join("src/lib.rs"), wrapper_source(&shared).as_bytes())?;
    // The crate's own lock, so that the same versions are used without the network.
    let lock = wrapper.join("Cargo.lock");
    if !lock.exists() {
        if let Ok(bytes) = std::fs::read(dir.join("Cargo.lock")) {
            std::fs::write(&lock, bytes)?;
        }
    }
    let mut command = nightly("cargo");
    command.current_dir(&wrapper).args(["build", "--release", "--quiet", "--message-format", "short"]);
    let Finished { status, stderr, .. } = output_within(&mut command, timeout)?;
    match status {
        None => {
            bail!("{}: the CPU build did not finish within {} s and was stopped", shared.display(), timeout.as_secs())
        }
        Some(s) if !s.success() => {
            eprint!("{stderr}");
            bail!(
                "{}: the crate's shared library does not build for the CPU (the compiler's errors are above)",
                shared.display()
            )
        }
        Some(_) => {}
    }
    let built = wrapper.join("target/release/libtwinray_cpu.so");
    let to = out.join(LIBRARY);
    std::fs::copy(&built, &to).with_context(|| format!("copying {}", built.display()))?;
    Ok(to)
}

/// The wrapper around the library in `shared`: what a crate leaves out it does not need, so
/// a crate made before materials could be added lists none (no `MATERIALS`), and one whose hit
/// stages do not trace declares no `RECURSION_DEPTH` (1, twinray's own).
fn wrapper_source(shared: &Path) -> String {
    let lib = std::fs::read_to_string(shared.join("src/lib.rs")).unwrap_or_default();
    let mut source = WRAPPER.to_string();
    for (item, absent) in [("MATERIALS", "&[]"), ("RECURSION_DEPTH", "1")] {
        if !lib.contains(&format!("pub const {item}")) {
            source = source.replace(&format!("own::{item}"), absent);
        }
    }
    source
}

fn write_if_changed(path: &Path, bytes: &[u8]) -> Result<()> {
    if std::fs::read(path).ok().as_deref() != Some(bytes) {
        std::fs::write(path, bytes).with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}
