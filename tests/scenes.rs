//! Every built-in scene renders with the Rust set, the GLSL set and a per-stage mix, on
//! lavapipe with validation on, and each pair agrees within the scene's own parity tolerance
//! (its `[parity]` table; see scenes/spheres.toml for why a tolerance and not equality).
//! The context closes at the end, so an object leaked by any of the renders fails the test.

use twinray_host::compare::{scene_diff, verdict};
use twinray_tests::{builtin_scenes, render_scene, validated_context, SCENE_TEST_SIZE};

/// One mix per scene, taken in turn, so every stage is mixed in across the suite.
const MIXES: [&str; 4] =
    ["rust,intersection=glsl", "glsl,raygen=rust", "rust,closest_hit=glsl,miss=glsl", "glsl,intersection=rust"];

#[test]
fn every_builtin_scene_agrees_across_sets_and_a_mix() {
    let ctx = validated_context();
    let pixels = u64::from(SCENE_TEST_SIZE.0 * SCENE_TEST_SIZE.1);
    let mut failures = Vec::new();
    for (i, scene) in builtin_scenes().iter().enumerate() {
        let rust = render_scene(&ctx, scene, "rust");
        let glsl = render_scene(&ctx, scene, "glsl");
        let mix = MIXES[i % MIXES.len()];
        let mixed = render_scene(&ctx, scene, mix);
        assert!(twinray_host::compare::hit_count(&rust) > 0, "{}: nothing visible", scene.name());
        let parity = scene.file.parity;
        for (label, a, b) in
            [("rust vs glsl", &rust, &glsl), ("mix vs rust", &mixed, &rust), ("mix vs glsl", &mixed, &glsl)]
        {
            let d = scene_diff(scene, a, b);
            let f = verdict(&d, &parity, pixels);
            eprintln!(
                "{} {label} ({mix}): rmse {:.6}, {} over, {} hit mismatches",
                scene.name(),
                d.color.rmse,
                d.color.pixels_over_threshold,
                d.hit_mismatches
            );
            if !f.is_empty() {
                failures.push(format!("{} {label}: {f:?}", scene.name()));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    // Every scene's objects are destroyed by now: the layer reports any that are not.
    ctx.close().expect("validation errors or leaked objects at teardown");
}
