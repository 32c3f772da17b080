//! A large model's cost in host memory: `render` gives the scene's meshes up once the buffers
//! the stages read hold them, so what a model adds to the command's peak stays within 2.5 times
//! its file plus its acceleration structures as built (docs/gltf.md, "Peak memory of a large
//! primitive"). On lavapipe, whose device memory is host memory, a mesh held by the scene as
//! well while its structure is built would pass that by about half the file.

use std::path::{Path, PathBuf};
use twinray_tests::cli::twinray;

/// A flat sheet of `n` x `n` vertices (positions and normals) and 2 (n - 1)^2 triangles of u32
/// indices, written to `dir` as `name`.gltf and .bin; its buffer's length.
fn sheet(dir: &Path, name: &str, n: u32) -> (PathBuf, u64) {
    let at = |i: u32| 2.0 * i as f32 / (n - 1) as f32 - 1.0;
    let floats = |f: &dyn Fn(u32, u32) -> [f32; 3]| -> Vec<u8> {
        (0..n * n).flat_map(|k| f(k % n, k / n)).flat_map(f32::to_le_bytes).collect()
    };
    let mut bytes = floats(&|x, y| [at(x), at(y), 0.0]);
    let positions = bytes.len();
    bytes.extend(floats(&|_, _| [0.0, 0.0, 1.0]));
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            let k = y * n + x;
            bytes.extend([k, k + 1, k + n + 1, k, k + n + 1, k + n].iter().flat_map(|i| i.to_le_bytes()));
        }
    }
    let (vertices, indices) = (n * n, 6 * (n - 1) * (n - 1));
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {len}, "uri": "{name}.bin"}}],
        "bufferViews": [{{"buffer": 0, "byteLength": {positions}}}, {{"buffer": 0, "byteOffset": {positions}, "byteLength": {positions}}},
                        {{"buffer": 0, "byteOffset": {twice}, "byteLength": {rest}}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": {vertices}, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5126, "count": {vertices}, "type": "VEC3"}},
                      {{"bufferView": 2, "componentType": 5125, "count": {indices}, "type": "SCALAR"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        len = bytes.len(),
        twice = 2 * positions,
        rest = bytes.len() - 2 * positions,
    );
    std::fs::write(dir.join(format!("{name}.bin")), &bytes).unwrap();
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, gltf).unwrap();
    (path, bytes.len() as u64)
}

/// `render --json` of `model`: its peak memory and its BLASes' bytes as built.
fn render(model: &Path, dir: &Path) -> (u64, u64) {
    let args = ["render", model.to_str().unwrap(), "--width", "32", "--height", "32", "--out", "x.png", "--json"];
    let out = twinray(&args, dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("render --json");
    let peak = json["peak_memory_bytes"].as_u64().expect("a peak on Linux");
    (peak, json["acceleration_structures"]["blas_built_bytes"].as_u64().unwrap())
}

#[test]
fn a_large_model_adds_at_most_two_and_a_half_files_and_its_structures_to_the_peak() {
    let dir = tempfile::tempdir().unwrap();
    let (small, _) = sheet(dir.path(), "small", 11);
    // 500,000 triangles: 12 MB of file, a 64-byte vertex 16 MB on the GPU, the BLAS ~50 MiB on
    // lavapipe; held twice, the mesh would add 22 MB to a peak of ~80.
    let (large, file) = sheet(dir.path(), "large", 501);
    let (base, _) = render(&small, dir.path());
    let (peak, structures) = render(&large, dir.path());
    let own = peak.saturating_sub(base);
    let allowed = file * 5 / 2 + structures;
    let mib = |b: u64| b as f64 / f64::from(1 << 20);
    assert!(
        own <= allowed,
        "the model added {:.1} MiB to a {:.1} MiB peak: more than 2.5 x {:.1} MiB of file + {:.1} MiB of structures",
        mib(own),
        mib(base),
        mib(file),
        mib(structures)
    );
}
