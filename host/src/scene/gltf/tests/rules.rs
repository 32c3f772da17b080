//! The validator's rules of `rules` and the primitive restart value of `geometry`: a model
//! that morphs, is skinned and animated loads, and each rule broken alone is refused in one
//! line naming the object.

use super::{document, floats, load_text, refused, SQUARE};

/// One buffer: the square (view 0), key times 0 and 1 (view 1), key times 1 and 0.5 (view 2),
/// an identity matrix (view 3), each vertex's joints (view 4: joint 0, or `joint` at vertex
/// 2), and weights 1 (view 5). Accessors: 0 positions, 1 and 2 the times, 3 two translations
/// (the square's first two corners), 4 the inverse bind matrices (`matrices` of them), 5
/// joints, 6 weights.
fn rigged(joint: u8, matrices: usize, json: &str) -> String {
    let mut bytes = floats(&SQUARE);
    bytes.extend([0.0f32, 1.0, 1.0, 0.5].iter().flat_map(|t| t.to_le_bytes()));
    let identity = glam::Mat4::IDENTITY.to_cols_array();
    bytes.extend((0..2).flat_map(|_| identity).flat_map(f32::to_le_bytes));
    bytes.extend((0..4u8).flat_map(|v| [if v == 2 { joint } else { 0 }, 0, 0, 0]));
    bytes.extend((0..4).flat_map(|_| [1.0f32, 0.0, 0.0, 0.0]).flat_map(f32::to_le_bytes));
    let views = r#"{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 8},
        {"buffer": 0, "byteOffset": 56, "byteLength": 8}, {"buffer": 0, "byteOffset": 64, "byteLength": 128},
        {"buffer": 0, "byteOffset": 192, "byteLength": 16}, {"buffer": 0, "byteOffset": 208, "byteLength": 64}"#;
    let accessors = format!(
        r#"{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
        {{"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]}},
        {{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0.5], "max": [1]}},
        {{"bufferView": 0, "componentType": 5126, "count": 2, "type": "VEC3"}},
        {{"bufferView": 3, "componentType": 5126, "count": {matrices}, "type": "MAT4"}},
        {{"bufferView": 4, "componentType": 5121, "count": 4, "type": "VEC4"}},
        {{"bufferView": 5, "componentType": 5126, "count": 4, "type": "VEC4"}}"#
    );
    document(&bytes, &format!(r#""bufferViews": [{views}], "accessors": [{accessors}], {json}"#))
}

/// A mesh of one target and its default weight, a skin of two joints, and an animation moving
/// joint 1 and the mesh's weight: all as glTF asks.
const PRIMITIVE: &str =
    r#"{"attributes": {"POSITION": 0, "JOINTS_0": 5, "WEIGHTS_0": 6}, "targets": [{"POSITION": 0}]}"#;
const MESHES: &str = r#""meshes": [{"primitives": [PRIMITIVE], "weights": [0.5]}]"#;
const NODES: &str = r#""nodes": [{"mesh": 0, "skin": 0}, {"children": [2]}, {}], "scenes": [{"nodes": [0, 1]}]"#;
const SKINS: &str = r#""skins": [{"joints": [1, 2], "inverseBindMatrices": 4}]"#;
const ANIMATIONS: &str = r#""animations": [{"samplers": [{"input": 1, "output": 3}, {"input": 1, "output": 1}],
    "channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}},
                 {"sampler": 1, "target": {"node": 0, "path": "weights"}}]}]"#;

fn whole(meshes: &str, nodes: &str, skins: &str, animations: &str) -> String {
    let meshes = meshes.replace("PRIMITIVE", PRIMITIVE);
    format!("{meshes}, {nodes}, {skins}, {animations}")
}

fn valid() -> String {
    whole(MESHES, NODES, SKINS, ANIMATIONS)
}

/// The valid rigged model, whole: what the fuzz target's rig edits start from.
pub(crate) fn rigged_model() -> String {
    rigged(1, 2, &valid())
}

#[test]
fn a_model_that_morphs_is_skinned_and_animated_loads() {
    let model = load_text(&rigged(1, 2, &valid())).expect("a valid rigged model");
    assert_eq!(model.file.objects.len(), 1);
}

#[test]
fn each_rule_on_morphs_skins_and_animations_broken_alone_is_refused() {
    let plain = r#"{"attributes": {"POSITION": 0}}"#;
    let cases: [(String, &str); 9] = [
        (
            rigged(1, 2, &whole(&MESHES.replace("[PRIMITIVE]", &format!("[PRIMITIVE, {plain}]")), NODES, SKINS, ANIMATIONS)),
            "mesh 0 primitive 1 has 0 morph targets, its primitive 0 1",
        ),
        (rigged(1, 2, &whole(&MESHES.replace("[0.5]", "[0.5, 0.5]"), NODES, SKINS, ANIMATIONS)), "mesh 0 has 2 weights for its 1 morph targets"),
        (
            rigged(1, 2, &whole(MESHES, &NODES.replace(r#""skin": 0}"#, r#""skin": 0, "weights": [1, 0]}"#), SKINS, ANIMATIONS)),
            "node 0 has 2 weights for its mesh's 1 morph targets",
        ),
        (rigged(2, 2, &valid()), "JOINTS_0 (accessor 5) names joint 2, past the 2 joints of skin 0 of node 0"),
        (rigged(1, 1, &valid()), "skin 0 has 1 inverse bind matrices (accessor 4) for its 2 joints"),
        (
            rigged(1, 2, &whole(MESHES, NODES, SKINS, &ANIMATIONS.replace(r#""input": 1, "output": 3"#, r#""input": 2, "output": 3"#))),
            "animation 0 sampler 0: input (accessor 2) key 1 is at 0.5 s, not after key 0's 1 s",
        ),
        (
            rigged(1, 2, &whole(MESHES, NODES, SKINS, &ANIMATIONS.replace(r#""output": 1}"#, r#""output": 3}"#))),
            "animation 0 channel 1: its sampler 1's output (accessor 3) is Vec3 of F32",
        ),
        (
            rigged(1, 2, &whole(MESHES, NODES, SKINS, &ANIMATIONS.replace(r#""output": 3}"#, r#""output": 3, "interpolation": "CUBICSPLINE"}"#))),
            "animation 0 channel 0: its sampler 0's output (accessor 3) has 2 elements for 2 keys of Translation (it needs 6)",
        ),
        (
            rigged(1, 2, &whole(MESHES, NODES, SKINS, &ANIMATIONS.replace(r#""node": 0, "path": "weights""#, r#""node": 2, "path": "weights""#))),
            "animation 0 channel 1 drives the weights of node 2, which has no morph targets",
        ),
    ];
    // What the `gltf` crate's validation does not check, and would panic on.
    let astray = ANIMATIONS.replace(r#""node": 2, "path": "translation""#, r#""node": 7, "path": "translation""#);
    refused(
        &rigged(1, 2, &whole(MESHES, NODES, SKINS, &astray)),
        "animation 0 channel 0 targets node 7, past its 3 nodes",
    );
    let pathless = ANIMATIONS.replace(r#""path": "translation""#, r#""path": "shear""#);
    refused(
        &rigged(1, 2, &whole(MESHES, NODES, SKINS, &pathless)),
        "animation 0 channel 0 targets a path glTF does not define",
    );
    for (text, why) in &cases {
        refused(text, why);
    }
}

/// Cameras, accessors and materials: an orthographic camera of xmag 0, a float accessor
/// marked normalized, a texture read through a TEXCOORD set the primitive lacks, and an index
/// equal to the primitive restart value of its type (reached only with more vertices than 255:
/// below, the vertex it would name is past the mesh, which is said first).
#[test]
fn cameras_accessors_materials_and_indices_that_break_a_rule_are_refused() {
    let base = rigged(1, 2, &valid());
    let ortho = r#""cameras": [{"type": "orthographic", "orthographic": {"xmag": 0, "ymag": 1, "znear": 0, "zfar": 10}}], "meshes""#;
    refused(&base.replacen(r#""meshes""#, ortho, 1), "camera 0 is orthographic with an xmag of 0");
    let far = ortho.replace(r#""xmag": 0"#, r#""xmag": 1"#).replace(r#""zfar": 10"#, r#""zfar": 0"#);
    refused(&base.replacen(r#""meshes""#, &far, 1), "camera 0 has a zfar of 0, not beyond its znear of 0");
    let normalized = base.replacen(
        r#""componentType": 5126, "count": 4, "type": "VEC3""#,
        r#""componentType": 5126, "normalized": true, "count": 4, "type": "VEC3""#,
        1,
    );
    refused(&normalized, "accessor 0 is normalized but of F32");
    let textured = r#""textures": [{"source": 0}], "images": [{"uri": "absent.png"}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}}], "meshes""#;
    let text = base.replacen(r#""meshes""#, textured, 1).replacen(r#""targets""#, r#""material": 0, "targets""#, 1);
    refused(&text, "mesh 0 primitive 0 has no TEXCOORD_1, which its material 0's baseColorTexture reads");
    refused(&fan(255), "indices (accessor 1) hold 255, the primitive restart value of 8-bit indices");
    load_text(&fan(254)).expect("a fan of 256 vertices indexed by bytes below 255");
}

/// A fan of 256 vertices on a circle, its last triangle's last corner given by `last` (a byte).
fn fan(last: u8) -> String {
    let corners: Vec<[f32; 3]> =
        (0..256).map(|k| (k as f32 / 256.0 * std::f32::consts::TAU).sin_cos()).map(|(s, c)| [c, s, 0.0]).collect();
    let mut bytes = floats(&corners);
    bytes.extend([0, 1, 2, 0, 2, last, 0, 0]);
    let rest = r#""bufferViews": [{"buffer": 0, "byteLength": 3072}, {"buffer": 0, "byteOffset": 3072, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 256, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5121, "count": 6, "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#;
    document(&bytes, rest)
}
