//! Alpha exactly at the cutoff: a glTF quad whose alpha equals its material's cutoff, by its
//! base colour factor, by its vertex colours and by its texture, rendered by both sets with
//! `compare`. A tie is decided alike in both (the surface is there: alpha >= cutoff), so no
//! pixel differs. Before issue 78 the sets interpolated a vertex colour's alpha of 1 to
//! 0.99999994 in one set and 1 in the other, and a BLEND material of alpha 0.5 (tested at 0.5)
//! had hit mismatches in `compare`.

use std::path::Path;
use twinray_tests::cli::twinray;

/// One way to put the alpha at the cutoff.
struct Tie {
    what: &'static str,
    /// The material's JSON members besides its base colour texture.
    material: &'static str,
    /// Every vertex's COLOR_0.
    vertex: [f32; 4],
    /// Every texel's RGBA, if the quad has a base colour texture.
    texel: Option<[u8; 4]>,
}

const TIES: [Tie; 4] = [
    Tie {
        what: "BLEND, factor 0.5",
        material: r#""alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.2, 0.5]"#,
        vertex: [1.0; 4],
        texel: None,
    },
    Tie {
        what: "MASK 0.25, factor 0.25",
        material: r#""alphaMode": "MASK", "alphaCutoff": 0.25, "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.6, 0.9, 0.25]"#,
        vertex: [1.0; 4],
        texel: None,
    },
    Tie {
        what: "MASK 0.5, vertex alpha 0.5",
        material: r#""alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]"#,
        vertex: [0.8, 0.4, 0.1, 0.5],
        texel: None,
    },
    Tie {
        // 128/255 as f32, the value the sampler returns for a texel's alpha of 128.
        what: "MASK 128/255, texel alpha 128",
        material: r#""alphaMode": "MASK", "alphaCutoff": 0.501960813999176, "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]"#,
        vertex: [1.0; 4],
        texel: Some([200, 120, 40, 128]),
    },
];

/// A model of one quad in `dir` with the alpha of `tie`; its path.
fn model(dir: &Path, tie: &Tie) -> std::path::PathBuf {
    let positions = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
    let uv = [0.0f32, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let mut bytes: Vec<u8> = positions.iter().flat_map(|v| v.to_le_bytes()).collect();
    bytes.extend([0, 1, 2, 0, 2, 3, 0, 0]);
    bytes.extend(uv.iter().flat_map(|v| v.to_le_bytes()));
    bytes.extend([tie.vertex; 4].iter().flatten().flat_map(|v| v.to_le_bytes()));
    std::fs::write(dir.join("quad.bin"), &bytes).unwrap();
    let texture = match tie.texel {
        Some(texel) => {
            image::RgbaImage::from_pixel(8, 8, image::Rgba(texel)).save(dir.join("alpha.png")).unwrap();
            r#", "baseColorTexture": {"index": 0}"#
        }
        None => "",
    };
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {}, "uri": "quad.bin"}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 8}},
                        {{"buffer": 0, "byteOffset": 56, "byteLength": 32}}, {{"buffer": 0, "byteOffset": 88, "byteLength": 64}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5121, "count": 6, "type": "SCALAR"}},
                      {{"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"}},
                      {{"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"}}],
        "images": [{{"uri": "alpha.png"}}], "textures": [{{"source": 0}}],
        "materials": [{{"doubleSided": true, {}{texture}}}}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 2, "COLOR_0": 3}}, "indices": 1, "material": 0}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        bytes.len(),
        tie.material
    );
    let path = dir.join("tie.gltf");
    std::fs::write(&path, gltf).unwrap();
    path
}

#[test]
fn alpha_exactly_at_the_cutoff_is_decided_alike_in_both_sets() {
    for tie in &TIES {
        let dir = tempfile::tempdir().unwrap();
        let path = model(dir.path(), tie);
        let size = ["--width", "160", "--height", "120"];
        let untimed = ["--runs", "1", "--warmup", "0", "--placements", "1"];
        let args = [&["compare", path.to_str().unwrap()][..], &size, &untimed].concat();
        let out = twinray(&args, dir.path());
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{}: {}\n{stdout}", tie.what, String::from_utf8_lossy(&out.stderr));
        assert!(stdout.contains("hit mismatches: 0 (0.000%)"), "{}: {stdout}", tie.what);
        // The surface is there: the quad covers the middle of the picture in both sets.
        let a = image::open(dir.path().join("compare/a.png")).unwrap().to_rgba8();
        let background = *a.get_pixel(0, 0);
        assert_ne!(*a.get_pixel(80, 60), background, "{}: the quad is a hole", tie.what);
    }
}
