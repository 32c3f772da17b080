//! Builds a shader set from its sources: the Rust set with rust-gpu (through the small
//! `shaders-rs/builder` binary on the pinned nightly), the GLSL set with glslangValidator;
//! every module validated with spirv-val and checked for what the host expects. `cargo xtask
//! shaders` and `watch` use it on this checkout; `twinray view` on any checkout it is given.

pub mod builder;
pub mod cpu;
mod exact;
mod exit;
pub mod folder;
mod metadata;
mod process;
pub mod scaffold;
pub mod starter;
pub mod uniformity;

use anyhow::{bail, Context, Result};
use builder::nightly;
pub use builder::{builder_target, cache_dir, ensure_toolchain, NIGHTLY, NIGHTLY_COMPONENTS};
pub use exit::exit_words;
pub use process::{have, output, run};
use std::path::Path;
use std::process::Command;
use twinray_shared::catalog::{module, own_intersection, own_material, GlslSource, Language, ModuleSpec, MODULES};
use twinray_shared::interface::MAX_RECURSION_DEPTH;
use twinray_shared::spirv_info::{self, ModuleInfo};

/// The sources of each set, relative to a checkout's root: a change under them rebuilds it.
pub fn sources(language: Language) -> &'static [&'static str] {
    match language {
        Language::Rust => &["shaders-rs/stages/src", "shaders-rs/shared/src"],
        Language::Glsl => &["shaders-glsl"],
    }
}

/// Shared files the host or the GLSL include are generated from: a change to them needs
/// `cargo xtask shaders` and a new host, which an edit loop cannot do.
pub const GENERATORS: [&str; 5] = ["layout.rs", "bindings.rs", "catalog.rs", "glsl.rs", "shapes/mod.rs"];

/// Which sets the changed files (relative to the root) rebuild, in `Language::ALL` order.
pub fn sets_for<'a>(changed: impl IntoIterator<Item = &'a Path> + Clone) -> Vec<Language> {
    let under = |language| changed.clone().into_iter().any(|p| sources(language).iter().any(|d| p.starts_with(d)));
    Language::ALL.into_iter().filter(|&l| under(l)).collect()
}

/// Whether `root` holds the sources of `language`'s set (with, for Rust, its builder).
pub fn has_sources(root: &Path, language: Language) -> bool {
    match language {
        Language::Rust => {
            root.join("shaders-rs/stages/Cargo.toml").is_file() && root.join("shaders-rs/builder/Cargo.toml").is_file()
        }
        Language::Glsl => root.join("shaders-glsl/raygen.rgen").is_file(),
    }
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

/// Builds every module of `language` from the sources under `root` into `dir` (emptied first)
/// as `NAME.spv`, validates each with spirv-val and checks what it declares.
pub fn build_set(root: &Path, language: Language, dir: &Path, output: Output) -> Result<()> {
    build_set_without(root, language, dir, output, 0)
}

/// As `build_set`, without the code of the features `without` (bits of
/// `twinray_shared::features`): the Rust crate's cargo features `without-NAME`, GLSL's
/// `TWINRAY_WITHOUT_NAME` defines.
pub fn build_set_without(root: &Path, language: Language, dir: &Path, output: Output, without: u32) -> Result<()> {
    if dir.exists() {
        std::fs::remove_dir_all(dir)?;
    }
    std::fs::create_dir_all(dir)?;
    match language {
        Language::Rust => build_rust(root, dir, output, without)?,
        Language::Glsl => build_glsl(&root.join("shaders-glsl"), dir, output, without)?,
    }
    let names: Vec<String> = MODULES.iter().map(|m| m.name.to_string()).collect();
    postprocess(dir, &names, language, (&twinray_shared::contract::record(), MAX_RECURSION_DEPTH))
}

/// Stamps each module `names` of `dir` with the contract `record` (rust-gpu's first stripped of
/// their debug info), validates it with spirv-val and checks what it declares for its stage.
pub(crate) fn postprocess(
    dir: &Path,
    names: &[String],
    language: Language,
    (record, depth): (&str, u32),
) -> Result<()> {
    if language == Language::Rust {
        strip_debug_info(dir, names)?;
    }
    for spec in specs_of(names) {
        let spec = &spec;
        let path = dir.join(format!("{}.spv", spec.name));
        let label = format!("{} {}", language.name(), spec.name);
        record_contract(&path, record)?;
        process::output(Command::new("spirv-val").args(twinray_shared::catalog::SPIRV_VAL_ARGS).arg(&path))
            .with_context(|| format!("spirv-val rejected {label}"))?;
        let (info, _) = read_module(dir, spec)?;
        let entry = spec.find_entry(&info).unwrap_or_else(|| spec.entry_point(language).to_string());
        twinray_shared::module_check::check_module(spec, &info, &entry, depth)
            .map_err(|e| anyhow::anyhow!("{label}: {e}"))?;
    }
    Ok(())
}

/// Records in the module at `path` the contract it was built against (`record`, an
/// `OpModuleProcessed`), which the host checks before it uses the module.
pub fn record_contract(path: &Path, record: &str) -> Result<()> {
    let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    let stamped = spirv_info::with_record(&bytes, record).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    std::fs::write(path, stamped).with_context(|| format!("writing {}", path.display()))
}

/// What a built module declares, and its size in bytes.
pub fn read_module(dir: &Path, spec: &ModuleSpec) -> Result<(ModuleInfo, usize)> {
    let path = dir.join(format!("{}.spv", spec.name));
    let bytes = std::fs::read(&path).with_context(|| format!("reading {}", path.display()))?;
    let info = spirv_info::parse(&bytes).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok((info, bytes.len()))
}

/// The GLSL define that builds a set without feature `name` (`-DTWINRAY_WITHOUT_TEXTURES`), which
/// the generated layout include reads (`twinray_shared::glsl`).
fn glsl_define(feature: &twinray_shared::features::Feature) -> String {
    format!("-DTWINRAY_WITHOUT_{}", feature.macro_name())
}

/// The features of `without`, each as `f(feature)`.
fn without_names(without: u32, f: impl Fn(&twinray_shared::features::Feature) -> String) -> Vec<String> {
    twinray_shared::features::FEATURES.iter().filter(|x| without & x.bit != 0).map(f).collect()
}

fn build_rust(root: &Path, out: &Path, output: Output, without: u32) -> Result<()> {
    let builder = builder::compiled(&root.join("shaders-rs/builder/Cargo.toml"), output == Output::Shown)?;
    let features = without_names(without, |feature| format!("without-{}", feature.name));
    // A target folder of its own for other features, so that switching does not rebuild both.
    let shader_target = cache_dir().join(if without == 0 { "shader-target" } else { "shader-target-without" });
    run_tool(output, &mut run_builder(&builder, &root.join("shaders-rs/stages"), out, &shader_target, &features))
        .context("building the Rust shaders")?;
    name_modules_plainly(out)
}

/// Renames each module rust-gpu wrote to `out` by its entry point's function alone: rust-gpu
/// names the module of an entry point in a module by its path (`closest_hit::triangle_closest_hit`).
pub(crate) fn name_modules_plainly(out: &Path) -> Result<()> {
    for entry in std::fs::read_dir(out)? {
        let path = entry?.path();
        let Some(name) = path.file_name().map(|s| s.to_string_lossy().into_owned()) else { continue };
        let Some((_, plain)) = name.strip_suffix(".spv").and_then(|n| n.rsplit_once("::")) else { continue };
        let renamed = out.join(format!("{plain}.spv"));
        if renamed.exists() {
            bail!("two entry points are called `{plain}` (one is {})", name.trim_end_matches(".spv"));
        }
        std::fs::rename(&path, &renamed)?;
    }
    Ok(())
}

/// The builder's command that compiles the shader crate `crate_dir` (with its cargo
/// `features`) into `out`, one `ENTRY.spv` per entry point, in the cargo target folder `target`.
pub(crate) fn run_builder(builder: &Path, crate_dir: &Path, out: &Path, target: &Path, features: &[String]) -> Command {
    let mut command = nightly(&builder.to_string_lossy());
    command.arg(crate_dir).arg(out).arg(target).arg(features.join(","));
    // spirv-builder looks for librustc_codegen_spirv.so on the library path.
    command.env("LD_LIBRARY_PATH", builder.parent().unwrap_or(Path::new(".")));
    command
}

/// The specs of the modules `names`: the catalog's, and a crate's own shapes' and materials'
/// (folder.rs lets in only `*_intersection` and `*_material` ones) as intersection and callable
/// modules, whose hit kinds and names are the host's to check against the crate's lists.
fn specs_of(names: &[String]) -> Vec<ModuleSpec> {
    let own = names.iter().filter(|n| module(n).is_none());
    let shapes = own.clone().filter_map(|n| n.strip_suffix("_intersection")).map(|shape| own_intersection(shape, 0));
    let materials = own.filter_map(|n| n.strip_suffix("_material")).map(own_material);
    let catalog = MODULES.iter().copied().filter(|m| names.iter().any(|n| n == m.name));
    catalog.chain(shapes).chain(materials).collect()
}

/// Strips the debug info (source paths, lines) that rust-gpu leaves in when its spirv-opt pass
/// is off, so that the committed modules depend only on the code; names each entry point by
/// its function alone, not its path in the crate (as the module is named); strips the ray query capability
/// from modules that trace no ray query; decorates non-uniform descriptor accesses
/// `NonUniform`, which rust-gpu's inliner drops (`uniformity`), and the error-free arithmetic
/// of `twinray_shared::exact` `NoContraction`, which rust-gpu cannot write (`exact`).
fn strip_debug_info(dir: &Path, names: &[String]) -> Result<()> {
    for spec in specs_of(names) {
        let spec = &spec;
        let path = dir.join(format!("{}.spv", spec.name));
        // Before the names go: they say which functions are exact.
        let (exact, _) =
            exact::decorate(&std::fs::read(&path)?).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        std::fs::write(&path, exact)?;
        let stripped = dir.join(format!("{}.stripped", spec.name));
        run(Command::new("spirv-opt").arg("--strip-debug").arg(&path).arg("-o").arg(&stripped))
            .with_context(|| format!("stripping {}", path.display()))?;
        // rust-gpu declares every capability the builder names in every module: one that
        // declares ray queries without using them would need VK_KHR_ray_query for nothing.
        let bytes = std::fs::read(&stripped)?;
        let named =
            spirv_info::with_plain_entry_names(&bytes).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        let trimmed =
            spirv_info::without_unused_ray_query(&named).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        let decorated = uniformity::decorate(&trimmed).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        std::fs::write(&path, decorated)?;
        std::fs::remove_file(&stripped)?;
    }
    Ok(())
}

/// Compiles every GLSL module of the twins in `include` (a checkout's `shaders-glsl/`); a
/// shape's intersection stage is the few lines of `ModuleSpec::glsl_wrapper`, written beside
/// the output, with `include` on the include path.
pub(crate) fn build_glsl(include: &Path, out: &Path, output: Output, without: u32) -> Result<()> {
    let defines = without_names(without, glsl_define);
    let include = include.to_path_buf();
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
        command.args(&defines);
        run_tool(output, command.arg(format!("-I{}", include.display())).arg(&source))
            .with_context(|| format!("compiling {}", source.display()))?;
    }
    Ok(())
}

/// Compiles the intersection stages of a crate's own shapes and the callables of its own
/// materials among the GLSL twins in `dir` (`SHAPE_intersection.rint`,
/// `MATERIAL_material.rcall`, stage files of their own) into `out`; returns their modules' names.
pub(crate) fn build_own_glsl(dir: &Path, out: &Path, output: Output) -> Result<Vec<String>> {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("listing {}", dir.display()))? {
        let path = entry?.path();
        let Some(name) = path.file_name().and_then(|n| n.to_str()) else { continue };
        let shape = name.strip_suffix(".rint").filter(|s| s.ends_with("_intersection"));
        let material = name.strip_suffix(".rcall").filter(|s| s.ends_with("_material"));
        let Some(stem) = shape.or(material).filter(|s| module(s).is_none()) else { continue };
        let mut command = Command::new("glslangValidator");
        command.args(["-V", "--target-env", "spirv1.4", "-o"]).arg(out.join(format!("{stem}.spv")));
        run_tool(output, command.arg(format!("-I{}", dir.display())).arg(&path))
            .with_context(|| format!("compiling {}", path.display()))?;
        names.push(stem.to_string());
    }
    names.sort();
    Ok(names)
}

fn run_tool(output: Output, command: &mut Command) -> Result<()> {
    match output {
        Output::Shown => run(command),
        Output::OnFailure => process::output(command).map(|_| ()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_change_rebuilds_only_the_set_of_its_sources() {
        let sets = |paths: &[&str]| sets_for(paths.iter().map(Path::new));
        assert_eq!(sets(&["shaders-rs/shared/src/shapes/sphere.rs"]), [Language::Rust]);
        assert_eq!(sets(&["shaders-glsl/shapes/sphere.glsl"]), [Language::Glsl]);
        assert_eq!(sets(&["shaders-rs/stages/src/lib.rs", "shaders-glsl/raygen.rgen"]), Language::ALL);
        assert!(sets(&["scenes/showcase.toml"]).is_empty());
    }

    #[test]
    fn a_set_without_features_names_each_in_both_languages() {
        use twinray_shared::features::{ALPHA_MASKS, TEXTURES};
        assert_eq!(
            without_names(TEXTURES | ALPHA_MASKS, glsl_define),
            ["-DTWINRAY_WITHOUT_TEXTURES", "-DTWINRAY_WITHOUT_ALPHA_MASKS"]
        );
        assert_eq!(without_names(TEXTURES, |f| format!("without-{}", f.name)), ["without-textures"]);
        assert!(without_names(0, |f| f.name.to_string()).is_empty());
    }
}
