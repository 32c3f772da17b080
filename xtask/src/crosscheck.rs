//! `cargo xtask crosscheck [SCENES...] [--refresh] [-- TWINRAY-ARGS]`: twinray's references
//! against Mitsuba 3 (docs/shading-model.md). Makes, once, a Python virtual environment in
//! `target/crosscheck/venv` with Mitsuba pinned, then runs `twinray crosscheck` with it; with
//! `--refresh`, renders the Mitsuba data the tests compare against into `tests/crosscheck/`.

use crate::process::{self, cargo, repo_root};
use crate::setup::{self, Scope};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// What the virtual environment holds; a change makes it again.
const PINS: &[&str] = &["mitsuba==3.9.1", "drjit==1.5.0", "numpy==2.4.6"];

/// The committed Mitsuba data: `(scene, width, height, Mitsuba samples per pixel)`. Scene
/// names are built-in scenes or files of `tests/crosscheck/` (without `.toml`).
pub const TEST_SCENES: &[(&str, u32, u32, u32)] = &[
    ("plate", 160, 120, 512),
    ("sphere", 80, 60, 2048),
    ("meshes", 80, 60, 2048),
    ("emitters", 80, 60, 2048),
    ("textured", 160, 120, 2048),
];

pub fn run(scenes: &[String], refresh: bool, twinray_args: &[String]) -> Result<()> {
    setup::run(Scope::Vulkan)?;
    let python = venv()?;
    let python = python.to_string_lossy();
    let base = ["run", "--release", "--quiet", "-p", "twinray", "--", "crosscheck", "--python", &python];
    if !refresh {
        let args: Vec<&str> = scenes.iter().chain(twinray_args).map(String::as_str).collect();
        return cargo(&[&base[..], &args].concat(), &[]);
    }
    let root = repo_root();
    let out = root.join("target/crosscheck/refresh");
    for (scene, width, height, spp) in TEST_SCENES {
        let file = root.join("tests/crosscheck").join(format!("{scene}.toml"));
        let scene_arg = if file.exists() { file.to_string_lossy().into_owned() } else { scene.to_string() };
        let (w, h, spp) = (width.to_string(), height.to_string(), spp.to_string());
        let size = ["--width", &w, "--height", &h, "--mitsuba-spp", &spp, "--spp", "256"];
        let out_arg = out.to_string_lossy();
        cargo(&[&base[..], &[&scene_arg, "--out", &out_arg], &size].concat(), &[])?;
        copy_data(&out.join(scene).join("mitsuba"), &root.join("tests/crosscheck").join(scene))?;
    }
    println!("crosscheck: Mitsuba data rewritten in tests/crosscheck/; review with git diff before committing");
    Ok(())
}

/// The manifest and the passes' renders of `from` into `to`, the renders gzipped (twinray reads
/// `NAME.f32.gz` where `NAME.f32` is absent: 3.4 MB of floats keep in 0.18 MB). The scene
/// dictionaries and meshes stay behind: the tests need only the images.
fn copy_data(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).with_context(|| format!("creating {}", to.display()))?;
    for entry in std::fs::read_dir(from).with_context(|| format!("reading {}", from.display()))? {
        let path = entry?.path();
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if name == "manifest.json" {
            std::fs::copy(&path, to.join(&name)).with_context(|| format!("copying {}", path.display()))?;
        } else if name.ends_with(".f32") {
            // -n: no name or time in the header, so that the same render gives the same file.
            let zipped = Command::new("gzip").args(["-9", "-n", "-c"]).arg(&path).output()?;
            anyhow::ensure!(zipped.status.success(), "gzip {} failed", path.display());
            std::fs::write(to.join(format!("{name}.gz")), zipped.stdout)?;
            let _ = std::fs::remove_file(to.join(&name));
        }
    }
    Ok(())
}

/// The virtual environment's Python, made (or remade, when the pins changed) if needed.
fn venv() -> Result<PathBuf> {
    let dir = repo_root().join("target/crosscheck/venv");
    let python = dir.join("bin/python");
    let marker = dir.join("twinray-pins.txt");
    let pins = PINS.join("\n");
    if std::fs::read_to_string(&marker).is_ok_and(|m| m == pins) && python.exists() {
        return Ok(python);
    }
    // Debian keeps venv's pip bootstrap in its own package.
    if !Command::new("python3").args(["-c", "import ensurepip"]).output().is_ok_and(|o| o.status.success()) {
        setup::ensure_packages(&["python3-venv"])?;
    }
    println!("crosscheck: making {} with {}", dir.display(), PINS.join(" "));
    let _ = std::fs::remove_dir_all(&dir);
    process::run(Command::new("python3").arg("-m").arg("venv").arg(&dir))?;
    process::run(
        Command::new(&python).args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check"]).args(PINS),
    )?;
    std::fs::write(&marker, pins).with_context(|| format!("writing {}", marker.display()))?;
    Ok(python)
}
