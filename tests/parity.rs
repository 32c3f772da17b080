//! Rust against GLSL (and per-stage mixes) on the sphere scene, on lavapipe with validation on.
//!
//! The tolerance is the scene's own `[parity]` table (scenes/spheres.toml): RMSE <= 0.01, at
//! most 0.2% of pixels more than 2 8-bit steps apart, at most 0.2% of pixels with different hit
//! ids, and none of those away from a silhouette. Both sets compute the same f32 formulas, but
//! the compilers may fuse, reorder and round differently within Vulkan's precision rules, so
//! exact equality is not promised; a one-step shading difference or a silhouette pixel that
//! flips is noise, anything beyond it a real difference. The negative control shows the
//! tolerance is tight enough to catch a change far smaller than a shader slip.

use std::sync::Arc;
use twinray_host::compare::{diff, verdict};
use twinray_host::{Context, RenderOutput, Scene};
use twinray_tests::{default_scene, render, validated_context, TEST_SIZE};

fn failures(a: &RenderOutput, b: &RenderOutput) -> Vec<String> {
    let parity = default_scene().file.parity;
    let d = diff(a, b, parity.pixel_threshold);
    eprintln!("{d:?}");
    verdict(&d, &parity, u64::from(TEST_SIZE * TEST_SIZE))
}

/// The default scene rendered with each whole set.
fn both_sets() -> (Arc<Context>, Scene, RenderOutput, RenderOutput) {
    let ctx = validated_context();
    let scene = default_scene();
    let rust = render(&ctx, &scene, "rust");
    let glsl = render(&ctx, &scene, "glsl");
    (ctx, scene, rust, glsl)
}

#[test]
fn rust_and_glsl_sets_agree_within_tolerance() {
    let (_, _, rust, glsl) = both_sets();
    let f = failures(&rust, &glsl);
    assert!(f.is_empty(), "rust vs glsl: {f:?}");
    // The image is not trivially empty: most pixels see a sphere, some see the background.
    let hits = twinray_host::compare::hit_count(&rust);
    assert!(hits > 1000 && hits < u64::from(TEST_SIZE * TEST_SIZE), "{hits} hit pixels");
}

#[test]
fn per_stage_mixes_agree_with_both_sets() {
    let (ctx, scene, rust, glsl) = both_sets();
    for mix in ["rust,intersection=glsl", "glsl,closest_hit=rust", "glsl,raygen=rust,miss=rust"] {
        let out = render(&ctx, &scene, mix);
        for (name, other) in [("rust", &rust), ("glsl", &glsl)] {
            let f = failures(&out, other);
            assert!(f.is_empty(), "{mix} vs {name}: {f:?}");
        }
    }
}

/// A camera moved by 0.05 units (under a tenth of a pixel's footprint at the scene centre)
/// must already fail the tolerance: parity would catch any shader slip of that size or more.
#[test]
fn tolerance_catches_a_small_change() {
    let ctx = validated_context();
    let scene = default_scene();
    let mut moved = scene.clone();
    moved.file.camera.eye[0] += 0.05;
    let a = render(&ctx, &scene, "rust");
    let b = render(&ctx, &moved, "rust");
    assert!(!failures(&a, &b).is_empty(), "a moved camera passed the parity tolerance");
}
