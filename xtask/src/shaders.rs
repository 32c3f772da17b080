//! `cargo xtask shaders [--check]`: builds the Rust set with rust-gpu and the GLSL set with
//! glslangValidator, validates every module with spirv-val, checks each declares the entry
//! point, SPIR-V version and bindings the host expects, and installs them in `spirv/` (or, with
//! `--check`, fails if the committed modules differ).

use crate::process::{self, have, repo_root};
use crate::setup::NIGHTLY;
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;
use twinray_shared::catalog::{GlslSource, Language, ModuleSpec, MODULES};
use twinray_shared::spirv_info::{self, ModuleInfo};

const LAYOUT_INCLUDE: &str = "shaders-glsl/twinray_layout.glsl";
const SHAPE_DISPATCH: &str = "shaders-glsl/shape_dispatch.glsl";
const SCENE_FORMAT: &str = "docs/scene-format.md";

pub fn run(check: bool) -> Result<()> {
    let root = repo_root();
    require_tools()?;
    sync_generated(&root, check)?;
    let scratch = root.join("target/xtask-shaders");
    for language in Language::ALL {
        build_set(&root, language, &scratch.join(language.name()), Output::Shown)?;
    }
    let mut stale = Vec::new();
    println!("{:<28} {:>12} {:>12} {:>12} {:>12}", "module", "rust bytes", "glsl bytes", "rust instrs", "glsl instrs");
    for spec in MODULES {
        let [rust, glsl] = Language::ALL.map(|language| read_module(&scratch.join(language.name()), spec));
        let ((rust, rust_bytes), (glsl, glsl_bytes)) = (rust?, glsl?);
        if rust.bindings != glsl.bindings {
            bail!("{}: Rust binds {:?} but GLSL binds {:?}", spec.name, rust.bindings, glsl.bindings);
        }
        println!(
            "{:<28} {rust_bytes:>12} {glsl_bytes:>12} {:>12} {:>12}",
            spec.name, rust.instruction_count, glsl.instruction_count
        );
        for language in Language::ALL {
            let built = scratch.join(language.name()).join(format!("{}.spv", spec.name));
            let committed = root.join(spec.spirv_path(language));
            if check {
                if std::fs::read(&committed).ok() != Some(std::fs::read(&built)?) {
                    stale.push(spec.spirv_path(language));
                }
            } else {
                std::fs::create_dir_all(committed.parent().unwrap_or(&root))?;
                std::fs::copy(&built, &committed).with_context(|| format!("installing {}", committed.display()))?;
            }
        }
    }
    stale.extend(unlisted_modules(&root)?);
    if !stale.is_empty() {
        bail!("committed SPIR-V is stale (run `cargo xtask shaders` and commit): {}", stale.join(", "));
    }
    println!(
        "shaders: {} modules per set built, validated and {}",
        MODULES.len(),
        if check { "up to date" } else { "installed in spirv/" }
    );
    Ok(())
}

/// Whether the build tools' own output is shown, or kept and shown only when they fail.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Output {
    Shown,
    OnFailure,
}

/// The tools every shader build needs.
pub fn require_tools() -> Result<()> {
    for tool in ["glslangValidator", "spirv-val", "spirv-opt"] {
        if !have(tool) {
            bail!("{tool} not found: run `cargo xtask setup` (Debian packages glslang-tools, spirv-tools)");
        }
    }
    Ok(())
}

/// Builds every module of `language` into `dir` (emptied first) as `NAME.spv`, validates each
/// with spirv-val and checks what it declares.
pub fn build_set(root: &Path, language: Language, dir: &Path, output: Output) -> Result<()> {
    if dir.exists() {
        std::fs::remove_dir_all(dir)?;
    }
    std::fs::create_dir_all(dir)?;
    match language {
        Language::Rust => build_rust(root, dir, output)?,
        Language::Glsl => build_glsl(root, dir, output)?,
    }
    for spec in MODULES {
        let path = dir.join(format!("{}.spv", spec.name));
        let label = format!("{} {}", language.name(), spec.name);
        process::output(Command::new("spirv-val").args(twinray_shared::catalog::SPIRV_VAL_ARGS).arg(&path))
            .with_context(|| format!("spirv-val rejected {label}"))?;
        let (info, _) = read_module(dir, spec)?;
        spec.check_declarations(&info, language).map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    }
    Ok(())
}

/// What a built module declares, and its size in bytes.
fn read_module(dir: &Path, spec: &ModuleSpec) -> Result<(ModuleInfo, usize)> {
    let path = dir.join(format!("{}.spv", spec.name));
    let bytes = std::fs::read(&path).with_context(|| format!("reading {}", path.display()))?;
    let info = spirv_info::parse(&bytes).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok((info, bytes.len()))
}

/// Committed `.spv` files that no longer belong to a module of the catalog.
fn unlisted_modules(root: &Path) -> Result<Vec<String>> {
    let mut extra = Vec::new();
    for language in Language::ALL {
        let dir = root.join("spirv").join(language.name());
        for entry in std::fs::read_dir(&dir).with_context(|| format!("listing {}", dir.display()))? {
            let name = entry?.file_name().to_string_lossy().into_owned();
            let listed = MODULES.iter().any(|m| format!("{}.spv", m.name) == name);
            if !listed {
                extra.push(format!("spirv/{}/{name} (not in the module catalog: delete it)", language.name()));
            }
        }
    }
    Ok(extra)
}

/// Writes (or checks) what is generated from twinray-shared: the GLSL mirror of the layout and
/// the shape table of the scene format's docs.
fn sync_generated(root: &Path, check: bool) -> Result<()> {
    let include = twinray_shared::glsl::layout_include().map_err(anyhow::Error::msg)?;
    sync_file(root, LAYOUT_INCLUDE, &include, check)?;
    sync_file(root, SHAPE_DISPATCH, &twinray_shared::glsl::shape_dispatch_include(), check)?;
    let doc = std::fs::read_to_string(root.join(SCENE_FORMAT)).with_context(|| format!("reading {SCENE_FORMAT}"))?;
    let doc = twinray_shared::shapes::with_docs_table(&doc).map_err(|e| anyhow::anyhow!("{SCENE_FORMAT}: {e}"))?;
    sync_file(root, SCENE_FORMAT, &doc, check)
}

fn sync_file(root: &Path, relative: &str, text: &str, check: bool) -> Result<()> {
    let path = root.join(relative);
    let current = std::fs::read_to_string(&path).unwrap_or_default();
    if current == text {
        return Ok(());
    }
    if check {
        bail!("{relative} differs from what twinray-shared generates: run `cargo xtask shaders` and commit");
    }
    std::fs::write(&path, text)?;
    println!("shaders: regenerated {relative}");
    Ok(())
}

/// Where the builder's build outlives a fresh clone, so CI pays for rustc_codegen_spirv once.
fn cache_dir() -> PathBuf {
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(|| repo_root().join("target"));
    base.join("twinray")
}

/// A command on the pinned nightly, without the outer (stable) cargo's toolchain variables.
fn nightly(program: &str) -> Command {
    let mut command = Command::new("rustup");
    command.args(["run", NIGHTLY, program]);
    for var in ["RUSTUP_TOOLCHAIN", "RUSTC", "RUSTDOC", "CARGO", "RUSTC_WRAPPER", "CARGO_TARGET_DIR"] {
        command.env_remove(var);
    }
    command
}

fn build_rust(root: &Path, out: &Path, output: Output) -> Result<()> {
    let cache = cache_dir();
    let target = cache.join("builder-target");
    if !target.join("release/twinray-shader-builder").exists() {
        println!("shaders: building the rust-gpu builder (about 9 minutes, once; cached in {})", target.display());
    }
    run_tool(
        output,
        nightly("cargo")
            .args(["build", "--release", "--manifest-path"])
            .arg(root.join("shaders-rs/builder/Cargo.toml"))
            .env("CARGO_TARGET_DIR", &target),
    )?;
    // spirv-builder looks for librustc_codegen_spirv.so on the library path.
    let deps = target.join("release");
    run_tool(
        output,
        nightly(&target.join("release/twinray-shader-builder").to_string_lossy())
            .arg(root.join("shaders-rs/shaders"))
            .arg(out)
            .arg(cache.join("shader-target"))
            .env("LD_LIBRARY_PATH", deps),
    )
    .context("building the Rust shaders")?;
    strip_debug_info(out)
}

/// Strips the debug info (source paths, lines) that rust-gpu leaves in when its spirv-opt pass
/// is off, so that the committed modules depend only on the code, and the ray query capability
/// from modules that trace no ray query.
fn strip_debug_info(dir: &Path) -> Result<()> {
    for spec in MODULES {
        let path = dir.join(format!("{}.spv", spec.name));
        let stripped = dir.join(format!("{}.stripped", spec.name));
        process::run(Command::new("spirv-opt").arg("--strip-debug").arg(&path).arg("-o").arg(&stripped))
            .with_context(|| format!("stripping {}", path.display()))?;
        // rust-gpu declares every capability the builder names in every module: one that
        // declares ray queries without using them would need VK_KHR_ray_query for nothing.
        let bytes = std::fs::read(&stripped)?;
        let trimmed =
            spirv_info::without_unused_ray_query(&bytes).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        std::fs::write(&path, trimmed)?;
        std::fs::remove_file(&stripped)?;
    }
    Ok(())
}

/// Compiles every GLSL module; a shape's intersection stage is the few lines of
/// `ModuleSpec::glsl_wrapper`, written beside the output, with `shaders-glsl/` on the include
/// path.
fn build_glsl(root: &Path, out: &Path, output: Output) -> Result<()> {
    let include = root.join("shaders-glsl");
    let wrappers = out.join("wrappers");
    std::fs::create_dir_all(&wrappers)?;
    for spec in MODULES {
        let source = match spec.glsl_wrapper() {
            Some(text) => {
                let path = wrappers.join(spec.glsl_file());
                std::fs::write(&path, text)?;
                path
            }
            None => include.join(spec.glsl_file()),
        };
        let mut command = Command::new("glslangValidator");
        command.args(["-V", "--target-env", "spirv1.4", "-o"]).arg(out.join(format!("{}.spv", spec.name)));
        if let GlslSource::Variant { define, .. } = spec.glsl {
            command.arg(format!("-D{define}"));
        }
        run_tool(output, command.arg(format!("-I{}", include.display())).arg(&source))
            .with_context(|| format!("compiling {}", source.display()))?;
    }
    Ok(())
}

fn run_tool(output: Output, command: &mut Command) -> Result<()> {
    match output {
        Output::Shown => process::run(command),
        Output::OnFailure => process::output(command).map(|_| ()),
    }
}
