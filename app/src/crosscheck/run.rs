//! One scene's cross-check: its Mitsuba passes written to a folder and rendered there by
//! Python, or read from a folder of earlier renders; twinray's reference and coverage.

use super::compare::PassRender;
use super::convert::{convert, MitsubaScene, EMITTERS};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;
use twinray_host::error::{Error, Result};
use twinray_host::reference::image::reference;
use twinray_host::scene::file::MaterialDesc;
use twinray_host::scene::Scene;
use twinray_host::sets::ShaderSet;
use twinray_host::vk::context::Context;
use twinray_shared::shapes::mitsuba::TriangleMesh;

/// The Python program that renders the passes, written beside them.
pub const RENDER_PY: &str = include_str!("render.py");

/// What `render.py` reads, and what the comparison needs of the Mitsuba side.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Manifest {
    pub scene: String,
    pub variant: String,
    /// Samples per pixel of each pass, over its two halves.
    pub spp: u32,
    pub width: u32,
    pub height: u32,
    pub passes: Vec<String>,
    pub background: [f32; 3],
    pub notes: Vec<String>,
}

/// Writes `scene`'s Mitsuba passes, meshes, manifest and `render.py` into `dir`.
pub fn write_mitsuba(scene: &Scene, dir: &Path, size: (u32, u32), spp: u32, variant: &str) -> Result<Manifest> {
    check_mitsuba_spp(spp)?;
    let MitsubaScene { passes, meshes, images, background, notes } = convert(scene, size, spp / 2)?;
    std::fs::create_dir_all(dir.join("meshes")).map_err(|source| Error::Io {
        what: "creating",
        path: dir.into(),
        source,
    })?;
    for (name, mesh, uvs) in &meshes {
        write(&dir.join("meshes").join(format!("{name}.ply")), ply(mesh, uvs))?;
    }
    for (k, image) in images.iter().enumerate() {
        let png = dir.join("textures").join(format!("{k}.png"));
        let rgba = image::RgbaImage::from_raw(image.width, image.height, image.rgba.clone());
        let saved = rgba.map(|i| {
            std::fs::create_dir_all(dir.join("textures"))?;
            i.save(&png).map_err(std::io::Error::other)
        });
        saved
            .unwrap_or_else(|| Err(std::io::Error::other("its pixels do not fill its size")))
            .map_err(|source| Error::Io { what: "writing", path: png.clone(), source })?;
    }
    for pass in &passes {
        write(&dir.join(format!("{}.json", pass.name)), serde_json::to_string_pretty(&pass.scene).unwrap_or_default())?;
    }
    let manifest = Manifest {
        scene: scene.name().to_string(),
        variant: variant.to_string(),
        spp,
        width: size.0,
        height: size.1,
        passes: passes.iter().map(|p| p.name.clone()).collect(),
        background,
        notes,
    };
    write(&dir.join("manifest.json"), serde_json::to_string_pretty(&manifest).unwrap_or_default())?;
    write(&dir.join("render.py"), RENDER_PY)?;
    Ok(manifest)
}

fn write(path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    std::fs::write(path, bytes).map_err(|source| Error::Io { what: "writing", path: path.into(), source })
}

/// Mitsuba's samples per pixel must be twice a square: two halves for the noise estimate, each
/// a square for the stratified sampler.
pub fn check_mitsuba_spp(spp: u32) -> Result<()> {
    if spp < 2 || !spp.is_multiple_of(2) || !is_square(spp / 2) {
        return Err(Error::Input(format!(
            "Mitsuba samples per pixel must be twice a square (2, 8, 32, 128, 512, 2048, ...), not {spp}"
        )));
    }
    Ok(())
}

fn is_square(n: u32) -> bool {
    let r = f64::from(n).sqrt().round() as u32;
    r * r == n
}

/// Runs `render.py` in `dir` with `python` (one that has `mitsuba`), passing its output on.
pub fn render_mitsuba(python: &Path, dir: &Path) -> Result<()> {
    let status = std::process::Command::new(python)
        .arg(dir.join("render.py"))
        .arg(dir.join("manifest.json"))
        .status()
        .map_err(|source| Error::Io { what: "running", path: python.into(), source })?;
    if !status.success() {
        return Err(Error::Unsupported(format!(
            "{} render.py failed ({status}) in {}",
            python.display(),
            dir.display()
        )));
    }
    Ok(())
}

/// The manifest and every pass of `dir`, the `emitters` pass last.
pub fn read_mitsuba(dir: &Path) -> Result<(Manifest, Vec<PassRender>, PassRender)> {
    let path = dir.join("manifest.json");
    if !path.exists() {
        return Err(Error::Input(format!(
            "{}: no Mitsuba renders here; run with --python PY (or `cargo xtask crosscheck`) to make them",
            dir.display()
        )));
    }
    let text =
        std::fs::read_to_string(&path).map_err(|source| Error::Io { what: "reading", path: path.clone(), source })?;
    let manifest: Manifest =
        serde_json::from_str(&text).map_err(|e| Error::Input(format!("{}: {e}", path.display())))?;
    let pixels = (manifest.width as usize) * (manifest.height as usize);
    let mut lights = Vec::new();
    let mut emitters = None;
    for name in &manifest.passes {
        let half = |part: &str| read_f32(&dir.join(format!("{name}.{part}.f32")), pixels);
        let render = PassRender { name: name.clone(), halves: [half("a")?, half("b")?] };
        if name == EMITTERS {
            emitters = Some(render);
        } else {
            lights.push(render);
        }
    }
    let emitters = emitters.ok_or_else(|| Error::Input(format!("{}: no {EMITTERS} pass", path.display())))?;
    Ok((manifest, lights, emitters))
}

/// One half of a pass: `path` as Mitsuba wrote it, or gzipped beside it (`PATH.gz`, as
/// tests/crosscheck keeps them: float images of mostly smooth light compress 20 to 30 times).
/// No more than the image's size is inflated.
fn read_f32(path: &Path, pixels: usize) -> Result<Vec<[f32; 4]>> {
    use std::io::Read;
    let size = pixels * 16;
    let zipped = path.with_extension("f32.gz");
    let (bytes, path) = if !path.exists() && zipped.exists() {
        let file = std::fs::File::open(&zipped).map_err(|source| Error::Io {
            what: "reading",
            path: zipped.clone(),
            source,
        })?;
        let mut bytes = Vec::with_capacity(size);
        flate2::read::GzDecoder::new(file)
            .take(size as u64 + 1)
            .read_to_end(&mut bytes)
            .map_err(|source| Error::Io { what: "inflating", path: zipped.clone(), source })?;
        (bytes, zipped)
    } else {
        (std::fs::read(path).map_err(|source| Error::Io { what: "reading", path: path.into(), source })?, path.into())
    };
    if bytes.len() != size {
        let got = if bytes.len() > size { format!("more than {size} bytes") } else { format!("{} bytes", bytes.len()) };
        return Err(Error::Input(format!("{}: {got}, not {size} (RGBA float32)", path.display())));
    }
    let floats: Vec<f32> = bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    Ok(floats.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]).collect())
}

/// twinray's side: the converged reference at `spp`, and the same scene with no lights, every
/// material black and a white background, which reads 1 - coverage.
pub fn twinray_side(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    size: (u32, u32),
    spp: u32,
    cache: &Path,
) -> Result<(Vec<[f32; 3]>, Vec<f32>)> {
    let image = reference(ctx, scene, set, size, spp, cache)?;
    let mut blank = scene.clone();
    blank.file.lights.clear();
    blank.file.background = [1.0; 3];
    for m in blank.file.materials.values_mut() {
        *m = MaterialDesc::Diffuse { color: [0.0; 3], texture: None, emission: None };
    }
    let coverage = reference(ctx, &blank, set, size, spp.min(256), cache)?;
    Ok((image.linear, coverage.linear.iter().map(|p| p[0]).collect()))
}

/// A binary little-endian PLY file: positions, normals and texture coordinates `uvs` (one
/// per vertex, or none), then triangles.
fn ply(mesh: &TriangleMesh, uvs: &[Vec2]) -> Vec<u8> {
    let uv = if uvs.is_empty() { "" } else { "property float u\nproperty float v\n" };
    let header = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\n{uv}element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    let mut out = header.into_bytes();
    for (i, (p, n)) in mesh.positions.iter().zip(&mesh.normals).enumerate() {
        let uv = uvs.get(i).map(|t| t.to_array()).into_iter().flatten();
        for v in p.to_array().into_iter().chain(n.to_array()).chain(uv) {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    for t in &mesh.triangles {
        out.push(3);
        for i in t {
            out.extend_from_slice(&(*i as i32).to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::read_f32;
    use std::io::Write;

    fn gzipped(bytes: &[u8]) -> Vec<u8> {
        let mut z = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(bytes).unwrap();
        z.finish().unwrap()
    }

    #[test]
    fn a_half_is_read_plain_or_gzipped_and_no_larger_than_its_image() {
        let dir = tempfile::tempdir().unwrap();
        let floats: Vec<u8> = (0..8).flat_map(|i| (i as f32).to_le_bytes()).collect();
        std::fs::write(dir.path().join("p.a.f32"), &floats).unwrap();
        std::fs::write(dir.path().join("p.b.f32.gz"), gzipped(&floats)).unwrap();
        let plain = read_f32(&dir.path().join("p.a.f32"), 2).unwrap();
        assert_eq!(plain, read_f32(&dir.path().join("p.b.f32"), 2).unwrap());
        assert_eq!(plain[1], [4.0, 5.0, 6.0, 7.0]);
        // A render that inflates past its image is refused, naming the file, not read whole.
        std::fs::write(dir.path().join("q.a.f32.gz"), gzipped(&vec![0u8; 1 << 20])).unwrap();
        let e = read_f32(&dir.path().join("q.a.f32"), 2).unwrap_err().to_string();
        assert!(e.contains("q.a.f32.gz: more than 32 bytes, not 32"), "{e}");
    }
}
