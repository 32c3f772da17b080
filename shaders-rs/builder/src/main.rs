//! Compiles the `twinray-stages` crate to SPIR-V 1.4 with rust-gpu, one module per entry point.
//!
//! Usage: `twinray-shader-builder <shader-crate-dir> <out-dir> <shader-target-dir> [features]`
//! (features: the shader crate's cargo features, comma-separated, e.g. `without-textures`).
//! Run by `cargo xtask shaders` and `twinray build`; it lives outside the stable workspace
//! because rustc_codegen_spirv must be compiled by the pinned nightly. Warnings fail the build
//! unless `TWINRAY_BUILDER_WARNINGS=allow` (a user's crate: `twinray build` shows them).

use spirv_builder::{Capability, ModuleResult, SpirvBuilder, SpirvMetadata};
use std::path::PathBuf;
use std::process::ExitCode;

/// Vulkan 1.1 environment with SPIR-V 1.4, the first version ray tracing modules may use.
const TARGET: &str = "spirv-unknown-vulkan1.1-spv1.4";

fn main() -> ExitCode {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let (crate_dir, out_dir, target_dir, features) = match args.as_slice() {
        [c, o, t] => (c, o, t, Vec::new()),
        [c, o, t, f] => (c, o, t, f.to_string_lossy().split(',').filter(|s| !s.is_empty()).map(String::from).collect()),
        _ => {
            eprintln!("usage: twinray-shader-builder <shader-crate-dir> <out-dir> <shader-target-dir> [features]");
            return ExitCode::from(2);
        }
    };
    match build(crate_dir, out_dir, target_dir, features) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn build(crate_dir: &PathBuf, out_dir: &PathBuf, target_dir: &PathBuf, features: Vec<String>) -> Result<(), String> {
    let mut builder = SpirvBuilder::new(crate_dir, TARGET);
    // The crate is compiled by the toolchain this builder runs on (`rustup run` sets it), the
    // one its backend was built by: spirv-builder clears RUSTUP_TOOLCHAIN for its cargo, so a
    // crate without a toolchain file of its own would otherwise get the default toolchain.
    builder.toolchain_overwrite = std::env::var("RUSTUP_TOOLCHAIN").ok();
    let result = builder
        .shader_crate_features(features)
        .capability(Capability::RayTracingKHR)
        .extension("SPV_KHR_ray_tracing")
        // For `raygen_query` and `render_compute`. rust-gpu declares it in every module, so
        // `cargo xtask shaders` drops it from the modules without a ray query.
        .capability(Capability::RayQueryKHR)
        .extension("SPV_KHR_ray_query")
        // The texture array (a runtime array of combined image samplers, indexed per hit):
        // descriptor indexing, core only from SPIR-V 1.5. `cargo xtask shaders` adds the
        // `NonUniform` decorations rust-gpu cannot yet emit (docs/upstream/non-uniform.md),
        // with the capabilities they need.
        .capability(Capability::RuntimeDescriptorArray)
        .extension("SPV_EXT_descriptor_indexing")
        .multimodule(true)
        // No spirv-opt performance passes: the driver optimises, as it does the GLSL set, which
        // glslang hands over unoptimised. On the H200 the passes cost the Rust ray generation
        // stack (224 bytes kept across each trace call against 192 without them) and time
        // (showcase at 16 spp: Rust/GLSL 1.135 with them, 1.086 without). `cargo xtask shaders`
        // strips the debug info they would have stripped.
        .extra_arg("--no-spirv-opt")
        // No OpName/OpLine: the committed modules then depend only on the code, not on paths.
        .spirv_metadata(SpirvMetadata::None)
        .deny_warnings(std::env::var_os("TWINRAY_BUILDER_WARNINGS").is_none_or(|v| v != "allow"))
        .target_dir_path(target_dir.clone())
        .build()
        .map_err(|e| format!("spirv-builder failed: {e}"))?;
    let ModuleResult::MultiModule(modules) = &result.module else {
        return Err("spirv-builder returned a single module although multimodule was asked".into());
    };
    std::fs::create_dir_all(out_dir).map_err(|e| format!("creating {}: {e}", out_dir.display()))?;
    for (entry, path) in modules {
        let dest = out_dir.join(format!("{entry}.spv"));
        std::fs::copy(path, &dest).map_err(|e| format!("copying {} to {}: {e}", path.display(), dest.display()))?;
        println!("{entry} -> {}", dest.display());
    }
    Ok(())
}
