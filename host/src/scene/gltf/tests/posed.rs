//! A still picture of an animated model shows its animation at 0 s: a node the
//! animation moves is placed where its keys put it then, not at its rest transform, children
//! included; a node with a matrix cannot be animated.

use super::{document, floats, load_text, refused, SQUARE};
use crate::scene::gltf::{load_at, Playing};
use glam::{Mat4, Vec3};

/// The square (accessor 0) in a node at rest at x = 5 with a child node (the square again,
/// one unit up); one animation (accessors 1 and 2: keys at 0.5 s and 1.5 s) moving the
/// parent's translation by `interpolation`, and with `node` the parent's extra members.
fn animated(interpolation: &str, parent: &str) -> String {
    let nodes = format!(r#"{{"mesh": 0, "children": [1]{parent}}}, {{"mesh": 0, "translation": [0, 1, 0]}}"#);
    keyed(interpolation, "translation", [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], &nodes, "")
}

/// The square (accessor 0) in `nodes`, node 0 animated: its `path` taken by two keys (0.5 s
/// and 1.5 s, accessors 1 and 2) through `values` by `interpolation`; `extra` are more
/// members of the document (cameras, ...).
pub(super) fn keyed(interpolation: &str, path: &str, values: [[f32; 3]; 2], nodes: &str, extra: &str) -> String {
    let mut bytes = floats(&SQUARE);
    bytes.extend([0.5f32, 1.5].iter().flat_map(|t| t.to_le_bytes()));
    bytes.extend(floats(&values));
    let rest = format!(
        r#""bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 8}}, {{"buffer": 0, "byteOffset": 56, "byteLength": 24}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0.5], "max": [1.5]}},
                      {{"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
        "nodes": [{nodes}],
        "animations": [{{"samplers": [{{"input": 1, "output": 2, "interpolation": "{interpolation}"}}],
                         "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "{path}"}}}}]}}],
        "scenes": [{{"nodes": [0]}}]{extra}"#
    );
    document(&bytes, &rest)
}

#[test]
fn a_still_picture_poses_the_first_animation_at_zero_seconds() {
    for interpolation in ["STEP", "LINEAR"] {
        let model = load_text(&animated(interpolation, r#", "translation": [5, 0, 0]"#)).expect("an animated model");
        let placed: Vec<Mat4> = model.file.objects.iter().map(|o| Mat4::from_cols_array(&o.matrix.unwrap())).collect();
        // 0 s is before the first key: the first key's value holds.
        let parent = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0));
        let child = parent * Mat4::from_translation(Vec3::Y);
        let names: Vec<_> = model.file.objects.iter().map(|o| o.name.clone().unwrap()).collect();
        for (name, want) in [("node 0", parent), ("node 1", child)] {
            let k = names.iter().position(|n| n == name).unwrap();
            assert!(placed[k].abs_diff_eq(want, 1e-6), "{interpolation}, {name}: {} against {want}", placed[k]);
        }
        // Keys to 1.5 s at 24 frames a second: a clip of 37 frames from 0 s.
        assert_eq!(model.clip.as_ref().map(|c| (c.start(), c.frames())), Some((0.0, 37)), "{interpolation}");
        assert!(model.ignored.is_empty(), "{:?}", model.ignored);
    }
    let matrix = r#", "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,0,0,1]"#;
    refused(&animated("LINEAR", matrix), "animation 0 channel 0 drives node 0, which has a matrix");
}

/// At a later time each interpolation places the node as its keys say: halfway between the
/// keys for LINEAR, on the earlier key for STEP, on the last key at the animation's end (1.5
/// s) and at the end of a later cycle (3 s); past its end the animation loops as
/// glTF-Sample-Viewer loops it, so 7 s is 1 s into its fifth cycle.
#[test]
fn a_later_time_poses_the_node_between_or_after_its_keys() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.gltf");
    let cases = [
        ("LINEAR", 1.0, [2.5, 3.5, 4.5]),
        ("STEP", 1.0, [1.0, 2.0, 3.0]),
        ("LINEAR", 1.5, [4.0, 5.0, 6.0]),
        ("LINEAR", 3.0, [4.0, 5.0, 6.0]),
        ("LINEAR", 7.0, [2.5, 3.5, 4.5]),
        ("STEP", 7.0, [1.0, 2.0, 3.0]),
    ];
    for (interpolation, time, want) in cases {
        std::fs::write(&path, animated(interpolation, "")).unwrap();
        let model = load_at(&path, None, Playing { time, ..Playing::default() }).expect("an animated model");
        let parent = model.file.objects.iter().find(|o| o.name.as_deref() == Some("node 0")).unwrap();
        let at = Mat4::from_cols_array(&parent.matrix.unwrap()).w_axis.truncate();
        assert!(at.abs_diff_eq(Vec3::from(want), 1e-6), "{interpolation} at {time} s: {at}");
        // From 1 s to the last key at 1.5 s: 13 frames; from 1.5 s on, a still.
        let frames = model.clip.as_ref().map(|c| c.frames());
        assert_eq!(frames, (time < 1.5).then_some(13), "{interpolation} at {time} s");
    }
}
