//! Morph targets and skins posed on the host (`deform`): a node's weights, else its mesh's,
//! else the animation's at the time drawn, move the vertices by their targets; a skin moves
//! them by their joints, the node's own transform ignored; each posing node gets a mesh of its
//! own. Checked on squares written here and on assimp's SimpleSkin, by hand from glTF's
//! formulas.

use super::{document, floats, load_text, SQUARE};
use crate::scene::gltf::{load_at, Playing, ASSIMP_TEST_MODELS};
use glam::{Mat4, Vec3};

/// The square (accessor 0) with one morph target lifting every corner by 2 in z (accessor 1);
/// `mesh` and `nodes` are the mesh's and the nodes' extra JSON, `animation` the document's
/// animations (accessor 2 holds key times 0 and 1, accessor 3 weights 0 and 1).
fn morphed(mesh: &str, nodes: &str, animations: &str) -> String {
    let mut bytes = floats(&SQUARE);
    bytes.extend(floats(&[[0.0, 0.0, 2.0]; 4]));
    bytes.extend([0.0f32, 1.0, 0.0, 1.0].iter().flat_map(|f| f.to_le_bytes()));
    let rest = format!(
        r#""bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 48}},
                          {{"buffer": 0, "byteOffset": 96, "byteLength": 8}}, {{"buffer": 0, "byteOffset": 104, "byteLength": 8}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 2], "max": [0, 0, 2]}},
                      {{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]}},
                      {{"bufferView": 3, "componentType": 5126, "count": 2, "type": "SCALAR"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "targets": [{{"POSITION": 1}}]}}]{mesh}}}],
        "nodes": [{nodes}], "scenes": [{{"nodes": [0]}}]{animations}"#
    );
    document(&bytes, &rest)
}

/// The z of every vertex of the mesh the object named `node` draws.
fn heights(model: &crate::scene::gltf::Model, node: &str) -> Vec<f32> {
    let object = model.file.objects.iter().find(|o| o.name.as_deref() == Some(node)).expect("the node's object");
    model.meshes[&object.shape].vertices.iter().map(|v| v.position.z).collect()
}

/// Every vertex position of `mesh`.
fn points(mesh: &crate::scene::mesh::MeshData) -> Vec<Vec3> {
    mesh.vertices.iter().map(|v| v.position.truncate()).collect()
}

#[test]
fn a_node_morphs_by_its_weights_else_its_meshes() {
    let cases = [
        (r#", "weights": [0.25]"#, r#"{"mesh": 0}"#, 0.5),
        (r#", "weights": [0.25]"#, r#"{"mesh": 0, "weights": [0.75]}"#, 1.5),
        (r#", "weights": [0.25]"#, r#"{"mesh": 0, "weights": [0]}"#, 0.0),
        ("", r#"{"mesh": 0}"#, 0.0),
    ];
    for (mesh, node, z) in cases {
        let model = load_text(&morphed(mesh, node, "")).expect("a morphed square");
        assert!(heights(&model, "node 0").iter().all(|&h| h == z), "mesh{mesh}, node {node}");
        assert_eq!(model.meshes.len(), 1, "only the mesh drawn is built: {:?}", model.meshes.keys());
        assert!(!model.ignored.iter().any(|i| i.contains("morph")), "{:?}", model.ignored);
    }
}

/// Two nodes of one mesh, one with weights of its own: each draws its own triangles.
#[test]
fn each_posing_node_draws_a_mesh_of_its_own() {
    let nodes = r#"{"children": [1, 2]}, {"mesh": 0, "weights": [1]}, {"mesh": 0}"#;
    let model = load_text(&morphed("", nodes, "")).unwrap();
    assert!(heights(&model, "node 1").iter().all(|&h| h == 2.0));
    assert!(heights(&model, "node 2").iter().all(|&h| h == 0.0));
    assert_eq!(model.meshes.len(), 2, "{:?}", model.meshes.keys());
}

/// The animation's weights at the time drawn win over the node's.
#[test]
fn an_animated_weight_is_posed_at_the_time_drawn() {
    let animations = r#", "animations": [{"samplers": [{"input": 2, "output": 3}],
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}]"#;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.gltf");
    std::fs::write(&path, morphed("", r#"{"mesh": 0, "weights": [0.5]}"#, animations)).unwrap();
    for (time, z) in [(0.0, 0.0), (0.25, 0.5), (1.0, 2.0), (3.0, 2.0)] {
        let model = load_at(&path, None, Playing { time, ..Playing::default() }).expect("an animated morph");
        let got = heights(&model, "node 0");
        assert!(got.iter().all(|&h| (h - z).abs() < 1e-6), "at {time} s: {got:?}, want {z}");
    }
}

/// The square skinned to two joints: corners 0 and 1 to joint 0 (node 1, at rest), corner 2 to
/// joint 1 (node 2, moved by 4 in x), corner 3 half to each. The skinned node's own
/// translation (100 in y) does not move it.
#[test]
fn a_skin_moves_each_vertex_by_its_weighted_joints_and_ignores_its_node() {
    let mut bytes = floats(&SQUARE);
    bytes.extend([0u8, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0]);
    let weights: [[f32; 4]; 4] =
        [[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.5, 0.5, 0.0, 0.0]];
    bytes.extend(weights.iter().flatten().flat_map(|f| f.to_le_bytes()));
    let rest = r#""bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 16},
                                  {"buffer": 0, "byteOffset": 64, "byteLength": 64}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5121, "count": 4, "type": "VEC4"},
                      {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC4"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}, "mode": 6}]}],
        "skins": [{"joints": [1, 2]}],
        "nodes": [{"mesh": 0, "skin": 0, "translation": [0, 100, 0]}, {}, {"translation": [4, 0, 0]}],
        "scenes": [{"nodes": [0, 1, 2]}]"#;
    let model = load_text(&document(&bytes, rest)).expect("a skinned square");
    let object = &model.file.objects[0];
    assert_eq!(object.matrix.map(|m| Mat4::from_cols_array(&m)), Some(Mat4::IDENTITY));
    let got = points(&model.meshes[&object.shape]);
    // Flat normals give each triangle corners of its own: the same four points, repeated.
    let want = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(5.0, 1.0, 0.0), Vec3::new(2.0, 1.0, 0.0)];
    assert!(got.iter().all(|p| want.contains(p)) && want.iter().all(|w| got.contains(w)), "{got:?}");
    assert!(!model.ignored.iter().any(|i| i.contains("skin") || i.contains("JOINTS")), "{:?}", model.ignored);
}

/// assimp's SimpleSkin: a strip of ten vertices up y from 0 to 2, weighted from joint 0 (node
/// 1, one unit up) at the bottom to joint 1 (node 2, its child) at the top, both with inverse
/// bind matrices of -0.5 in x and -1 in y; the animation turns joint 1 about z, a quarter
/// turn at 1 s. By glTF's formula, at 0 s every vertex moves by -0.5 in x; at 1 s the bottom
/// one still does, the top one turns a quarter about joint 1's origin, and the middle one,
/// half of each, goes halfway between.
#[test]
fn simple_skin_bends_where_its_joints_turn() {
    let path = std::path::Path::new(ASSIMP_TEST_MODELS).join("simple_skin/simple_skin.gltf");
    let at = |time: f32| {
        let model = load_at(&path, None, Playing { time, ..Playing::default() }).expect("SimpleSkin");
        points(&model.meshes[&model.file.objects[0].shape])
    };
    // Each of the strip's vertices posed, as a point of the mesh within `tolerance`.
    let has = |points: &[Vec3], want: [f32; 2], tolerance: f32| {
        points.iter().any(|p| (*p - Vec3::new(want[0], want[1], 0.0)).length() < tolerance)
    };
    let rest = at(0.0);
    for want in [[-0.5, 0.0], [0.5, 0.0], [-0.5, 1.0], [-0.5, 2.0], [0.5, 2.0]] {
        assert!(has(&rest, want, 1e-6), "at 0 s, no vertex at {want:?}: {rest:?}");
    }
    // The file's quaternion at 1 s is (0, 0, 0.707, 0.707), a quarter turn to 1e-4.
    let bent = at(1.0);
    for (want, which) in [([-0.5, 0.0], "bottom"), ([-1.0, 0.5], "top"), ([-0.25, 0.75], "middle")] {
        assert!(has(&bent, want, 1e-3), "at 1 s, the {which} vertex is not at {want:?}: {bent:?}");
    }
}
