//! Converged references: cached under a key of scene, size, samples and shaders (a changed
//! scene or set renders again), and what renders with more samples converge to.

use twinray::reference_image::reference;
use twinray::{render, RenderOptions};
use twinray_tests::{set, validated_context};

fn rmse(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let sum: f64 = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |c| f64::from(p[c] - q[c]).powi(2))).sum();
    (sum / (3 * a.len()) as f64).sqrt()
}

#[test]
fn references_are_cached_per_scene_set_and_samples() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let scene = twinray::Scene::load(Some("lights")).unwrap();
    let size = (24, 24);
    let first = reference(&ctx, &scene, &set("glsl"), size, 16, dir.path()).unwrap();
    assert!(!first.cached);
    let again = reference(&ctx, &scene, &set("glsl"), size, 16, dir.path()).unwrap();
    assert!(again.cached && again.path == first.path);
    assert_eq!(again.linear, first.linear, "the cache returns what was rendered");
    // Another set, sample count or scene is another key.
    let rust = reference(&ctx, &scene, &set("rust"), size, 16, dir.path()).unwrap();
    let more = reference(&ctx, &scene, &set("glsl"), size, 64, dir.path()).unwrap();
    let mut changed = scene.clone();
    changed.file.background = [0.5, 0.0, 0.0];
    let red = reference(&ctx, &changed, &set("glsl"), size, 16, dir.path()).unwrap();
    for other in [&rust, &more, &red] {
        assert!(!other.cached && other.path != first.path, "{}", other.path.display());
    }
    assert!(rmse(&red.linear, &first.linear) > 0.0);
}

#[test]
fn renders_converge_to_the_reference_as_samples_grow() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let scene = twinray::Scene::load(Some("lights")).unwrap();
    let (width, height) = (32, 32);
    let truth = reference(&ctx, &scene, &set("glsl"), (width, height), 1024, dir.path()).unwrap();
    let error = |side: u32| {
        let mut s = scene.clone();
        s.file.image.samples = side;
        s.file.image.seed = 12345; // independent of the reference's frames
        let out = render(&ctx, &s, &set("rust"), &RenderOptions { width, height, warmup: 0, runs: 1 }).unwrap();
        rmse(&out.linear, &truth.linear)
    };
    let (e1, e4, e16) = (error(1), error(4), error(16));
    assert!(e1 > 1.5 * e4 && e4 > 1.5 * e16, "RMSE at 1, 16, 256 spp: {e1} {e4} {e16}");
}
