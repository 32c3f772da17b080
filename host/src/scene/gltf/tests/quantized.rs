//! KHR_mesh_quantization: a square whose positions, normals and texture coordinates are
//! integers, and whose morph target's displacements are, loads to the vertices of its float
//! twin, placed by its node's scale; a file that does not declare the extension, or an
//! integer normal not normalized, is refused naming the accessor.

use super::{document, floats, load_text, SQUARE};
use crate::scene::file::ObjectDesc;
use crate::scene::gltf::Model;
use glam::{Vec3, Vec4};

/// How the square's attributes are stored: component type, normalized, and each element's
/// bytes.
struct Stored {
    position: (u32, bool, Vec<u8>),
    normal: (u32, bool, Vec<u8>),
    uv: (u32, bool, Vec<u8>),
    /// The morph target's position displacements (weight 0.5 on the mesh).
    target: (u32, bool, Vec<u8>),
}

fn shorts(v: &[i32]) -> Vec<u8> {
    v.iter().flat_map(|&c| (c as i16).to_le_bytes()).collect()
}

/// Each element padded to 4 bytes, as glTF asks of vertex attributes.
fn padded(bytes: &[u8], element: usize) -> Vec<u8> {
    let stride = element.div_ceil(4) * 4;
    bytes.chunks(element).flat_map(|e| e.iter().copied().chain(std::iter::repeat_n(0, stride - element))).collect()
}

fn model(stored: &Stored, extensions: &str, scale: f32) -> Result<Model, String> {
    let mut bytes = Vec::new();
    let (mut views, mut accessors) = (Vec::new(), Vec::new());
    let size = |component: u32| match component {
        5120 | 5121 => 1,
        5122 | 5123 => 2,
        _ => 4,
    };
    let mut add = |(component, normalized, data): &(u32, bool, Vec<u8>), kind: &str, n: usize, bounds: &str| {
        let element = n * size(*component);
        let data = padded(data, element);
        let stride = element.div_ceil(4) * 4;
        views.push(format!(
            r#"{{"buffer": 0, "byteOffset": {}, "byteLength": {}, "byteStride": {stride}}}"#,
            bytes.len(),
            data.len()
        ));
        bytes.extend(data);
        accessors.push(format!(
            r#"{{"bufferView": {}, "componentType": {component}, "normalized": {normalized}, "count": 4, "type": "{kind}"{bounds}}}"#,
            views.len() - 1
        ));
        accessors.len() - 1
    };
    let max = if stored.position.0 == 5126 { 1.0 } else { 1000.0 };
    let p = add(&stored.position, "VEC3", 3, &format!(r#", "min": [0, 0, 0], "max": [{max}, {max}, 0]"#));
    let n = add(&stored.normal, "VEC3", 3, "");
    let uv = add(&stored.uv, "VEC2", 2, "");
    let t = add(&stored.target, "VEC3", 3, r#", "min": [0, 0, 0], "max": [0, 0, 1]"#);
    let rest = format!(
        r#""bufferViews": [{}], "accessors": [{}], {extensions}
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {p}, "NORMAL": {n}, "TEXCOORD_0": {uv}}},
                      "targets": [{{"POSITION": {t}}}]}}], "weights": [0.5]}}],
        "nodes": [{{"mesh": 0, "scale": [{scale}, {scale}, {scale}]}}], "scenes": [{{"nodes": [0]}}]"#,
        views.join(", "),
        accessors.join(", ")
    );
    load_text(&document(&bytes, &rest))
}

/// The square's corners in the world, their normals and texture coordinates, in order.
fn corners(model: &Model) -> Vec<(Vec3, Vec3, Vec4)> {
    let object: &ObjectDesc = &model.file.objects[0];
    let mesh = &model.meshes[&object.shape];
    let world = object.transform();
    mesh.vertices.iter().map(|v| (world.transform_point3(v.position.truncate()), v.normal.truncate(), v.uv)).collect()
}

const DECLARED: &str =
    r#""extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],"#;

fn floats_twin() -> Stored {
    let uv: Vec<u8> = SQUARE.iter().flat_map(|c| [c[0], c[1]]).flat_map(f32::to_le_bytes).collect();
    Stored {
        position: (5126, false, floats(&SQUARE)),
        normal: (5126, false, floats(&[[0.0, 0.0, 1.0]; 4])),
        uv: (5126, false, uv),
        target: (5126, false, floats(&[[0.0, 0.0, 1.0]; 4])),
    }
}

/// Positions as unsigned shorts in thousandths (the node scales them back), normals as
/// normalized bytes, texture coordinates as normalized shorts, displacements as shorts.
fn quantized_twin() -> Stored {
    let corner = |c: &[f32; 3]| c.map(|x| (x * 1000.0) as u16);
    Stored {
        position: (5123, false, SQUARE.iter().flat_map(corner).flat_map(u16::to_le_bytes).collect()),
        normal: (5120, true, [0u8, 0, 127].repeat(4)),
        uv: (
            5122,
            true,
            shorts(&SQUARE.iter().flat_map(|c| [c[0] as i32 * 32767, c[1] as i32 * 32767]).collect::<Vec<_>>()),
        ),
        target: (5122, false, shorts(&[0, 0, 1000].repeat(4))),
    }
}

#[test]
fn a_quantized_square_loads_as_its_float_twin() {
    let float = model(&floats_twin(), "", 1.0).expect("the float square");
    let quantized = model(&quantized_twin(), DECLARED, 0.001).expect("the quantized square");
    let (a, b) = (corners(&float), corners(&quantized));
    assert_eq!(a.len(), b.len());
    for ((pa, na, ua), (pb, nb, ub)) in a.iter().zip(&b) {
        assert!((*pa - *pb).length() < 1e-6, "position {pa} against {pb}");
        assert!(pa.z > 0.49 && pa.z < 0.51, "the target's displacement at weight 0.5: {pa}");
        assert!((*na - *nb).length() < 1e-6, "normal {na} against {nb}");
        assert!((*ua - *ub).length() < 1e-6, "texture coordinates {ua} against {ub}");
    }
}

#[test]
fn integers_are_refused_where_the_file_does_not_declare_the_extension_or_gltf_forbids_them() {
    let e = model(&quantized_twin(), "", 0.001).map(|_| ()).expect_err("loaded undeclared");
    assert!(e.contains("POSITION (accessor 0) is Vec3 of U16") && e.contains("does not allow"), "{e}");
    let mut unnormalized = quantized_twin();
    unnormalized.normal.1 = false;
    let e = model(&unnormalized, DECLARED, 0.001).map(|_| ()).expect_err("loaded");
    assert!(e.contains("NORMAL (accessor 1) is I8 not normalized"), "{e}");
    let mut unsigned = quantized_twin();
    unsigned.target = (5123, false, [0u16, 0, 1000].repeat(4).iter().flat_map(|c| c.to_le_bytes()).collect());
    let e = model(&unsigned, DECLARED, 0.001).map(|_| ()).expect_err("loaded");
    assert!(e.contains("target 0 POSITION (accessor 3) is Vec3 of U16"), "{e}");
}
