//! Callable shaders (`material_shading = "callable"`), on lavapipe with validation on: the
//! closest-hit stages have the callable that a material's kind selects in the SBT's callable
//! region compute its colour, and the image is the one inline materials give, on scenes with
//! every material kind, procedural shapes and meshes, in both sets and with the callables or
//! the closest-hit stages from the other language.

use twinray::compare::{diff, verdict};
use twinray::scene::{MaterialShading, Scene};
use twinray_tests::{render_scene, validated_context, SCENE_TEST_SIZE};

#[test]
fn callable_materials_give_the_inline_image() {
    let ctx = validated_context();
    let pixels = u64::from(SCENE_TEST_SIZE.0 * SCENE_TEST_SIZE.1);
    for name in ["materials", "cutout", "meshes"] {
        let scene = Scene::load(Some(name)).expect("built-in scene");
        let mut callable = scene.clone();
        callable.file.material_shading = MaterialShading::Callable;
        assert!(!callable.build().plan.callables().is_empty());
        let parity = scene.file.parity;
        for (inline_set, callable_set) in
            [("rust", "rust"), ("glsl", "glsl"), ("rust", "rust,callable=glsl"), ("glsl", "glsl,closest_hit=rust")]
        {
            let a = render_scene(&ctx, &scene, inline_set);
            let b = render_scene(&ctx, &callable, callable_set);
            let d = diff(&b, &a, parity.pixel_threshold);
            eprintln!(
                "{name}: callable {callable_set} vs inline {inline_set}: rmse {:.6}, {} over, {} hit mismatches",
                d.color.rmse, d.color.pixels_over_threshold, d.hit_mismatches
            );
            let f = verdict(&d, &parity, pixels);
            assert!(f.is_empty(), "{name} callable {callable_set} vs inline {inline_set}: {f:?}");
            assert_eq!(d.hit_mismatches, 0, "{name}: the same surfaces are hit");
        }
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}
