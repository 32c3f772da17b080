//! Small glTF models written for a test: one quad with the material, vertex colours, texture
//! coordinates and texture the test asks for.

use std::path::{Path, PathBuf};

/// A quad's corners (0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0) and what each carries.
pub struct Quad<'a> {
    /// The material's JSON members, the last `pbrMetallicRoughness` left open for the base
    /// colour texture (`doubleSided` is added).
    pub material: &'a str,
    /// Each corner's COLOR_0.
    pub colors: [[f32; 4]; 4],
    /// Each corner's TEXCOORD_0.
    pub uv: [[f32; 2]; 4],
    /// The base colour texture, if any, and its sampler's JSON members.
    pub texture: Option<(&'a image::RgbaImage, &'a str)>,
}

impl Quad<'static> {
    /// A white quad, untextured, white at every corner.
    pub fn white() -> Self {
        Quad {
            material: r#""pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]"#,
            colors: [[1.0; 4]; 4],
            uv: UNIT_UV,
            texture: None,
        }
    }
}

impl Quad<'_> {
    /// Writes the model (`quad.gltf`, `quad.bin`, `texture.png`) into `dir`, the quad
    /// double-sided in one node at the origin; its path.
    pub fn write(&self, dir: &Path) -> PathBuf {
        self.write_placed(dir, true, &[""])
    }

    /// The same with the material `double_sided` or not, in one node per entry of `nodes`: each
    /// the node's JSON members besides its mesh (`"scale": [-1, 1, 1]`).
    pub fn write_placed(&self, dir: &Path, double_sided: bool, nodes: &[&str]) -> PathBuf {
        let positions = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
        let mut bytes: Vec<u8> = positions.iter().flat_map(|v| v.to_le_bytes()).collect();
        bytes.extend([0, 1, 2, 0, 2, 3, 0, 0]);
        bytes.extend(self.uv.iter().flatten().flat_map(|v| v.to_le_bytes()));
        bytes.extend(self.colors.iter().flatten().flat_map(|v| v.to_le_bytes()));
        std::fs::write(dir.join("quad.bin"), &bytes).unwrap();
        let (texture, sampler) = match self.texture {
            Some((image, sampler)) => {
                image.save(dir.join("texture.png")).unwrap();
                (r#", "baseColorTexture": {"index": 0}"#, sampler)
            }
            None => ("", ""),
        };
        let gltf = format!(
            r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {}, "uri": "quad.bin"}}],
            "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 8}},
                            {{"buffer": 0, "byteOffset": 56, "byteLength": 32}}, {{"buffer": 0, "byteOffset": 88, "byteLength": 64}}],
            "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                          {{"bufferView": 1, "componentType": 5121, "count": 6, "type": "SCALAR"}},
                          {{"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"}},
                          {{"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"}}],
            "images": [{{"uri": "texture.png"}}], "samplers": [{{{sampler}}}], "textures": [{{"source": 0, "sampler": 0}}],
            "materials": [{{"doubleSided": {double_sided}, {}{texture}}}}}],
            "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 2, "COLOR_0": 3}}, "indices": 1, "material": 0}}]}}],
            "nodes": [{nodes}], "scenes": [{{"nodes": [{roots}]}}], "scene": 0}}"#,
            bytes.len(),
            self.material,
            nodes = nodes
                .iter()
                .map(|n| format!(r#"{{"mesh": 0{}{n}}}"#, if n.is_empty() { "" } else { ", " }))
                .collect::<Vec<_>>()
                .join(", "),
            roots = (0..nodes.len()).map(|i| i.to_string()).collect::<Vec<_>>().join(", "),
        );
        let path = dir.join("quad.gltf");
        std::fs::write(&path, gltf).unwrap();
        path
    }
}

/// The unit square's texture coordinates at the quad's corners.
pub const UNIT_UV: [[f32; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

/// Writes `strip.gltf` and `strip.bin` into `dir`: one mesh of one primitive per colour, each
/// a unit quad in the z = 0 plane (primitive `p` over x in [1.2 p, 1.2 p + 1], y in [0, 1]),
/// double-sided, of a material of that base colour, placed by one node per translation of
/// `nodes`; its path.
pub fn strip(dir: &Path, colors: &[[f32; 3]], nodes: &[[f32; 3]]) -> PathBuf {
    let mut bytes: Vec<u8> = [0u8, 1, 2, 0, 2, 3].iter().flat_map(|i| u16::from(*i).to_le_bytes()).collect();
    let (mut views, mut accessors) = (vec![r#"{"buffer": 0, "byteLength": 12}"#.to_string()], Vec::new());
    accessors.push(r#"{"bufferView": 0, "componentType": 5123, "count": 6, "type": "SCALAR"}"#.to_string());
    let (mut primitives, mut materials) = (Vec::new(), Vec::new());
    for (p, [r, g, b]) in colors.iter().enumerate() {
        let x = 1.2 * p as f32;
        let corners = [x, 0.0, 0.0, x + 1.0, 0.0, 0.0, x + 1.0, 1.0, 0.0, x, 1.0, 0.0];
        views.push(format!(r#"{{"buffer": 0, "byteOffset": {}, "byteLength": 48}}"#, bytes.len()));
        bytes.extend(corners.iter().flat_map(|v| v.to_le_bytes()));
        accessors.push(format!(
            r#"{{"bufferView": {}, "componentType": 5126, "count": 4, "type": "VEC3", "min": [{x}, 0, 0], "max": [{}, 1, 0]}}"#,
            views.len() - 1,
            x + 1.0
        ));
        primitives.push(format!(r#"{{"attributes": {{"POSITION": {}}}, "indices": 0, "material": {p}}}"#, p + 1));
        materials.push(format!(
            r#"{{"doubleSided": true, "pbrMetallicRoughness": {{"baseColorFactor": [{r}, {g}, {b}, 1]}}}}"#
        ));
    }
    std::fs::write(dir.join("strip.bin"), &bytes).unwrap();
    let nodes: Vec<String> =
        nodes.iter().map(|[x, y, z]| format!(r#"{{"mesh": 0, "translation": [{x}, {y}, {z}]}}"#)).collect();
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {}, "uri": "strip.bin"}}],
        "bufferViews": [{}], "accessors": [{}], "materials": [{}], "meshes": [{{"primitives": [{}]}}],
        "nodes": [{}], "scenes": [{{"nodes": [{}]}}], "scene": 0}}"#,
        bytes.len(),
        views.join(", "),
        accessors.join(", "),
        materials.join(", "),
        primitives.join(", "),
        nodes.join(", "),
        (0..nodes.len()).map(|i| i.to_string()).collect::<Vec<_>>().join(", "),
    );
    let path = dir.join("strip.gltf");
    std::fs::write(&path, gltf).unwrap();
    path
}

/// As [`strip`], placed by one node that a clip moves from the origin to `to` over `seconds`
/// (a LINEAR translation, its keys in the same buffer); its path.
pub fn moving_strip(dir: &Path, colors: &[[f32; 3]], to: [f32; 3], seconds: f32) -> PathBuf {
    let path = strip(dir, colors, &[[0.0; 3]]);
    let mut bytes = std::fs::read(dir.join("strip.bin")).unwrap();
    let at = bytes.len();
    let keys = [0.0, seconds, 0.0, 0.0, 0.0, to[0], to[1], to[2]];
    bytes.extend(keys.iter().flat_map(|v: &f32| v.to_le_bytes()));
    std::fs::write(dir.join("strip.bin"), &bytes).unwrap();
    let (view, accessor) = (colors.len() + 1, colors.len() + 1);
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text
        .replacen(&format!(r#""byteLength": {at}, "uri""#), &format!(r#""byteLength": {}, "uri""#, bytes.len()), 1)
        .replacen(
            r#"], "accessors": ["#,
            &format!(
                r#", {{"buffer": 0, "byteOffset": {at}, "byteLength": 8}}, {{"buffer": 0, "byteOffset": {}, "byteLength": 24}}], "accessors": ["#,
                at + 8
            ),
            1,
        )
        .replacen(
            r#"], "materials": ["#,
            &format!(
                r#", {{"bufferView": {view}, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [{seconds}]}},
                {{"bufferView": {}, "componentType": 5126, "count": 2, "type": "VEC3"}}], "materials": ["#,
                view + 1
            ),
            1,
        )
        .replacen(
            r#""nodes": ["#,
            &format!(
                r#""animations": [{{"channels": [{{"sampler": 0, "target": {{"node": 0, "path": "translation"}}}}],
                "samplers": [{{"input": {accessor}, "output": {}}}]}}], "nodes": ["#,
                accessor + 1
            ),
            1,
        );
    std::fs::write(&path, text).unwrap();
    path
}
