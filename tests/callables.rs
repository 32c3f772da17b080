//! Where materials' colours come from, on lavapipe with validation on. With callable shaders
//! (`material_shading = "callable"`) the closest-hit stages have the callable that a material's
//! kind selects in the SBT's callable region compute it; with hit groups per material kind
//! (`hit_groups = "per-material"`) each instance's SBT offset selects a closest-hit stage made
//! for its material. Either way the image is the one a single closest-hit stage gives, on
//! scenes with every material kind, procedural shapes and meshes, in both sets and mixed.

use twinray_host::compare::{diff, verdict};
use twinray_host::scene::{HitGroups, MaterialShading, Scene};
use twinray_tests::{render_scene, validated_context, SCENE_TEST_SIZE};

/// Renders `materials`, `cutout` and `meshes` as written with the first set of each pair and
/// as `change` makes them with the second, and asserts the images agree within the scene's
/// tolerance with no hit mismatch.
fn same_image(change: impl Fn(&mut Scene), pairs: &[(&str, &str)]) {
    let ctx = validated_context();
    let pixels = u64::from(SCENE_TEST_SIZE.0 * SCENE_TEST_SIZE.1);
    for name in ["materials", "cutout", "meshes"] {
        let scene = Scene::load(Some(name)).expect("built-in scene");
        let mut changed = scene.clone();
        change(&mut changed);
        let parity = scene.file.parity;
        for &(written_set, changed_set) in pairs {
            let a = render_scene(&ctx, &scene, written_set);
            let b = render_scene(&ctx, &changed, changed_set);
            let d = diff(&b, &a, parity.pixel_threshold);
            eprintln!(
                "{name}: changed {changed_set} vs as written {written_set}: rmse {:.6}, {} over, {} hit mismatches",
                d.color.rmse, d.color.pixels_over_threshold, d.hit_mismatches
            );
            let f = verdict(&d, &parity, pixels);
            assert!(f.is_empty(), "{name} changed {changed_set} vs as written {written_set}: {f:?}");
            assert_eq!(d.hit_mismatches, 0, "{name}: the same surfaces are hit");
        }
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}

#[test]
fn callable_materials_give_the_inline_image() {
    let mut scene = Scene::load(Some("materials")).expect("materials");
    scene.file.material_shading = MaterialShading::Callable;
    assert_eq!(scene.build().plan.callables(), ["flat_material", "checker_material"]);
    let pairs = [("rust", "rust"), ("glsl", "glsl"), ("rust", "rust,callable=glsl"), ("glsl", "glsl,closest_hit=rust")];
    same_image(|s| s.file.material_shading = MaterialShading::Callable, &pairs);
}

#[test]
fn hit_groups_per_material_give_the_per_shape_image() {
    let mut scene = Scene::load(Some("materials")).expect("materials");
    scene.file.hit_groups = HitGroups::PerMaterial;
    let names: Vec<String> = scene.build().plan.hit_groups.iter().map(|g| g.name()).collect();
    // Checkers keep the general closest-hit stage; the rest get the flat one.
    assert!(names.contains(&"sphere".to_string()) && names.contains(&"sphere (flat)".to_string()), "{names:?}");
    let pairs = [("rust", "rust"), ("glsl", "glsl"), ("glsl", "glsl,closest_hit=rust")];
    same_image(|s| s.file.hit_groups = HitGroups::PerMaterial, &pairs);
}
