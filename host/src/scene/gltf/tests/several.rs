//! A file's animations play as glTF-Sample-Viewer starts them: together, each that drives no
//! node property an animation already played drives; one that does is named, not played.

use super::{document, floats, SQUARE};
use crate::scene::gltf::{load_at, Model, Playing};
use glam::{Mat4, Vec3};

/// Three squares (nodes 0, 1, 2) and four LINEAR animations: 0 moves node 0 (keys at 0.5 and
/// 1.5 s), 1 moves node 1 (0.5 and 3 s), 2 moves node 0 again (so it is not played), 3 scales
/// node 0 (its translation is 0's, its scale no one else's: played).
fn four_animations() -> String {
    let mut bytes = floats(&SQUARE);
    bytes.extend([0.5f32, 1.5, 0.5, 3.0].iter().flat_map(|t| t.to_le_bytes()));
    bytes.extend(floats(&[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])); // animation 0
    bytes.extend(floats(&[[0.0, 0.0, 0.0], [0.0, 5.0, 0.0]])); // animation 1
    bytes.extend(floats(&[[9.0, 9.0, 9.0], [9.0, 9.0, 9.0]])); // animation 2
    bytes.extend(floats(&[[1.0, 1.0, 1.0], [3.0, 3.0, 3.0]])); // animation 3
    let view = |k: usize, offset: usize, length: usize| {
        format!(r#"{{"buffer": 0, "byteOffset": {offset}, "byteLength": {length}}}{}"#, if k < 6 { ", " } else { "" })
    };
    let views: String = [(48, 8), (56, 8), (64, 24), (88, 24), (112, 24), (136, 24)]
        .iter()
        .enumerate()
        .map(|(k, &(offset, length))| view(k + 1, offset, length))
        .collect();
    let channel = |input: usize, output: usize, node: usize, path: &str| {
        format!(
            r#"{{"samplers": [{{"input": {input}, "output": {output}}}], "channels": [{{"sampler": 0, "target": {{"node": {node}, "path": "{path}"}}}}]}}"#
        )
    };
    let animations = [
        channel(1, 3, 0, "translation"),
        channel(2, 4, 1, "translation"),
        channel(1, 5, 0, "translation"),
        channel(1, 6, 0, "scale"),
    ]
    .join(", ");
    let rest = format!(
        r#""bufferViews": [{{"buffer": 0, "byteLength": 48}}, {views}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0.5], "max": [1.5]}},
                      {{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0.5], "max": [3.0]}},
                      {{"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"}},
                      {{"bufferView": 4, "componentType": 5126, "count": 2, "type": "VEC3"}},
                      {{"bufferView": 5, "componentType": 5126, "count": 2, "type": "VEC3"}},
                      {{"bufferView": 6, "componentType": 5126, "count": 2, "type": "VEC3"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
        "nodes": [{{"mesh": 0}}, {{"mesh": 0}}, {{"mesh": 0, "translation": [0, 0, 4]}}],
        "animations": [{animations}],
        "scenes": [{{"nodes": [0, 1, 2]}}]"#
    );
    document(&bytes, &rest)
}

fn at(model: &Model, node: usize) -> Mat4 {
    let name = format!("node {node}");
    let object = model.file.objects.iter().find(|o| o.name.as_deref() == Some(name.as_str())).unwrap();
    Mat4::from_cols_array(&object.matrix.unwrap())
}

#[test]
fn animations_driving_different_properties_play_together_and_a_conflicting_one_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.gltf");
    std::fs::write(&path, four_animations()).unwrap();
    let model = load_at(&path, None, Playing { time: 1.0, ..Playing::default() }).expect("a model of four animations");
    // At 1 s: animation 0 halfway (x = 1), animation 3 halfway (scale 2), animation 1 a fifth
    // of its way (y = 1); node 2 at rest; animation 2 (node 0's translation again) not played.
    let want = [
        (0, Mat4::from_scale_rotation_translation(Vec3::splat(2.0), glam::Quat::IDENTITY, Vec3::X)),
        (1, Mat4::from_translation(Vec3::Y)),
        (2, Mat4::from_translation(4.0 * Vec3::Z)),
    ];
    for (node, matrix) in want {
        assert!(at(&model, node).abs_diff_eq(matrix, 1e-6), "node {node}: {} against {matrix}", at(&model, node));
    }
    assert!(
        model.ignored.iter().any(|i| i == "animation 2 (driving what an animation played drives)"),
        "{:?}",
        model.ignored
    );
    // The clip runs to the last key of those played, 3 s: from 1 s at 24 frames a second, 49.
    assert_eq!(model.clip.as_ref().map(|c| c.frames()), Some(49));
    // Past their end (1.5 s) animations 0 and 3 loop, as glTF-Sample-Viewer loops each
    // animation over its own length: at 2.5 s they are 1 s into their second cycle, as at 1 s
    // (x = 1, scale 2), while animation 1 (3 s long) goes on (y = 4).
    let later = load_at(&path, None, Playing { time: 2.5, ..Playing::default() }).unwrap();
    assert!(at(&later, 0).abs_diff_eq(want[0].1, 1e-6), "{}", at(&later, 0));
    assert!(at(&later, 1).w_axis.truncate().abs_diff_eq(4.0 * Vec3::Y, 1e-6), "{}", at(&later, 1));
}

/// `KHR_animation_pointer` channels (a material's colour here) target no node; the `gltf`
/// crate cannot read them, so they are left out and the extension named: the file is not
/// refused, and the channels on nodes beside them play. Their keys still count toward their
/// animation's length, as glTF-Sample-Viewer counts them: animation 0, whose node keys end at
/// 1.5 s, lasts 3 s with a pointer channel keyed to 3 s, so at 2.5 s it holds its last node key
/// (x = 2) where alone it would be 1 s into its second cycle (x = 1); animation 3 (scale, 1.5
/// s) is.
#[test]
fn animation_pointer_channels_are_left_out_and_the_node_channels_play() {
    let mut root: serde_json::Value = serde_json::from_str(&four_animations()).unwrap();
    root["extensionsUsed"] = serde_json::json!(["KHR_animation_pointer"]);
    root["materials"] = serde_json::json!([{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]}}]);
    let pointer = "/materials/0/pbrMetallicRoughness/baseColorFactor";
    let channel = serde_json::json!({"sampler": 0, "target": {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": pointer}}}});
    root["animations"][1]["channels"].as_array_mut().unwrap().insert(0, channel.clone());
    // Animation 0's second sampler: accessor 2's keys (0.5 and 3 s), accessor 4's values.
    root["animations"][0]["samplers"].as_array_mut().unwrap().push(serde_json::json!({"input": 2, "output": 4}));
    let mut longer = channel;
    longer["sampler"] = 1.into();
    root["animations"][0]["channels"].as_array_mut().unwrap().push(longer);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.gltf");
    std::fs::write(&path, root.to_string()).unwrap();
    let model =
        load_at(&path, None, Playing { time: 1.0, ..Playing::default() }).expect("a model animating a material");
    assert!(at(&model, 1).w_axis.truncate().abs_diff_eq(Vec3::Y, 1e-6), "{}", at(&model, 1));
    assert!(model.ignored.contains("extension KHR_animation_pointer"), "{:?}", model.ignored);
    let later = load_at(&path, None, Playing { time: 2.5, ..Playing::default() }).unwrap();
    let want = Mat4::from_scale_rotation_translation(Vec3::splat(2.0), glam::Quat::IDENTITY, 2.0 * Vec3::X);
    assert!(at(&later, 0).abs_diff_eq(want, 1e-6), "{}", at(&later, 0));
}
