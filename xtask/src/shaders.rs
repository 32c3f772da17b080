//! `cargo xtask shaders [--check]`: builds the Rust set with rust-gpu and the GLSL set with
//! glslangValidator, validates every module with spirv-val, checks each declares the entry
//! point, SPIR-V version and bindings the host expects, and installs them in `spirv/` (or, with
//! `--check`, fails if the committed modules differ); with `--out DIR`, builds both sets into
//! DIR instead (`--without NAMES`: without some features' code).

use crate::process::repo_root;
use anyhow::{bail, Context, Result};
use std::path::Path;
use twinray_compile::{build_set, read_module, require_tools, Output};
use twinray_shared::catalog::{Language, MODULES};

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

/// `cargo xtask shaders --out DIR [--without NAMES]`: both sets built into `DIR/rust` and
/// `DIR/glsl` (without the code of the named features of `twinray_shared::features`), each
/// validated and checked as the committed sets are; loaded with `--sets DIR/rust,DIR/glsl`.
pub fn build_into(out: &Path, names: &[String]) -> Result<()> {
    let root = repo_root();
    require_tools()?;
    let mut bits = 0;
    for name in names {
        let Some(feature) = twinray_shared::features::by_name(name) else {
            let known = twinray_shared::features::names(twinray_shared::features::ALL);
            bail!("--without {name}: no such feature (the features are {known})");
        };
        bits |= feature.bit;
    }
    for language in Language::ALL {
        let dir = out.join(language.name());
        twinray_compile::build_set_without(&root, language, &dir, Output::Shown, bits)?;
        let without = if names.is_empty() { String::new() } else { format!(" without {}", names.join(", ")) };
        println!("shaders: the {} set{without} in {}", language.name(), dir.display());
    }
    Ok(())
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
