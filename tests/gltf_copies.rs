//! `EXT_mesh_gpu_instancing` on lavapipe, validation on: a glTF quad whose node lists its four
//! corners as its copies' translations tiles a 2 x 2 square, and a probe ray through each tile
//! meets its own copy (an object of its own) in both sets and in the f64 reference.

use glam::Vec4;
use twinray_host::probe::{probe, ProbeRay};
use twinray_host::reference::scene::{SceneReference, SceneVerdict};
use twinray_host::scene::Scene;
use twinray_shared::bindings::NO_HIT;
use twinray_tests::gltf::Quad;
use twinray_tests::{set, validated_context};

#[test]
fn each_copy_of_an_instanced_node_is_hit_where_its_translation_puts_it() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let quad = Quad::white();
    // Accessor 0 is the quad's corners: (0, 0), (1, 0), (1, 1), (0, 1), the copies' places.
    let node = r#""extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 0}}}"#;
    let path = quad.write_placed(dir.path(), true, &[node]);
    let scene = Scene::load(Some(path.to_str().unwrap())).expect("the model");
    assert_eq!(scene.file.objects.len(), 4);
    // Through each tile, off its diagonal; then beside the square, where nothing is.
    let tiles = [(0.3, 0.6), (1.3, 0.6), (1.3, 1.6), (0.3, 1.6), (2.5, 0.5)];
    let rays: Vec<ProbeRay> = tiles
        .iter()
        .map(|&(x, y)| ProbeRay { origin: Vec4::new(x, y, 5.0, 0.0), direction: Vec4::new(0.0, 0.0, -1.0, 100.0) })
        .collect();
    let reference = SceneReference::new(&scene).expect("reference");
    for set_text in ["rust", "glsl"] {
        let out = probe(&ctx, &scene, &set(set_text), &rays, 0, 1).expect("probe");
        for (copy, (ray, result)) in rays.iter().zip(&out.results).enumerate() {
            let label = format!("{set_text}, the ray through tile {copy}");
            let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
            let verdict = reference.trace(o, d, 0.0, 100.0);
            if copy == 4 {
                assert_eq!(result.ids.w, NO_HIT, "{label}: the set hit");
                assert!(matches!(verdict, SceneVerdict::Miss), "{label}: the reference says {verdict:?}");
                continue;
            }
            assert_eq!(result.ids.x as usize, copy, "{label}: the set's object ({:?})", result.ids);
            assert!((result.normal_t.w - 5.0).abs() < 1e-3, "{label}: the set's t {}", result.normal_t.w);
            match verdict {
                SceneVerdict::Hit { t, object, .. } => {
                    assert!((t - 5.0).abs() < 1e-3 && object == copy, "{label}: the reference's hit {verdict:?}")
                }
                other => panic!("{label}: the reference says {other:?}"),
            }
        }
    }
}
