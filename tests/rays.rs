//! Rays counted as traced (for Mrays/s): primary rays are pixels times samples, and ray
//! generation counts each shadow ray as it traces it, in both sets.

use twinray_host::scene::{MeshFiles, Scene};
use twinray_tests::{render_scene, validated_context, SCENE_TEST_SIZE};

/// A floor filling the whole view from above, lit by `lights` (TOML), 2 x 2 samples.
fn floor_scene(lights: &str) -> Scene {
    let text = format!(
        "name = \"floor\"\n[image]\nwidth = 64\nheight = 64\nsamples = 2\n\
         [camera]\neye = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\nfov_y_degrees = 40.0\n\
         [materials.m]\nkind = \"diffuse\"\ncolor = [0.8, 0.8, 0.8]\n\
         [shapes.floor]\nkind = \"rectangle\"\nsize = [100.0, 100.0]\n\
         [parity]\nmax_rmse = 0.0\npixel_threshold = 0\nmax_pixels_over_threshold = 0.0\nmax_hit_mismatches = 0.0\n\
         [[objects]]\nshape = \"floor\"\nmaterial = \"m\"\n{lights}"
    );
    Scene::parse(&text, "floor test", MeshFiles::Builtin).expect("floor scene")
}

#[test]
fn every_sample_of_a_lit_floor_traces_one_shadow_ray_per_light_sample() {
    let ctx = validated_context();
    let (w, h) = SCENE_TEST_SIZE;
    let samples = (u64::from(w) * u64::from(h)) * 4;
    let sun =
        "[[lights]]\nkind = \"directional\"\ndirection = [0.3, 1.0, 0.2]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n";
    // A rect light above, 3 x 3 shadow samples, plus a light behind the floor (no rays:
    // its cosine is negative) and one that casts no shadows.
    let rect = "[[lights]]\nkind = \"rect\"\ncenter = [0.0, 3.0, 0.0]\nu = [1.0, 0.0, 0.0]\nv = [0.0, 0.0, 1.0]\n\
                color = [1.0, 1.0, 1.0]\nintensity = 1.0\nsamples = 3\n";
    let below =
        "[[lights]]\nkind = \"directional\"\ndirection = [0.0, -1.0, 0.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n";
    let unshadowed = format!("{sun}shadows = false\n");
    for (lights, shadow_per_sample) in [(sun.to_string(), 1), (format!("{sun}{rect}{below}{unshadowed}"), 1 + 9)] {
        let scene = floor_scene(&lights);
        for set in ["rust", "glsl"] {
            let out = render_scene(&ctx, &scene, set);
            assert_eq!(out.rays.primary, samples, "{set}");
            assert_eq!(out.rays.shadow, samples * shadow_per_sample, "{set}: {lights}");
        }
    }
    let dark = floor_scene(&unshadowed);
    assert_eq!(render_scene(&ctx, &dark, "rust").rays.shadow, 0, "no light casts shadows");
}
