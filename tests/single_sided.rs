//! Single-sided meshes (glTF materials that are not `doubleSided`) on lavapipe, validation on:
//! a primary ray (here a probe's) that meets a triangle from behind passes through it in both
//! sets and in the f64 reference. A mirrored instance keeps the faces it fronts: glTF fronts
//! the clockwise faces in world space of a node whose determinant is negative, which are the
//! counterclockwise ones in object space (its NegativeScaleTest sample). A shadow ray sees
//! both faces.

use glam::DVec3;
use twinray_host::probe::{probe, ProbeRay};
use twinray_host::reference::scene::{SceneReference, SceneVerdict};
use twinray_host::scene::{MeshFiles, Scene};
use twinray_shared::bindings::{MASK_OCCLUDER, NO_HIT};
use twinray_tests::gltf::Quad;
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

/// The box's outward faces are fronts, plain and mirrored alike: a ray from outside stops at
/// the near face (t 4.5), one from inside passes every face. (Flipping a mirrored instance's
/// facing, as a rasterizer flips its front face in window space, would stop the ray from
/// outside at the far face, t 5.5, and the one from inside at the first, t 0.5.) A shadow ray
/// stops at the first face it meets.
#[test]
fn back_faces_of_single_sided_meshes_are_culled_in_both_sets_and_the_reference() {
    let ctx = validated_context();
    let rays = rays();
    let first_face = [4.5, 0.5];
    for scale in [[1.0, 1.0, 1.0], [-1.0, 1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, -1.0, -1.0]] {
        let want = [Some(4.5), None];
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

/// A glTF model's single-sided quad (corners counterclockwise seen from +z) in five nodes,
/// each with the side that faces +z in the world: plain; mirrored across x (its front still
/// faces +z, drawn clockwise there); mirrored across z (its front turns to -z); mirrored
/// through a point; turned half round y (no mirror, its front to -z).
const NODES: [(&str, bool); 5] = [
    (r#""translation": [-6, 0, 0]"#, true),
    (r#""translation": [-2, 0, 0], "scale": [-1, 1, 1]"#, true),
    (r#""translation": [0, 0, 0], "scale": [1, 1, -1]"#, false),
    (r#""translation": [3, 1, 0], "scale": [-1, -1, -1]"#, false),
    (r#""translation": [5, 0, 0], "rotation": [0, 1, 0, 0]"#, false),
];

/// Each node's quad, met at its centre along the z axis from either side, is hit at t 5 from
/// the side its front faces and passed from the other, by both sets and the reference, as
/// glTF's NegativeScaleTest has it.
#[test]
fn a_gltf_node_that_mirrors_keeps_the_faces_gltf_fronts() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let quad = Quad::white();
    let path = quad.write_placed(dir.path(), false, &NODES.map(|(node, _)| node));
    let scene = Scene::load(Some(path.to_str().unwrap())).expect("the model");
    // Near the quads' centres in the world (x of each node's placement, y 0.5, z 0): off the
    // diagonal their two triangles share, where the reference rightly calls a ray ambiguous.
    let centres = [-5.5, -2.5, 0.5, 2.5, 4.5];
    let mut rays = Vec::new();
    for x in centres {
        for z in [5.0f32, -5.0] {
            rays.push(ProbeRay {
                origin: glam::Vec4::new(x + 0.1, 0.7, z, 0.0),
                direction: glam::Vec4::new(0.0, 0.0, -z.signum(), 100.0),
            });
        }
    }
    let reference = SceneReference::new(&scene).expect("reference");
    for set_text in ["rust", "glsl"] {
        let out = probe(&ctx, &scene, &set(set_text), &rays, 0, 1).expect("probe");
        for (i, (ray, result)) in rays.iter().zip(&out.results).enumerate() {
            let ((node, front_to_plus_z), from_plus_z) = (NODES[i / 2], i % 2 == 0);
            let label = format!("{set_text}, node {{{node}}}, ray from {} z", if from_plus_z { "+" } else { "-" });
            let want_hit = front_to_plus_z == from_plus_z;
            let got = (result.ids.w != NO_HIT).then_some(result.normal_t.w);
            assert_eq!(got.is_some(), want_hit, "{label}: the set, t {got:?}");
            assert!(got.is_none_or(|t| (t - 5.0).abs() < 1e-3), "{label}: the set's t {got:?}");
            let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
            match reference.trace(o, d, 0.0, 100.0) {
                SceneVerdict::Hit { t, .. } if want_hit => {
                    assert!((t - 5.0).abs() < 1e-3, "{label}: the reference's t {t}")
                }
                SceneVerdict::Miss if !want_hit => {}
                verdict => panic!("{label}: the reference says {verdict:?}"),
            }
        }
    }
}
