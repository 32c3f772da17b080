//! A texture's alpha at a cutout's cutoff, against the f64 reference (`reference::texel`): a
//! quad whose base colour texture carries noise in its alpha, cut at 0.5 (glTF's MASK), read
//! nearest and bilinear through each wrap mode, with texture coordinates past [0, 1] and a
//! vertex alpha below 1 that scales the texture's. Wherever the reference decides a pixel's
//! first ray (the surface is there, or a hole), both sets on lavapipe decide it alike; it
//! leaves undecided only rays within rounding of the cutoff (a texel's border, a bilinear
//! contour), a small share of the quad.

use twinray_host::compare::hit_count;
use twinray_host::explain::rays::Camera;
use twinray_host::reference::scene::{SceneReference, SceneVerdict};
use twinray_host::render::NO_HIT_ID;
use twinray_host::scene::Scene;
use twinray_tests::gltf::Quad;
use twinray_tests::{allow_installed_models, render_scene, validated_context, SCENE_TEST_SIZE};

/// A 16 x 16 texture, grey, its alphas a hash of the texel's place over all 256 values.
fn noise() -> image::RgbaImage {
    image::RgbaImage::from_fn(16, 16, |x, y| {
        let h = (x * 73 + y * 151 + x * y * 37) % 256;
        image::Rgba([128, 128, 128, h as u8])
    })
}

#[test]
fn textured_cutouts_are_decided_where_the_reference_decides_them() {
    allow_installed_models();
    let ctx = validated_context();
    let texture = noise();
    // Nearest with repeat and mirror (texture coordinates -1 to 2), bilinear with clamp and
    // repeat; MASK at 0.5, and at 0.3 with vertex alphas of 0.8 (the cutoff at 0.375 of the
    // texture's alpha).
    let nearest = r#""magFilter": 9728, "minFilter": 9728"#;
    let cases =
        [(nearest, "10497", 1.0, 0.5), (nearest, "33648", 1.0, 0.5), ("", "33071", 1.0, 0.5), ("", "10497", 0.8, 0.3)];
    for (filter, wrap, vertex_alpha, cutoff) in cases {
        let dir = tempfile::tempdir().unwrap();
        let sampler =
            format!(r#""wrapS": {wrap}, "wrapT": {wrap}{}{filter}"#, if filter.is_empty() { "" } else { ", " });
        let material = format!(
            r#""alphaMode": "MASK", "alphaCutoff": {cutoff}, "pbrMetallicRoughness": {{"baseColorFactor": [1, 1, 1, 1]"#
        );
        let quad = Quad {
            material: &material,
            colors: [[1.0, 1.0, 1.0, vertex_alpha]; 4],
            uv: [[-1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [-1.0, 2.0]],
            texture: Some((&texture, &sampler)),
        };
        let path = quad.write(dir.path());
        let label = format!("sampler {sampler}, vertex alpha {vertex_alpha}, cutoff {cutoff}");
        let scene = Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{label}: {e}"));
        let reference = SceneReference::new(&scene).expect("reference");
        let rays = Camera::new(&scene, SCENE_TEST_SIZE).first_samples();
        let verdicts: Vec<SceneVerdict> = rays
            .iter()
            .map(|r| {
                let (o, d) = (r.origin.truncate().as_dvec3(), r.direction.truncate().as_dvec3());
                reference.trace(o, d, f64::from(r.origin.w), f64::from(r.direction.w))
            })
            .collect();
        let count = |want: fn(&SceneVerdict) -> bool| verdicts.iter().filter(|v| want(v)).count();
        let (solid, ambiguous) =
            (count(|v| matches!(v, SceneVerdict::Hit { .. })), count(|v| *v == SceneVerdict::Ambiguous));
        for set_text in ["rust", "glsl"] {
            let out = render_scene(&ctx, &scene, set_text);
            assert!(hit_count(&out) > 0, "{label}: nothing seen");
            let wrong: Vec<String> = (verdicts.iter().zip(&out.hit_ids).enumerate())
                .filter(|(_, (v, &id))| match v {
                    SceneVerdict::Hit { .. } => id == NO_HIT_ID,
                    SceneVerdict::Miss => id != NO_HIT_ID,
                    SceneVerdict::Ambiguous => false,
                })
                .map(|(i, (v, id))| format!("pixel {i}: reference {v:?}, {set_text} {id:#x}"))
                .collect();
            assert!(
                wrong.is_empty(),
                "{label}: {set_text} against the reference: {} wrong, {:?}",
                wrong.len(),
                &wrong[..wrong.len().min(5)]
            );
        }
        eprintln!("{label}: {solid} rays on the surface, {ambiguous} undecided of {}", verdicts.len());
        assert!(solid > 1000, "{label}: the surface is seen ({solid} rays)");
        assert!(ambiguous * 10 < solid, "{label}: {ambiguous} undecided rays against {solid} decided on the surface");
    }
}
