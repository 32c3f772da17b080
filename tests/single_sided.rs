//! Single-sided meshes (glTF materials that are not `doubleSided`) on lavapipe, validation on:
//! a primary ray (here a probe's) that meets a triangle from behind passes through it in both
//! sets and in the f64 reference, and a mirrored instance turns its front over, as glTF
//! decides the front by the winding in world space. A shadow ray sees both faces.

use glam::DVec3;
use twinray_host::probe::{probe, ProbeRay};
use twinray_host::reference::scene::{SceneReference, SceneVerdict};
use twinray_host::scene::{MeshFiles, Scene};
use twinray_shared::bindings::{MASK_OCCLUDER, NO_HIT};
use twinray_tests::{set, validated_context, SCENE_HEAD};

/// A closed box mesh, single-sided, scaled by `scale` (a negative axis mirrors it).
fn boxed(scale: [f32; 3]) -> Scene {
    let [x, y, z] = scale;
    let object = "[shapes.b]\nkind = \"mesh\"\nbuiltin = \"box\"\n[[objects]]\nshape = \"b\"\nmaterial = \"m\"\n";
    let text = format!("name = \"single-sided\"\n{SCENE_HEAD}{object}scale = [{x}, {y}, {z}]\nsingle_sided = true\n");
    Scene::parse(&text, "single-sided.toml", MeshFiles::Builtin).expect("scene")
}

/// Rays along -z, -x and +y: three from outside the box towards its centre, three from its
/// centre outwards.
fn rays() -> Vec<ProbeRay> {
    let directions = [DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y];
    // A little off the axis, across it: t is still the face's distance.
    let off = |d: DVec3| DVec3::new(0.01, 0.02, 0.03).reject_from_normalized(d);
    let outside = directions.map(|d| (-d * 5.0 + off(d), d));
    let inside = directions.map(|d| (off(d), d));
    outside
        .into_iter()
        .chain(inside)
        .map(|(o, d)| ProbeRay { origin: o.as_vec3().extend(0.0), direction: d.as_vec3().extend(100.0) })
        .collect()
}

/// Plain, the box's outward faces are fronts: a ray from outside stops at the near face
/// (t 4.5), one from inside passes every face. Mirrored, every face is a front from inside: a
/// ray from outside passes the near face and stops at the far one (t 5.5), one from inside
/// stops at the first face (t 0.5). A shadow ray stops at the first face it meets either way.
#[test]
fn back_faces_of_single_sided_meshes_are_culled_in_both_sets_and_the_reference() {
    let ctx = validated_context();
    let rays = rays();
    let first_face = [4.5, 0.5];
    for (scale, want) in [([1.0, 1.0, 1.0], [Some(4.5), None]), ([-1.0, 1.0, 1.0], [Some(5.5), Some(0.5)])] {
        let scene = boxed(scale);
        let reference = SceneReference::new(&scene).expect("reference");
        for set_text in ["rust", "glsl"] {
            let out = probe(&ctx, &scene, &set(set_text), &rays, 0, 1).expect("probe");
            for (i, (ray, result)) in rays.iter().zip(&out.results).enumerate() {
                let side = i / 3;
                let label = format!("{set_text}, scale {scale:?}, ray {i} from {}", ["outside", "inside"][side]);
                let near = |t: f64, want: f64| (t - want).abs() < 1e-3;
                let got = (result.ids.w != NO_HIT).then_some(f64::from(result.normal_t.w));
                assert_eq!(got.is_some(), want[side].is_some(), "{label}: the set, t {got:?}");
                if let (Some(t), Some(w)) = (got, want[side]) {
                    assert!(near(t, w), "{label}: the set's t {t}, not {w}");
                }
                let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
                match (reference.trace(o, d, 0.0, 100.0), want[side]) {
                    (SceneVerdict::Hit { t, .. }, Some(w)) => assert!(near(t, w), "{label}: the reference's t {t}"),
                    (SceneVerdict::Miss, None) => {}
                    (verdict, _) => panic!("{label}: the reference says {verdict:?}"),
                }
                let shadow = reference.trace_masked(o, d, (0.0, 100.0), MASK_OCCLUDER);
                let SceneVerdict::Hit { t, .. } = shadow else {
                    panic!("{label}: the reference's shadow ray, {shadow:?}")
                };
                assert!(near(t, first_face[side]), "{label}: the shadow ray stops at {t}");
            }
        }
    }
}
