//! Converged references: cached under a key of scene, size, samples and shaders (a changed
//! scene or set renders again), and what renders with more samples converge to.

use twinray_host::reference::image::reference;
use twinray_host::{render, RenderOptions};
use twinray_tests::{set, validated_context};

fn rmse(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let sum: f64 = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |c| f64::from(p[c] - q[c]).powi(2))).sum();
    (sum / (3 * a.len()) as f64).sqrt()
}

#[test]
fn references_are_cached_per_scene_set_and_samples() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let scene = twinray_host::Scene::load(Some("lights")).unwrap();
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
    let scene = twinray_host::Scene::load(Some("lights")).unwrap();
    let (width, height) = (32, 32);
    let truth = reference(&ctx, &scene, &set("glsl"), (width, height), 1024, dir.path()).unwrap();
    let error = |side: u32| {
        let mut s = scene.clone();
        s.file.image.samples = side;
        s.file.image.seed = 12345; // independent of the reference's frames
        let out = render(&ctx, &s, &set("rust"), &RenderOptions::once(width, height, 0, 1)).unwrap();
        rmse(&out.linear, &truth.linear)
    };
    let (e1, e4, e16) = (error(1), error(4), error(16));
    assert!(e1 > 1.5 * e4 && e4 > 1.5 * e16, "RMSE at 1, 16, 256 spp: {e1} {e4} {e16}");
}

#[test]
fn both_sets_place_random_shadow_samples_alike_and_stratified_ones_converge_faster() {
    use twinray::bench::plots::log_slope;
    use twinray::bench::samplers::{study, Study};
    use twinray_host::scene::file::ShadowSampler;
    let ctx = validated_context();
    let mut scene = twinray_host::Scene::load(Some("lights")).unwrap();
    let opts = RenderOptions::once(32, 32, 0, 1);
    let stratified = render(&ctx, &scene, &set("glsl"), &opts).unwrap();
    scene.file.shadow_sampler = ShadowSampler::Random;
    let (rust, glsl) =
        (render(&ctx, &scene, &set("rust"), &opts).unwrap(), render(&ctx, &scene, &set("glsl"), &opts).unwrap());
    assert!(rmse(&rust.linear, &glsl.linear) < 1e-5, "the sets sample the light alike");
    assert!(rmse(&glsl.linear, &stratified.linear) > 1e-3, "the sampler changes the image");
    let dir = tempfile::tempdir().unwrap();
    let s = Study {
        set: &set("rust"),
        size: (32, 32),
        counts: &[4, 16, 64],
        reference_spp: 1024,
        cache: dir.path(),
        warmup: 0,
        runs: 1,
    };
    let rows = study(&ctx, &twinray_host::Scene::load(Some("lights")).unwrap(), &s, &|_| {}).unwrap();
    let slope = |sampler: &str| {
        let points: Vec<(f64, f64)> =
            rows.iter().filter(|r| r.sampler == sampler).map(|r| (f64::from(r.shadow_spp), r.rmse)).collect();
        log_slope(&points).unwrap()
    };
    let (st, rn) = (slope("stratified"), slope("random"));
    assert!(st < rn - 0.1 && (rn + 0.5).abs() < 0.15, "slopes: stratified {st}, random {rn}");
}
