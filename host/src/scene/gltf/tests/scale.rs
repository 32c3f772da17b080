//! How large a primitive may be: more than 2^20 triangles load (up to 2^24, `MAX_MESH_TRIANGLES`),
//! and an accessor declaring more elements than three per triangle of that is refused by its
//! count, before any of it is read.

use super::{document, floats, load_text, SQUARE};
use crate::scene::mesh::MAX_MESH_TRIANGLES;

/// The square with normals, its triangle (0, 1, 2) indexed `triangles` times by unsigned
/// bytes, whose accessor declares `count` indices.
fn repeated(triangles: usize, count: usize) -> String {
    let mut bytes = floats(&SQUARE);
    bytes.extend(floats(&[[0.0, 0.0, 1.0]; 4]));
    bytes.extend([0u8, 1, 2].iter().cycle().take(3 * triangles));
    let rest = format!(
        r#""bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 48}},
                           {{"buffer": 0, "byteOffset": 96, "byteLength": {}}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"}},
                      {{"bufferView": 2, "componentType": 5121, "count": {count}, "type": "SCALAR"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}]"#,
        3 * triangles
    );
    document(&bytes, &rest)
}

#[test]
fn a_primitive_of_more_than_a_million_triangles_loads() {
    let triangles = (1 << 20) + 1;
    let model = load_text(&repeated(triangles, 3 * triangles)).expect("a large primitive");
    let mesh = model.meshes.values().next().unwrap();
    assert_eq!(mesh.indices.len(), 3 * triangles);
    // Shared corners (the primitive has normals): the three it names, not three per triangle.
    assert_eq!(mesh.vertices.len(), 3);
}

#[test]
fn an_accessor_of_more_elements_than_the_largest_mesh_is_refused_by_its_count() {
    let past = 3 * MAX_MESH_TRIANGLES + 3;
    let e = load_text(&repeated(1, past)).map(|_| ()).expect_err("loaded");
    assert!(e.contains(&format!("has {past} elements (1 to {})", 3 * MAX_MESH_TRIANGLES)), "{e}");
}
