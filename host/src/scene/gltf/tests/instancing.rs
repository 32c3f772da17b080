//! `EXT_mesh_gpu_instancing`: a node's copies become objects of their own, each placed by its
//! translation, rotation and scale before the node's transform; accessors that break the
//! extension's rules are refused naming the node.

use super::{document, floats, load_text, refused, SQUARE};
use glam::{Mat4, Quat, Vec3};

/// The square (accessor 0), three translations (accessor 1) and three rotations as
/// normalized shorts (accessor 2: none, a quarter turn about z, a half turn about y), placed
/// by one node translated to x = 10 whose instancing attributes are `attributes`.
fn copies(attributes: &str) -> String {
    let mut bytes = floats(&SQUARE);
    bytes.extend(floats(&[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0]]));
    let h = (32767.0 * std::f32::consts::FRAC_1_SQRT_2) as i16;
    let rotations: [[i16; 4]; 3] = [[0, 0, 0, 32767], [0, 0, h, h], [0, 32767, 0, 0]];
    bytes.extend(rotations.iter().flatten().flat_map(|c| c.to_le_bytes()));
    let rest = format!(
        r#""extensionsUsed": ["EXT_mesh_gpu_instancing"],
        "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 84, "byteLength": 24}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}},
                      {{"bufferView": 2, "componentType": 5122, "normalized": true, "count": 3, "type": "VEC4"}},
                      {{"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
        "nodes": [{{"mesh": 0, "translation": [10, 0, 0], "extensions": {{"EXT_mesh_gpu_instancing": {{"attributes": {attributes}}}}}}}],
        "scenes": [{{"nodes": [0]}}]"#
    );
    document(&bytes, &rest)
}

#[test]
fn each_copy_is_an_object_placed_by_its_own_transform_then_the_nodes() {
    let model = load_text(&copies(r#"{"TRANSLATION": 1, "ROTATION": 2}"#)).expect("an instanced node");
    let placed: Vec<Mat4> = model.file.objects.iter().map(|o| Mat4::from_cols_array(&o.matrix.unwrap())).collect();
    let node = Mat4::from_translation(Vec3::X * 10.0);
    let want = [
        node,
        node * Mat4::from_rotation_translation(Quat::from_rotation_z(std::f32::consts::FRAC_PI_2), Vec3::X * 2.0),
        node * Mat4::from_rotation_translation(Quat::from_rotation_y(std::f32::consts::PI), Vec3::Y * 3.0),
    ];
    assert_eq!(placed.len(), 3, "{:?}", model.file.objects);
    for (k, (got, want)) in placed.iter().zip(want).enumerate() {
        assert!(got.abs_diff_eq(want, 1e-4), "copy {k}: {got} against {want}");
        assert_eq!(model.file.objects[k].name.as_deref(), Some(format!("node 0 copy {k}").as_str()));
    }
    assert!(model.ignored.iter().all(|i| !i.contains("EXT_mesh_gpu_instancing")), "{:?}", model.ignored);
    // Required as well as used: the same copies (the `gltf` crate's validation alone refuses
    // a required extension it has no feature for).
    let required = copies(r#"{"TRANSLATION": 1, "ROTATION": 2}"#).replacen(
        r#""extensionsUsed": ["EXT_mesh_gpu_instancing"],"#,
        r#""extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"],"#,
        1,
    );
    let again = load_text(&required).expect("instancing required");
    assert_eq!(again.file.objects.len(), 3);
}

#[test]
fn instancing_accessors_that_break_the_extensions_rules_are_refused() {
    refused(
        &copies(r#"{"TRANSLATION": 1, "SCALE": 3}"#),
        "node 0: EXT_mesh_gpu_instancing: accessor 3 has 2 elements, its other attributes 3",
    );
    refused(
        &copies(r#"{"TRANSLATION": 2}"#),
        "TRANSLATION (accessor 2) is Vec4 of I16, which glTF does not allow there",
    );
    refused(&copies(r#"{"_ID": 1}"#), "has none of TRANSLATION, ROTATION and SCALE");
    refused(&copies(r#"{"ROTATION": 9}"#), "ROTATION names accessor 9, past the list");
}

/// With KHR_mesh_quantization listed, translations may be shorts (here unnormalized, padded
/// to 8 bytes each): the copies land where float translations put them; without it listed,
/// the shorts are refused.
#[test]
fn quantized_translations_place_the_copies_where_the_extension_is_listed() {
    let mut bytes = floats(&SQUARE);
    let shorts: [[i16; 4]; 2] = [[0, 0, 0, 0], [2, 0, 5, 0]];
    bytes.extend(shorts.iter().flatten().flat_map(|c| c.to_le_bytes()));
    let with = |used: &str| {
        document(
            &bytes,
            &format!(
                r#"{used} "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 16, "byteStride": 8}}],
                "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                              {{"bufferView": 1, "componentType": 5122, "count": 2, "type": "VEC3"}}],
                "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
                "nodes": [{{"mesh": 0, "extensions": {{"EXT_mesh_gpu_instancing": {{"attributes": {{"TRANSLATION": 1}}}}}}}}],
                "scenes": [{{"nodes": [0]}}]"#
            ),
        )
    };
    let listed = r#""extensionsUsed": ["EXT_mesh_gpu_instancing", "KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],"#;
    let model = load_text(&with(listed)).expect("quantized translations");
    let placed: Vec<Vec3> =
        model.file.objects.iter().map(|o| Mat4::from_cols_array(&o.matrix.unwrap()).w_axis.truncate()).collect();
    assert_eq!(placed, [Vec3::ZERO, Vec3::new(2.0, 0.0, 5.0)]);
    refused(&with(r#""extensionsUsed": ["EXT_mesh_gpu_instancing"],"#), "TRANSLATION (accessor 1) is Vec3 of I16");
}
