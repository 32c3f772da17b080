//! Rays that reach the whole scene (`FrameUniform::reach`, `scene::reach`): a sphere seen from
//! 5,000 and from 1e6 units renders with both sets alike, and a directional light's occluder
//! 1,500 (300,000) units along the light, out of view, casts its shadow on it. With the fixed
//! reach of 1,000 units these rendered as empty background, unshadowed.

use twinray_host::{RenderOptions, Scene};
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
        let opts = RenderOptions::once(96, 96, 0, 1);
        let reach = scene.frame_uniform(96, 96).reach;
        let extent = scene.file.camera.eye[2];
        assert!(
            reach.x > extent && reach.x < extent * 1.1,
            "{name}: primary rays reach the sphere's far side: {reach}"
        );
        let [rust, glsl] = ["rust", "glsl"].map(|s| twinray_host::render(&ctx, &scene, &set(s), &opts).unwrap());
        let d = twinray_host::compare::diff(&rust, &glsl, scene.file.parity.pixel_threshold);
        let failures = twinray_host::compare::verdict(&d, &scene.file.parity, 96 * 96);
        assert!(failures.is_empty(), "{name}: {failures:?}");
        for out in [&rust, &glsl] {
            assert!(out.written.is_clean(), "{name}: {:?}", out.written);
            let hits = twinray_host::compare::hit_count(out);
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
    let e = Scene::parse(&tiny, "tiny.toml", twinray_host::scene::MeshFiles::Builtin).unwrap_err().to_string();
    assert!(e.contains("object 1 (shape \"blocker\")") && e.contains("f32 cannot resolve it"), "{e}");
}

/// `scene` as if modelled in a unit `s` times smaller: the camera, every placement, grid and
/// light moved `s` times as far, every object `s` times as large (shapes keep their own space,
/// so their materials' patterns scale with them), and point lights `s^2` times as intense so
/// that they light what they lit at the same distance (rect lights' irradiance is their solid
/// angle's, which scaling keeps; directional lights have no distance).
fn scaled(scene: &Scene, s: f32) -> Scene {
    use twinray_host::scene::file::{LightDesc, Scale};
    let (file, source, meshes) = (scene.file.clone(), scene.source.clone(), scene.meshes.clone());
    // The GPU centred as the scene is (on the camera, which moves `s` times as far), or not.
    let mut out =
        Scene { file, source, meshes, animation: None, origin: scene.origin.map(|o| o * s), ray_starts: None };
    let f = &mut out.file;
    let times = |v: &mut [f32; 3]| v.iter_mut().for_each(|x| *x *= s);
    let grow = |scale: &mut Scale| match scale {
        Scale::Uniform(k) => *k *= s,
        Scale::PerAxis(k) => k.iter_mut().for_each(|x| *x *= s),
    };
    times(&mut f.camera.eye);
    times(&mut f.camera.target);
    for o in &mut f.objects {
        times(&mut o.translate);
        grow(&mut o.scale);
    }
    for g in &mut f.grids {
        times(&mut g.origin);
        times(&mut g.spacing);
        grow(&mut g.scale);
    }
    for light in &mut f.lights {
        match light {
            LightDesc::Directional { .. } => {}
            LightDesc::Point { position, intensity, .. } => {
                times(position);
                *intensity *= s * s;
            }
            LightDesc::Rect { center, u, v, .. } => {
                times(center);
                times(u);
                times(v);
            }
        }
    }
    out
}

/// A scene's unit does not change its picture (the near reach once was 0.1 units, and the
/// shadow rays' offset near the origin 1/65536 units, so the same scene modelled 1/100 as large
/// rendered as background, and 1/10,000 as large lost its shadows): each scene and its camera
/// scaled by 10^k, k from -4 to 4, hit the same objects off silhouettes and give the same image
/// within the scene's parity, in both sets. The scene: a rect light's soft shadows, a point
/// light, a checker floor, an emitter and ellipsoids (lights). One scene: lavapipe compiles
/// the pipeline again for each scale (about 7 s each with a cold shader cache; showcase and
/// cutout as well took 4 to 5 minutes in all).
#[test]
fn a_scene_scaled_by_powers_of_ten_renders_the_same_picture() {
    let ctx = validated_context();
    let (width, height) = (96, 54);
    let opts = RenderOptions::once(width, height, 0, 1);
    for name in ["lights"] {
        let scene = Scene::load(Some(name)).unwrap();
        for s in ["rust", "glsl"] {
            let one = twinray_host::render(&ctx, &scene, &set(s), &opts).unwrap();
            assert!(
                twinray_host::compare::hit_count(&one) > u64::from(width * height) / 4,
                "{name}: the scene is in view"
            );
            for k in (-4..=4).filter(|&k| k != 0) {
                let big = scaled(&scene, 10f32.powi(k));
                let reach = big.frame_uniform(width, height).reach;
                let out = twinray_host::render(&ctx, &big, &set(s), &opts).unwrap();
                let d = twinray_host::compare::diff(&one, &out, scene.file.parity.pixel_threshold);
                let failures = twinray_host::compare::verdict(&d, &scene.file.parity, u64::from(width * height));
                eprintln!(
                    "{name} {s} x10^{k}: reach {reach}, rmse {:.6}, {} hit mismatches ({} off silhouette)",
                    d.color.rmse, d.hit_mismatches, d.hit_mismatches_off_silhouette
                );
                assert!(failures.is_empty(), "{name} {s} x10^{k}: {failures:?}");
                assert_eq!(d.hit_mismatches_off_silhouette, 0, "{name} {s} x10^{k}: other objects hit");
            }
        }
    }
}
