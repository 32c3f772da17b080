//! Rays that reach the whole scene (`FrameUniform::reach`, `scene::reach`): a sphere seen from
//! 5,000 and from 1e6 units renders with both sets alike, and a directional light's occluder
//! 1,500 (300,000) units along the light, out of view, casts its shadow on it. With the fixed
//! reach of 1,000 units these rendered as empty background, unshadowed.

use twinray::{RenderOptions, Scene};
use twinray_tests::{repo_root, set, validated_context};

/// The pixel at the centre of the occluder's shadow (the sphere's point (0, 70.7, 70.7) of
/// radius 100, scaled), and one on the lit part of the sphere below it.
const SHADOWED: (usize, usize) = (48, 22);
const LIT: (usize, usize) = (48, 40);

#[test]
fn far_scenes_render_whole_with_their_distant_shadows() {
    let ctx = validated_context();
    for name in ["far-5000", "far-1e6"] {
        let path = repo_root().join(format!("tests/reach/{name}.toml"));
        let scene = Scene::load(Some(&path.to_string_lossy())).unwrap();
        let opts = RenderOptions { width: 96, height: 96, warmup: 0, runs: 1, placements: 1 };
        let reach = scene.frame_uniform(96, 96).reach;
        let extent = scene.file.camera.eye[2];
        assert!(
            reach.x > extent && reach.x < extent * 1.1,
            "{name}: primary rays reach the sphere's far side: {reach}"
        );
        let [rust, glsl] = ["rust", "glsl"].map(|s| twinray::render(&ctx, &scene, &set(s), &opts).unwrap());
        let d = twinray::compare::diff(&rust, &glsl, scene.file.parity.pixel_threshold);
        let failures = twinray::compare::verdict(&d, &scene.file.parity, 96 * 96);
        assert!(failures.is_empty(), "{name}: {failures:?}");
        for out in [&rust, &glsl] {
            assert!(out.written.is_clean(), "{name}: {:?}", out.written);
            let hits = twinray::compare::hit_count(out);
            assert!(hits > 96 * 96 * 2 / 5, "{name}: the sphere fills nearly half the view ({hits} pixels hit)");
            let luminance = |(x, y): (usize, usize)| out.linear[y * 96 + x].iter().sum::<f32>();
            let id = |(x, y): (usize, usize)| out.hit_ids[y * 96 + x];
            assert_eq!(id(SHADOWED), id(LIT), "{name}: both pixels see the sphere");
            assert_eq!(luminance(SHADOWED), 0.0, "{name}: the distant occluder shadows the sphere");
            assert!(luminance(LIT) > 1.0, "{name}: the rest of the lit side is lit: {}", luminance(LIT));
        }
    }
}

#[test]
fn a_scene_f32_cannot_resolve_is_refused_by_name() {
    let text = std::fs::read_to_string(repo_root().join("tests/reach/far-1e6.toml")).unwrap();
    // The occluder shrunk to a millimetre at 300,000 units, where f32 steps by 1/32.
    let tiny = text.replace("radius = 10000.0", "radius = 0.001");
    let e = Scene::parse(&tiny, "tiny.toml", twinray::scene::MeshFiles::Builtin).unwrap_err().to_string();
    assert!(e.contains("object 1 (shape \"blocker\")") && e.contains("f32 cannot resolve it"), "{e}");
}
