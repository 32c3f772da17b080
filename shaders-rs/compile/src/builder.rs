//! The rust-gpu builder (`shaders-rs/builder`) and the toolchain it needs: the pinned nightly
//! installed with rustup when missing, and the builder compiled once per machine into the cache
//! (`builder_target`), where rustc_codegen_spirv, the backend, is built once for every crate
//! and checkout on the machine.

use crate::process::{output, run};
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// rustc_codegen_spirv 0.11.0 builds only with this nightly.
pub const NIGHTLY: &str = "nightly-2026-08-15";

/// Where the builder's build outlives a fresh clone, so CI pays for rustc_codegen_spirv once.
pub fn cache_dir() -> PathBuf {
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir);
    base.join("twinray")
}

/// The rust-gpu builder's own target folder (under [`cache_dir`]), and whether it holds the
/// builder: a cold machine builds it first (197 s on 2 cores, bench/reports/tools/runs/crate-builders.tar.xz).
pub fn builder_target() -> PathBuf {
    cache_dir().join("builder-target")
}

/// A command on the pinned nightly, without the outer (stable) cargo's toolchain variables.
pub(crate) fn nightly(program: &str) -> Command {
    let mut command = Command::new("rustup");
    command.args(["run", NIGHTLY, program]);
    for var in ["RUSTUP_TOOLCHAIN", "RUSTC", "RUSTDOC", "CARGO", "RUSTC_WRAPPER", "CARGO_TARGET_DIR"] {
        command.env_remove(var);
    }
    command
}

/// The components rustc_codegen_spirv needs of its nightly.
pub const NIGHTLY_COMPONENTS: [&str; 3] = ["rust-src", "rustc-dev", "llvm-tools"];

/// The pinned nightly with the components rust-gpu needs, installed when rustup lacks the
/// toolchain or any of them (a nightly installed by hand, minimal, has none): every command
/// that builds Rust stages calls it first (`cargo xtask setup`, `shaders`, `watch`,
/// `new-shape`; `twinray build`), so none stops at rustup's "toolchain is not installed".
pub fn ensure_toolchain() -> Result<()> {
    ensure_toolchain_with(Path::new("rustup"))
}

/// [`ensure_toolchain`] with the rustup at `rustup`.
fn ensure_toolchain_with(rustup: &Path) -> Result<()> {
    let installed = output(Command::new(rustup).args(["component", "list", "--installed", "--toolchain", NIGHTLY]))
        .unwrap_or_default();
    let has = |c: &str| installed.lines().any(|l| l.starts_with(c));
    if NIGHTLY_COMPONENTS.iter().all(|c| has(c)) {
        return Ok(());
    }
    output(Command::new(rustup).arg("--version"))
        .context("rustup is needed to build Rust stages (https://rustup.rs)")?;
    eprintln!("build: installing the Rust toolchain {NIGHTLY} that rust-gpu 0.11 needs, with its components (once per machine)");
    run(Command::new(rustup)
        .args(["toolchain", "install", NIGHTLY, "--profile", "minimal", "--component"])
        .arg(NIGHTLY_COMPONENTS.join(",")))
}

/// The builder compiled from the manifest `manifest` (a checkout's `shaders-rs/builder`, or the
/// embedded copy), with its output shown when `shown`.
pub fn compiled(manifest: &Path, shown: bool) -> Result<PathBuf> {
    ensure_toolchain()?;
    let target = builder_target();
    let binary = target.join("release/twinray-shader-builder");
    let first = !binary.exists();
    if first {
        eprintln!(
            "build: compiling rust-gpu's backend ({BACKEND_MINUTES} on 2 cores, once; cached in {})",
            target.display()
        );
    }
    let mut command = nightly("cargo");
    command.args(["build", "--release", "--manifest-path"]).arg(manifest).env("CARGO_TARGET_DIR", &target);
    if shown {
        run(&mut command)?;
    } else if first {
        with_progress(&mut command, lock_packages(manifest)).context("compiling the rust-gpu builder")?;
    } else {
        output(command.arg("--quiet")).context("compiling the rust-gpu builder")?;
    }
    Ok(binary)
}

/// What the backend's first build took on 2 cores where it was measured: 197 s on an idle
/// machine, 562 s beside CI's other steps on a slower one (bench/reports/tools and
/// bench/reports/build-time).
const BACKEND_MINUTES: &str = "3 to 10 minutes";

/// How often a first build of the backend says how far it got.
const PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_secs(20);

/// The packages of the lock file beside `manifest`: about as many crates as a first build
/// compiles (a few are for other platforms).
fn lock_packages(manifest: &Path) -> usize {
    let lock = std::fs::read_to_string(manifest.with_file_name("Cargo.lock")).unwrap_or_default();
    lock.matches("[[package]]").count()
}

/// Runs cargo's `command`, saying every [`PROGRESS_EVERY`] how many of about `total` crates it
/// has compiled and for how long; its output is shown only when it fails.
fn with_progress(command: &mut Command, total: usize) -> Result<()> {
    use std::io::BufRead;
    let mut child = command
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .context("starting cargo")?;
    let stderr = child.stderr.take().context("cargo's output")?;
    let (lines, said) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stderr).lines().map_while(Result::ok) {
            if lines.send(line).is_err() {
                break;
            }
        }
    });
    let start = std::time::Instant::now();
    let (mut kept, mut compiled, mut last) = (Vec::new(), 0, start);
    let status = loop {
        while let Ok(line) = said.try_recv() {
            compiled += usize::from(line.trim_start().starts_with("Compiling "));
            kept.push(line);
        }
        if let Some(status) = child.try_wait()? {
            kept.extend(said.try_iter());
            break status;
        }
        if last.elapsed() >= PROGRESS_EVERY {
            last = std::time::Instant::now();
            eprintln!("build: {}", progress(compiled, total, start.elapsed()));
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    };
    if !status.success() {
        bail!("cargo failed with {status}:\n{}", kept.join("\n"));
    }
    Ok(())
}

/// A first build's progress in words.
fn progress(compiled: usize, total: usize, elapsed: std::time::Duration) -> String {
    let s = elapsed.as_secs();
    format!(
        "rust-gpu's backend: {compiled} of about {total} crates compiled in {}:{:02} (the largest, rustc_codegen_spirv, \
         comes last; {BACKEND_MINUTES} in all)",
        s / 60,
        s % 60
    )
}

/// The builder this binary carries, written to the cache (only files that changed, so cargo
/// sees nothing new) and compiled.
pub fn embedded() -> Result<PathBuf> {
    let dir = cache_dir().join("builder-src");
    for (path, bytes) in crate::starter::builder_sources() {
        let full = dir.join(path);
        if std::fs::read(&full).is_ok_and(|old| old == *bytes) {
            continue;
        }
        std::fs::create_dir_all(full.parent().unwrap_or(&dir))?;
        // Written aside and renamed: two builds at once never read half a file.
        let temporary = full.with_extension(format!("tmp{}", std::process::id()));
        std::fs::write(&temporary, bytes)?;
        std::fs::rename(&temporary, &full)?;
    }
    compiled(&dir.join("Cargo.toml"), false)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rustup that logs its arguments and lists `components` as installed.
    fn fake_rustup(dir: &Path, components: &str) -> PathBuf {
        let path = dir.join("rustup");
        let log = dir.join("log");
        let script = format!(
            "#!/bin/sh\necho \"$@\" >> '{}'\n[ \"$1\" = component ] && printf '{components}'\nexit 0\n",
            log.display()
        );
        std::fs::write(&path, script).unwrap();
        std::process::Command::new("chmod").arg("+x").arg(&path).status().unwrap();
        path
    }

    #[test]
    fn a_first_build_says_how_far_it_got() {
        let said = progress(57, 143, std::time::Duration::from_secs(130));
        assert!(said.starts_with("rust-gpu's backend: 57 of about 143 crates compiled in 2:10"), "{said}");
        let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("../builder/Cargo.toml");
        assert!(lock_packages(&manifest) > 50, "the builder's lock lists its crates");
    }

    /// The nightly is installed where a component is missing (a toolchain installed by hand),
    /// and rustup is not asked to install anything where all are there.
    #[test]
    fn the_nightly_is_installed_with_its_components_where_any_is_missing() {
        let dir = tempfile::tempdir().unwrap();
        let partial = fake_rustup(dir.path(), "rust-src\\nllvm-tools-x86_64-unknown-linux-gnu\\n");
        ensure_toolchain_with(&partial).unwrap();
        let log = std::fs::read_to_string(dir.path().join("log")).unwrap();
        let install =
            format!("toolchain install {NIGHTLY} --profile minimal --component rust-src,rustc-dev,llvm-tools");
        assert!(log.contains(&install), "{log}");
        std::fs::remove_file(dir.path().join("log")).unwrap();
        let whole = fake_rustup(
            dir.path(),
            "rust-src\\nrustc-dev-x86_64-unknown-linux-gnu\\nllvm-tools-x86_64-unknown-linux-gnu\\n",
        );
        ensure_toolchain_with(&whole).unwrap();
        let log = std::fs::read_to_string(dir.path().join("log")).unwrap();
        assert!(!log.contains("toolchain install"), "{log}");
    }
}
