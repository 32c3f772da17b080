//! Rays leaving a box from inside get its exit as computed: the slab test widens t_far by
//! 1 + 2 gamma_3 (3.6e-7) only where it compares it with t_near (`shapes::boxes`). Returned,
//! the widening made every exit long, by +0.8e-7 to +6.6e-7 relative (median +3.9e-7), in
//! both sets. Here rays start at random points inside a turned, scaled box, in both sets on
//! lavapipe (validation on), and their signed t errors against the f64 reference must be as
//! often short as long, with a median within a tenth of the widening.

use glam::Vec3;
use twinray_host::probe::{probe, ProbeRay};
use twinray_host::reference::scene::{SceneReference, SceneVerdict};
use twinray_host::scene::{MeshFiles, Scene};
use twinray_shared::bindings::NO_HIT;
use twinray_shared::random::SplitMix64;
use twinray_tests::{set, validated_context, SCENE_HEAD};

const BOX: &str = r#"
[shapes.slab]
kind = "box"
size = [2.0, 0.7, 3.0]
[[objects]]
shape = "slab"
material = "m"
translate = [0.5, -0.25, 1.0]
rotate = [20.0, -35.0, 50.0]
scale = [1.0, 1.5, 0.5]
"#;

/// 2 gamma_3, the widening of t_far the exits once carried.
const WIDENING: f64 = 2.0 * 3.0 * 5.960_464_5e-8 / (1.0 - 3.0 * 5.960_464_5e-8);

#[test]
fn box_exits_are_unbiased_in_both_sets() {
    let scene = Scene::parse(&format!("{SCENE_HEAD}{BOX}"), "box-exits.toml", MeshFiles::Builtin).expect("scene");
    let reference = SceneReference::new(&scene).expect("reference");
    let to_world = reference.objects[0].object_to_world.as_mat4();
    let mut rng = SplitMix64(90);
    let mut unit = || Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
    let rays: Vec<ProbeRay> = (0..2000)
        .map(|_| {
            // A point inside, at most 0.9 of the half extents out, in world space.
            let inside = to_world.transform_point3(unit() * 1.8 * Vec3::new(1.0, 0.35, 1.5));
            ProbeRay { origin: inside.extend(0.0), direction: unit().normalize().extend(1e30) }
        })
        .collect();
    let ctx = validated_context();
    for name in ["rust", "glsl"] {
        let out = probe(&ctx, &scene, &set(name), &rays, 0, 1).expect("probe");
        let mut errors: Vec<f64> = Vec::new();
        for (ray, r) in rays.iter().zip(&out.results) {
            let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
            let SceneVerdict::Hit { t, .. } = reference.trace(o, d, 0.0, 1e30) else { continue };
            assert_ne!(r.ids.w, NO_HIT, "{name}: a ray from inside missed the box");
            errors.push((f64::from(r.normal_t.w) - t) / t);
        }
        assert!(errors.len() > 1900, "{name}: only {} exits decided", errors.len());
        errors.sort_by(f64::total_cmp);
        let median = errors[errors.len() / 2];
        let long = errors.iter().filter(|&&e| e > 0.0).count();
        let short = errors.iter().filter(|&&e| e < 0.0).count();
        assert!(median.abs() < 0.1 * WIDENING, "{name}: exits' median signed error {median:e}");
        assert!(4 * long > short && 4 * short > long, "{name}: {long} exits long, {short} short");
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}
