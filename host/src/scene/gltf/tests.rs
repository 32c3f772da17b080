//! glTF documents written here, each testing one rule of `load`; the models no one here made
//! are tests/assimp.rs's.

use super::*;
use base64::Engine as _;

mod clips;
mod instancing;
mod lights;
mod posed;
mod quantized;
mod rigs;
pub(crate) mod rules;
mod scale;
mod several;

/// A square of two triangles in z = 0, four vertices.
const SQUARE: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

/// A glTF file of one buffer (`bytes`, as a data URI), with `rest` (the JSON members after
/// "buffers": accessors, bufferViews, meshes, nodes, scenes, ...).
fn document(bytes: &[u8], rest: &str) -> String {
    let data = base64::engine::general_purpose::STANDARD.encode(bytes);
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{data}"}}], {rest}}}"#,
        bytes.len()
    )
}

fn floats(v: &[[f32; 3]]) -> Vec<u8> {
    v.iter().flatten().flat_map(|f| f.to_le_bytes()).collect()
}

/// The square's positions (view 0, accessor 0) and, when given, indices of `component`
/// (5121, 5123 or 5125) as view 1, accessor 1; `mesh` is the primitive's extra members.
fn square(indices: Option<(&[u32], u32)>, nodes: &str, mesh: &str) -> String {
    let mut bytes = floats(&SQUARE);
    let mut views = format!(r#"{{"buffer": 0, "byteOffset": 0, "byteLength": {}}}"#, bytes.len());
    let mut accessors =
        r#"{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}"#
            .to_string();
    let mut primitive = r#""attributes": {"POSITION": 0}"#.to_string();
    if let Some((list, component)) = indices {
        let start = bytes.len();
        for &i in list {
            match component {
                5121 => bytes.push(i as u8),
                5123 => bytes.extend((i as u16).to_le_bytes()),
                _ => bytes.extend(i.to_le_bytes()),
            }
        }
        while !bytes.len().is_multiple_of(4) {
            bytes.push(0);
        }
        views += &format!(r#", {{"buffer": 0, "byteOffset": {start}, "byteLength": {}}}"#, bytes.len() - start);
        accessors += &format!(
            r#", {{"bufferView": 1, "componentType": {component}, "count": {}, "type": "SCALAR"}}"#,
            list.len()
        );
        primitive += r#", "indices": 1"#;
    }
    document(
        &bytes,
        &format!(
            r#""bufferViews": [{views}], "accessors": [{accessors}], "meshes": [{{"primitives": [{{{primitive}{mesh}}}]}}], "nodes": [{nodes}], "scenes": [{{"nodes": [0]}}]"#
        ),
    )
}

fn load_text(text: &str) -> Result<Model, String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.gltf");
    std::fs::write(&path, text).unwrap();
    load(&path, None)
}

const ONE_NODE: &str = r#"{"mesh": 0}"#;

#[test]
fn every_index_type_and_none_give_the_same_triangles() {
    let list = [0, 1, 2, 0, 2, 3];
    let unindexed = load_text(&square(None, ONE_NODE, r#", "mode": 6"#)).unwrap(); // a fan
    let mut triangles = Vec::new();
    for component in [5121, 5123, 5125] {
        let model = load_text(&square(Some((&list, component)), ONE_NODE, "")).unwrap();
        let mesh = model.meshes.values().next().unwrap();
        let corners: Vec<[f32; 3]> =
            mesh.indices.iter().map(|&i| mesh.vertices[i as usize].position.truncate().into()).collect();
        triangles.push(corners);
    }
    assert!(triangles.windows(2).all(|w| w[0] == w[1]), "{triangles:?}");
    let fan = unindexed.meshes.values().next().unwrap();
    assert_eq!(fan.indices.len(), 6, "a fan of four vertices is two triangles");
    // Without NORMAL, flat normals: the square faces +z.
    assert!(fan.vertices.iter().all(|v| v.normal.truncate() == glam::Vec3::Z), "{:?}", fan.vertices);
}

#[test]
fn nodes_compose_their_transforms_and_share_their_mesh() {
    let nodes = r#"{"translation": [10, 0, 0], "children": [1, 2]}, {"mesh": 0, "scale": [2, 2, 2]}, {"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,5,0,1]}"#;
    let model = load_text(&square(None, nodes, "")).unwrap();
    assert_eq!(model.meshes.len(), 1, "one mesh shape for both nodes");
    assert_eq!(model.file.objects.len(), 2);
    let at = |o: &ObjectDesc, p: glam::Vec3| o.transform().transform_point3(p);
    let [a, b] = [&model.file.objects[0], &model.file.objects[1]];
    assert_eq!(at(a, glam::Vec3::ONE), glam::Vec3::new(12.0, 2.0, 2.0), "child scaled, then parent moved");
    assert_eq!(at(b, glam::Vec3::ZERO), glam::Vec3::new(10.0, 5.0, 0.0));
    assert_eq!(a.shape, b.shape);
}

#[test]
fn a_camera_node_is_the_camera_and_sets_the_aspect() {
    let nodes = r#"{"children": [1, 2]}, {"mesh": 0}, {"camera": 0, "translation": [0.5, 0.5, 4]}"#;
    let text = square(None, nodes, "").replacen(
        r#""scenes""#,
        r#""cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 2.0, "znear": 0.1}}], "scenes""#,
        1,
    );
    let model = load_text(&text).unwrap();
    let c = model.file.camera;
    assert_eq!(c.eye, [0.5, 0.5, 4.0]);
    assert!((c.fov_y_degrees - 0.5f32.to_degrees()).abs() < 1e-4);
    assert_eq!((model.file.image.width, model.file.image.height), (960, 480));
    assert!(c.target[2] < c.eye[2], "looks down its -z");
}

#[test]
fn without_camera_or_lights_the_model_is_framed_and_lit() {
    let model = load_text(&square(None, ONE_NODE, "")).unwrap();
    let c = model.file.camera;
    assert_eq!(c.target, [0.5, 0.5, 0.0], "the bounds' centre");
    assert!(c.eye[2] > 0.0, "from in front");
    assert_eq!(model.file.lights.len(), 2, "key and fill");
    assert!(model.file.materials.contains_key(DEFAULT_MATERIAL));
    assert!(model.ignored.is_empty(), "{:?}", model.ignored);
}

#[test]
fn what_is_not_modelled_is_named() {
    let text = square(None, ONE_NODE, r#", "material": 0"#).replacen(
        r#""scenes""#,
        r#""materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}, "alphaMode": "BLEND"}], "extensionsUsed": ["EXT_made_up"], "scenes""#,
        1,
    );
    let model = load_text(&text).unwrap();
    let ignored: Vec<&str> = model.ignored.iter().map(String::as_str).collect();
    for want in
        ["alpha mode BLEND (alpha-tested at 0.5)", "extension EXT_made_up", "metallic-roughness (shaded as diffuse)"]
    {
        assert!(ignored.contains(&want), "{ignored:?}");
    }
    let red = model.file.materials.values().next().unwrap();
    assert!(matches!(red, MaterialDesc::Cutout { color: [1.0, 0.0, 0.0], threshold: 0.5, .. }), "{red:?}");
}

/// MASK is an alpha-tested cutout at the material's cutoff, of its base colour's alpha;
/// OPAQUE, and a cutoff of 0, are plain diffuse.
/// The square of one node, its primitive of `material` (a glTF material's JSON), loaded.
fn square_of(material: &str) -> Model {
    let text = square(None, ONE_NODE, r#", "material": 0"#).replacen(
        r#""scenes""#,
        &format!(r#""materials": [{material}], "scenes""#),
        1,
    );
    load_text(&text).unwrap()
}

#[test]
fn alpha_modes_become_alpha_tested_cutouts() {
    let with = |material: &str| square_of(material).file.materials.into_values().next().unwrap();
    let mask = with(
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.7]}, "alphaMode": "MASK", "alphaCutoff": 0.3}"#,
    );
    assert!(
        matches!(mask, MaterialDesc::Cutout { pattern: CutoutPattern::Alpha, threshold: 0.3, opacity: 0.7, .. }),
        "{mask:?}"
    );
    assert!(matches!(with(r#"{"alphaMode": "MASK"}"#), MaterialDesc::Cutout { threshold: 0.5, .. }));
    assert!(matches!(with(r#"{"alphaMode": "MASK", "alphaCutoff": 0}"#), MaterialDesc::Diffuse { .. }));
    assert!(matches!(with(r#"{"alphaMode": "OPAQUE"}"#), MaterialDesc::Diffuse { .. }));
}

/// The emissive factor, times KHR_materials_emissive_strength, is the material's emission; a
/// black factor (glTF's default) emits nothing.
#[test]
fn emissive_factors_become_emission() {
    let with = |material: &str| {
        let text = square(None, ONE_NODE, r#", "material": 0"#).replacen(
            r#""scenes""#,
            &format!(r#""materials": [{material}], "scenes""#),
            1,
        );
        load_text(&text).unwrap().file.materials.into_values().next().unwrap()
    };
    let emission = |m: MaterialDesc| match m {
        MaterialDesc::Diffuse { emission, .. } | MaterialDesc::Cutout { emission, .. } => emission,
        other => panic!("{other:?}"),
    };
    let strong = emission(with(
        r#"{"emissiveFactor": [1, 0.5, 0], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}"#,
    ))
    .expect("emission");
    assert_eq!((strong.color, strong.intensity), ([1.0, 0.5, 0.0], 4.0));
    let masked = emission(with(r#"{"emissiveFactor": [0, 0, 1], "alphaMode": "MASK"}"#)).expect("emission");
    assert_eq!((masked.color, masked.intensity), ([0.0, 0.0, 1.0], 1.0));
    assert!(emission(with(r#"{"emissiveFactor": [0, 0, 0]}"#)).is_none());
    assert!(emission(with("{}")).is_none());
}

/// KHR_materials_unlit shows the base colour and texture whatever the lights: a black
/// surface that emits them, alpha-tested as any other.
#[test]
fn unlit_materials_emit_their_base_colour() {
    let text = square(None, ONE_NODE, r#", "material": 0"#).replacen(
        r#""scenes""#,
        r#""materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 0.5]}, "emissiveFactor": [1, 1, 1],
            "alphaMode": "MASK", "extensions": {"KHR_materials_unlit": {}}}],
          "extensionsUsed": ["KHR_materials_unlit"], "extensionsRequired": ["KHR_materials_unlit"], "scenes""#,
        1,
    );
    let model = load_text(&text).expect("an unlit material");
    let MaterialDesc::Cutout { color, emission: Some(emission), opacity, .. } =
        model.file.materials.into_values().next().unwrap()
    else {
        panic!("not an alpha-tested material with emission")
    };
    assert_eq!((color, opacity), ([0.0; 3], 0.5));
    assert_eq!(
        (emission.color, emission.intensity),
        ([0.2, 0.4, 0.6], 1.0),
        "the base colour, not the emissive factor"
    );
    assert!(!model.ignored.iter().any(|i| i.contains("unlit") || i.contains("metallic")), "{:?}", model.ignored);
}

/// `load` refuses `text`, saying `why`.
fn refused(text: &str, why: &str) {
    match load_text(text) {
        Ok(_) => panic!("loaded, though {why}"),
        Err(e) => assert!(e.contains(why), "{e:?} does not say {why:?}"),
    }
}

#[test]
fn malformed_models_are_refused_with_their_fault_named() {
    let good = square(Some((&[0, 1, 2, 0, 2, 3], 5123)), ONE_NODE, "");
    refused(
        &good.replacen("{\"asset\"", "{\"extensionsRequired\": [\"KHR_draco_mesh_compression\"], \"asset\"", 1),
        "requires the extension KHR_draco_mesh_compression",
    );
    refused(&square(Some((&[0, 1, 9], 5123)), ONE_NODE, ""), "indexes vertex 9, past its 4 vertices");
    refused(&good.replacen(r#""count": 4"#, r#""count": 5"#, 1), "reaches past the end of its buffer view");
    refused(&good.replacen(r#""type": "VEC3""#, r#""type": "VEC2""#, 1), "which glTF does not allow there");
    refused(&good.replacen(r#""byteLength": 60"#, r#""byteLength": 600"#, 1), "fewer than its byteLength");
    // The crate's reader panicked on a stride shorter than the element.
    let strided = good.replacen(
        r#""byteOffset": 0, "byteLength": 48}"#,
        r#""byteOffset": 0, "byteLength": 48, "byteStride": 8}"#,
        1,
    );
    refused(&strided, "has a byteStride of 8, less than its 12-byte elements");
    let misaligned =
        good.replacen(r#""count": 4, "type": "VEC3""#, r#""count": 3, "byteOffset": 2, "type": "VEC3""#, 1);
    refused(
        &misaligned,
        "starts at byte 2 of buffer view 0 (byte 2 of its buffer), not a multiple of its 4-byte components",
    );
    let no_primitives = good.replacen(r#""meshes": ["#, r#""meshes": [{"primitives": []}, "#, 1);
    refused(&no_primitives.replace(r#""mesh": 0"#, r#""mesh": 1"#), "mesh 0 has no primitives");
    refused(&square(None, r#"{"mesh": 0, "children": [0]}"#, ""), "has a cycle");
    refused(&square(None, ONE_NODE, r#", "mode": 1"#), "places no triangles (ignored: Lines primitives)");
    refused("{\"asset\": {\"version\": \"2.0\"}, \"scenes\": [{\"nodes\": 7}]}", "not a valid glTF 2.0 file");
    refused("not json at all", "not a valid glTF 2.0 file");
    let far = floats(&[[0.0; 3], [1e30, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3]]);
    let text = square(None, ONE_NODE, "");
    let square_data = base64::engine::general_purpose::STANDARD.encode(floats(&SQUARE));
    refused(
        &text.replace(&square_data, &base64::engine::general_purpose::STANDARD.encode(far)),
        "coordinates must be finite, at most",
    );
}

/// `extras` may be any JSON value, wherever the schema allows it (the crate read only objects
/// until its `extras` feature was on), and so may an unknown extension's object.
#[test]
fn extras_of_every_json_type_load() {
    let good = square(Some((&[0, 1, 2, 0, 2, 3], 5123)), ONE_NODE, "");
    for value in ["[1, 2]", "3", "\"text\"", "null", "true", "{\"a\": 1}"] {
        let extras = format!(r#""extras": {value}, "#);
        let places = [
            good.replacen("{\"asset\": {", &format!("{{{extras}\"asset\": {{{extras}"), 1),
            good.replacen("{\"buffer\": 0,", &format!("{{{extras}\"buffer\": 0,"), 1),
            good.replacen("{\"bufferView\": 0,", &format!("{{{extras}\"bufferView\": 0,"), 1),
            good.replacen("{\"primitives\": [{", &format!("{{{extras}\"primitives\": [{{{extras}"), 1),
            good.replacen(
                "{\"mesh\": 0}",
                &format!("{{{extras}\"extensions\": {{\"EXT_unknown\": {value}}}, \"mesh\": 0}}"),
                1,
            ),
            good.replacen("{\"nodes\": [0]}", &format!("{{{extras}\"nodes\": [0]}}"), 1),
        ];
        for (i, text) in places.iter().enumerate() {
            assert_ne!(text, &good, "place {i} of extras {value}");
            load_text(text).unwrap_or_else(|e| panic!("extras {value} at place {i}: {e}"));
        }
    }
}

/// The square with vertex 2 moved to (2, 2, 0) by a sparse accessor: `sparse` is its JSON.
fn sparse_square(sparse: &str) -> String {
    sparse_document([2, 0], 1, sparse)
}

/// The square with `count` (1 or 2) sparse elements at `indices` (the second is padding for
/// one), each moving its vertex to (2, 2, 0).
fn sparse_square_at(indices: [u16; 2], count: usize) -> String {
    let sparse = format!(
        r#"{{"count": {count}, "indices": {{"bufferView": 1, "componentType": 5123}}, "values": {{"bufferView": 2}}}}"#
    );
    sparse_document(indices, count, &sparse)
}

fn sparse_document(indices: [u16; 2], values: usize, sparse: &str) -> String {
    let mut bytes = floats(&SQUARE);
    bytes.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    bytes.extend(floats(&vec![[2.0, 2.0, 0.0]; values]));
    let length = 12 * values;
    document(
        &bytes,
        &format!(
            r#""bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 4}}, {{"buffer": 0, "byteOffset": 52, "byteLength": {length}}}],
            "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [2, 2, 0], "sparse": {sparse}}}],
            "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "mode": 6}}]}}], "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}]"#
        ),
    )
}

#[test]
fn sparse_accessors_are_read_and_checked() {
    let good = r#"{"count": 1, "indices": {"bufferView": 1, "componentType": 5123}, "values": {"bufferView": 2}}"#;
    let model = load_text(&sparse_square(good)).unwrap();
    let mesh = model.meshes.values().next().unwrap();
    let moved = mesh.vertices.iter().any(|v| v.position.truncate() == glam::Vec3::new(2.0, 2.0, 0.0));
    assert!(moved, "{:?}", mesh.vertices);
    refused(&sparse_square(&good.replace(r#""count": 1"#, r#""count": 0"#)), "0 sparse elements");
    refused(
        &sparse_square(&good.replace(r#""count": 1"#, r#""count": 3"#)),
        "reaches past the end of its buffer view 1",
    );
    // Index 2 is the square's third vertex: 4 lies past its four; 2 then 0 does not rise.
    refused(&sparse_square_at([4, 0], 1), "sparse index 0 is 4, past its 4 elements");
    refused(&sparse_square_at([2, 0], 2), "sparse index 1 is 0, not above the one before");
    assert!(load_text(&sparse_square_at([1, 2], 2)).is_ok(), "two rising indices load");
}

/// The glTF validator's rules on node graphs and attributes (`graph`, `geometry`): a file that
/// breaks one is refused with the node or accessor named, where it used to render one reading.
#[test]
fn node_graphs_and_attributes_that_break_the_validators_rules_are_refused() {
    let two_parents = r#"{"children": [2]}, {"children": [2]}, {"mesh": 0}"#;
    let text =
        square(None, two_parents, "").replace(r#""scenes": [{"nodes": [0]}]"#, r#""scenes": [{"nodes": [0, 1]}]"#);
    refused(&text, "node 2 is a child of both node 0 and node 1");
    let both = r#"{"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "translation": [1, 0, 0]}"#;
    refused(&square(None, both, ""), "node 0 has both a matrix and a translation");
    let child_listed = r#"{"children": [1]}, {"mesh": 0}"#;
    let text = square(None, child_listed, "").replace(r#""scenes": [{"nodes": [0]}]"#, r#""scenes": [{"nodes": [1]}]"#);
    refused(&text, "scene 0 lists node 1, a child of node 0");
    // NORMAL with 3 elements for 4 vertices: which normal would the fourth get?
    let short = r#", {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}]"#;
    let text = square(None, ONE_NODE, "")
        .replacen(r#""max": [1, 1, 0]}]"#, &format!(r#""max": [1, 1, 0]}}{short}"#), 1)
        .replacen(r#""attributes": {"POSITION": 0}"#, r#""attributes": {"POSITION": 0, "NORMAL": 1}"#, 1);
    refused(&text, "NORMAL has 3 elements, its POSITION 4");
}

/// A scale of zero on an axis hides a node and its children (glTF's way), and the rest of the
/// model renders; a model all of whose nodes are hidden places nothing.
#[test]
fn a_node_scaled_to_zero_is_not_drawn() {
    let nodes = r#"{"children": [1, 2]}, {"mesh": 0, "scale": [1, 0, 1], "children": [3]}, {"mesh": 0, "translation": [3, 0, 0]}, {"mesh": 0}"#;
    let model = load_text(&square(None, nodes, "")).expect("a hidden node is valid glTF");
    assert_eq!(model.file.objects.len(), 1, "only node 2 is drawn: {:?}", model.file.objects);
    assert_eq!(model.file.objects[0].name.as_deref(), Some("node 2"));
    assert!(model.ignored.iter().any(|i| i.contains("scaled to zero")), "{:?}", model.ignored);
    refused(&square(None, r#"{"mesh": 0, "scale": [0, 0, 0]}"#, ""), "places no triangles");
}

/// A material that is not `doubleSided` (glTF's default, and the default material's) makes its
/// objects single-sided; a `doubleSided` one does not; neither is named as not modelled.
#[test]
fn single_sided_materials_make_single_sided_objects() {
    let with = square_of;
    assert!(with("{}").file.objects[0].single_sided);
    assert!(!with(r#"{"doubleSided": true}"#).file.objects[0].single_sided);
    assert!(load_text(&square(None, ONE_NODE, "")).unwrap().file.objects[0].single_sided, "the default material");
    assert!(with("{}").ignored.iter().all(|i| !i.contains("sided")), "{:?}", with("{}").ignored);
}

/// A mesh of 16,384 one-triangle primitives that share one POSITION and one NORMAL accessor
/// of all their vertices, each with its own indices (as exporters write a mesh's primitives): each
/// primitive keeps its own 3 vertices, and loading takes time in the file's size. Reading the
/// shared accessor whole for each primitive took 9.4 s here (0.05 s read once, `shared`).
#[test]
fn a_shared_vertex_accessor_is_read_once() {
    let n = 16_384usize;
    let mut bytes: Vec<u8> = (0..n)
        .flat_map(|i| {
            let x = i as f32;
            [x, 0.0, 0.0, x + 1.0, 0.0, 0.0, x, 1.0, 0.0]
        })
        .flat_map(f32::to_le_bytes)
        .collect();
    let positions = bytes.len();
    bytes.extend((0..3 * n).flat_map(|_| [0.0f32, 0.0, 1.0]).flat_map(f32::to_le_bytes));
    bytes.extend((0..3 * n as u32).flat_map(u32::to_le_bytes));
    let vec3 = |view: usize, bounds: &str| {
        format!(r#"{{"bufferView": {view}, "componentType": 5126, "count": {}, "type": "VEC3"{bounds}}}"#, 3 * n)
    };
    let mut accessors = vec![vec3(0, &format!(r#", "min": [0, 0, 0], "max": [{n}, 1, 0]"#)), vec3(1, "")];
    accessors.extend((0..n).map(|i| {
        format!(r#"{{"bufferView": 2, "byteOffset": {}, "componentType": 5125, "count": 3, "type": "SCALAR"}}"#, 12 * i)
    }));
    let primitives: Vec<String> =
        (0..n).map(|i| format!(r#"{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": {}}}"#, i + 2)).collect();
    let views = format!(
        r#"{{"buffer": 0, "byteLength": {positions}}}, {{"buffer": 0, "byteOffset": {positions}, "byteLength": {positions}}},
        {{"buffer": 0, "byteOffset": {}, "byteLength": {}}}"#,
        2 * positions,
        bytes.len() - 2 * positions
    );
    let rest = format!(
        r#""bufferViews": [{views}], "accessors": [{}], "meshes": [{{"primitives": [{}]}}], "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}]"#,
        accessors.join(","),
        primitives.join(",")
    );
    let started = std::time::Instant::now();
    let model = load_text(&document(&bytes, &rest)).expect("the model");
    let took = started.elapsed().as_secs_f64();
    assert_eq!(model.meshes.len(), n);
    let corner = |m: &MeshData| m.vertices.iter().map(|v| v.position.x).fold(f32::INFINITY, f32::min);
    for (k, mesh) in model.meshes.values().enumerate().step_by(997) {
        assert_eq!(mesh.vertices.len(), 3, "primitive {k} keeps only its own vertices");
        assert!(mesh.vertices.iter().all(|v| v.normal.z == 1.0), "primitive {k}: the file's normals");
        assert!(corner(mesh) >= 0.0 && mesh.indices.iter().all(|&i| i < 3), "{mesh:?}");
    }
    let spans: std::collections::BTreeSet<u32> = model.meshes.values().map(|m| corner(m) as u32).collect();
    assert_eq!(spans.len(), n, "each primitive its own triangle");
    // Ample room for a loaded machine: the quadratic reading took 190 times the linear one.
    assert!(took < 3.0, "loading took {took:.2} s");
}
