//! Converged reference images: a scene rendered with many samples per pixel, averaged in f64
//! over frames of up to 16 x 16 samples with independent seeds, kept as f32, and cached on
//! disk under a key of the scene, the image size, the sample count and the shaders that
//! render it, so that a changed scene or shader is rendered again.

use crate::error::{Error, Result};
use crate::render::{render, RenderOptions};
use crate::scene::Scene;
use crate::sets::{ShaderSet, MODULES};
use crate::util::checksum::{fnv1a, Fnv};
use crate::util::input::read_bounded;
use crate::util::output::{cache_dir, file_safe};
use crate::vk::context::Context;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Primary samples per side in one frame: 16 x 16, the most a scene allows.
pub const FRAME_SIDE: u32 = 16;
const MAGIC: &[u8; 8] = b"TWREF2\0\0";

/// A converged image: mean radiance per pixel over `spp` samples.
pub struct ReferenceImage {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub linear: Vec<[f32; 3]>,
    /// The file it was read from or written to.
    pub path: PathBuf,
    /// Whether it came from the cache rather than from rendering.
    pub cached: bool,
}

/// Most samples per pixel of a reference: 256 frames of 16 x 16.
pub const MAX_REFERENCE_SPP: u32 = 1 << 16;

/// Frames and samples per side that make `spp` samples per pixel: a square up to 16 x 16 in
/// one frame, or a multiple of 256 in frames of 16 x 16.
pub fn frames(spp: u32) -> Result<(u32, u32)> {
    if spp > MAX_REFERENCE_SPP {
        return Err(Error::Input(format!(
            "reference samples per pixel must be at most {MAX_REFERENCE_SPP} (got {spp})"
        )));
    }
    let side = (1..=FRAME_SIDE).find(|m| m * m == spp);
    match side {
        Some(m) => Ok((1, m)),
        None if spp > 0 && spp.is_multiple_of(FRAME_SIDE * FRAME_SIDE) => {
            Ok((spp / (FRAME_SIDE * FRAME_SIDE), FRAME_SIDE))
        }
        None => Err(Error::Input(format!(
            "reference samples per pixel must be a square up to 256 (1, 4, 9, .., 256) or a multiple of 256 (got {spp})"
        ))),
    }
}

/// What a reference converges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Converge {
    /// The pixel: `spp` jittered primary samples over its area.
    Pixel,
    /// Rect lights' shadows at each pixel's centre: one primary sample, `spp` shadow samples
    /// per light (the sampler study's truth, which pixel samples would blur).
    Shadows,
}

/// The reference of `scene` at `size` with `spp` samples per pixel rendered by `set`: read
/// from `cache` when it holds one under the same key, else rendered and written there.
pub fn reference(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    size: (u32, u32),
    spp: u32,
    cache: &Path,
) -> Result<ReferenceImage> {
    converged(ctx, scene, set, size, (spp, Converge::Pixel), cache)
}

/// As `reference`, for `Converge` `what`.
pub fn converged(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    (width, height): (u32, u32),
    (spp, what): (u32, Converge),
    cache: &Path,
) -> Result<ReferenceImage> {
    let (frames, side) = frames(spp)?;
    let key = key(scene, set, (width, height), spp, what);
    let tag = if what == Converge::Shadows { "-shadows" } else { "" };
    let path = cache.join(format!("{}{tag}-{width}x{height}-{spp}spp-{key:016x}.ref", file_safe(scene.name())));
    if let Some(linear) = read(&path, (width, height, spp)) {
        return Ok(ReferenceImage { width, height, spp, linear, path, cached: true });
    }
    // Before a render that may take minutes: can its result be kept?
    check_writable(cache)?;
    let mut sum = vec![[0.0f64; 3]; (width as usize) * (height as usize)];
    for k in 0..frames {
        let mut frame = scene.clone();
        match what {
            Converge::Pixel => frame.file.image.samples = side,
            Converge::Shadows => {
                frame.file.image.samples = 1;
                frame.set_shadow_samples(side);
            }
        }
        frame.file.image.seed = frame_seed(scene.file.image.seed, k);
        let out = render(ctx, &frame, set, &RenderOptions::once(width, height, 0, 1))?;
        out.written.require(&set.to_string(), "pixels", &format!("the reference of {}", scene.name()))?;
        for (s, p) in sum.iter_mut().zip(&out.linear) {
            for c in 0..3 {
                s[c] += f64::from(p[c]);
            }
        }
    }
    let linear: Vec<[f32; 3]> = sum.iter().map(|s| s.map(|v| (v / f64::from(frames)) as f32)).collect();
    write(&path, (width, height, spp), &linear)?;
    Ok(ReferenceImage { width, height, spp, linear, path, cached: false })
}

/// Seed of frame `k`: never the scene's own, so that renders measured against the reference
/// (which use the scene's seed) share none of its random numbers.
fn frame_seed(seed: u32, k: u32) -> u32 {
    seed ^ (k + 1).wrapping_mul(0x9e37_79b9)
}

/// FNV-1a over everything the image depends on: the parsed scene and its meshes, the size,
/// the sample count and the SPIR-V of every module the set resolves to.
fn key(scene: &Scene, set: &ShaderSet, (width, height): (u32, u32), spp: u32, what: Converge) -> u64 {
    let mut hash = Fnv::default();
    hash.eat(format!("{:?}{what:?}", scene.file).as_bytes());
    // The meshes' bytes, not their text: a million triangles print to hundreds of megabytes.
    for (name, mesh) in &scene.meshes {
        hash.eat(name.as_bytes());
        hash.eat(&[mesh.vertices.len(), mesh.indices.len()].map(|n| (n as u64).to_le_bytes()).concat());
        hash.eat(bytemuck::cast_slice(&mesh.vertices));
        hash.eat(bytemuck::cast_slice(&mesh.indices));
    }
    hash.eat(&[width, height, spp].map(u32::to_le_bytes).concat());
    for spec in MODULES.iter() {
        if let Ok(module) = set.resolve(spec) {
            hash.eat(&module.spirv);
        }
    }
    hash.value()
}

/// The pixels of a cache file whose header, size and checksum match and whose pixels are
/// finite; `None` for anything else (absent, short, foreign, corrupted, not a regular file),
/// which is then rendered again and overwritten.
fn read(path: &Path, (width, height, spp): (u32, u32, u32)) -> Option<Vec<[f32; 3]>> {
    let header: Vec<u8> = [MAGIC.as_slice(), &[width, height, spp].map(u32::to_le_bytes).concat()].concat();
    let pixels = (width as usize) * (height as usize);
    let size = header.len() + pixels * 12 + 8;
    let bytes = read_bounded(path, size as u64).ok()?;
    if bytes.len() != size {
        return None;
    }
    let (content, sum) = bytes.split_at(size - 8);
    if sum != checksum(content).to_le_bytes() {
        return None;
    }
    let body = content.strip_prefix(header.as_slice())?;
    let floats: Vec<f32> = body.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    if !floats.iter().all(|v| v.is_finite()) {
        return None;
    }
    Some(floats.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect())
}

/// FNV-1a over a cache file's header and pixels: its last eight bytes.
fn checksum(bytes: &[u8]) -> u64 {
    fnv1a(bytes)
}

/// Fails, naming the folder, when references cannot be written into `cache`.
fn check_writable(cache: &Path) -> Result<()> {
    let cannot = |e: std::io::Error| {
        Error::Input(format!(
            "reference cache {}: cannot write there ({e}); choose another with --cache",
            cache.display()
        ))
    };
    std::fs::create_dir_all(cache).map_err(cannot)?;
    let probe = cache.join(format!(".write-test-{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(cannot)?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Writes through a temporary file and a rename, so that a failure leaves no partial file.
fn write(path: &Path, (width, height, spp): (u32, u32, u32), linear: &[[f32; 3]]) -> Result<()> {
    let io = |what: &'static str, path: &Path| {
        let path = path.to_path_buf();
        move |source| Error::Io { what, path, source }
    };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(io("creating", dir))?;
    }
    let mut bytes: Vec<u8> = MAGIC.to_vec();
    bytes.extend([width, height, spp].map(u32::to_le_bytes).concat());
    bytes.extend(linear.iter().flatten().flat_map(|v| v.to_le_bytes()));
    bytes.extend(checksum(&bytes).to_le_bytes());
    let temporary = path.with_extension("ref.partial");
    std::fs::write(&temporary, bytes).map_err(io("writing", &temporary))?;
    std::fs::rename(&temporary, path).map_err(io("renaming", path))
}

/// Where references are cached by default: $XDG_CACHE_HOME/twinray/references, else
/// ~/.cache/twinray/references, else ./twinray-references.
pub fn default_cache() -> PathBuf {
    cache_dir("references")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_counts_are_squares_or_whole_frames() {
        assert_eq!(frames(1).unwrap(), (1, 1));
        assert_eq!(frames(64).unwrap(), (1, 8));
        assert_eq!(frames(256).unwrap(), (1, 16));
        assert_eq!(frames(1024).unwrap(), (4, 16));
        for bad in [0, 2, 300] {
            assert!(frames(bad).unwrap_err().to_string().contains("square up to 256"), "{bad}");
        }
    }

    #[test]
    fn cache_files_round_trip_and_reject_other_headers() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub").join("x.ref");
        let pixels = vec![[0.25, 1.5, -0.0], [f32::MAX, 0.0, 1e-30]];
        write(&path, (2, 1, 16), &pixels).unwrap();
        assert_eq!(read(&path, (2, 1, 16)), Some(pixels));
        assert_eq!(read(&path, (2, 1, 64)), None, "another sample count");
        assert_eq!(read(&path, (1, 2, 16)), None, "another size");
        std::fs::write(&path, b"TWREF1\0\0short").unwrap();
        assert_eq!(read(&path, (2, 1, 16)), None);
    }

    /// One flipped bit anywhere, a truncation, a byte more, or non-finite pixels with a
    /// matching checksum: never read.
    #[test]
    fn corrupted_cache_files_are_not_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.ref");
        let pixels = vec![[0.25, 1.5, 2.0], [3.0, 0.0, 1e-3]];
        write(&path, (2, 1, 16), &pixels).unwrap();
        let good = std::fs::read(&path).unwrap();
        for i in 0..good.len() {
            let mut bad = good.clone();
            bad[i] ^= 0x10;
            std::fs::write(&path, &bad).unwrap();
            assert_eq!(read(&path, (2, 1, 16)), None, "bit flipped in byte {i}");
        }
        for bad in [&good[..good.len() - 1], &[good.as_slice(), &[0]].concat()[..]] {
            std::fs::write(&path, bad).unwrap();
            assert_eq!(read(&path, (2, 1, 16)), None, "{} bytes", bad.len());
        }
        write(&path, (2, 1, 16), &[[f32::NAN, 0.0, 0.0], [0.0; 3]]).unwrap();
        assert_eq!(read(&path, (2, 1, 16)), None, "NaN pixel");
    }

    #[test]
    fn frame_seeds_differ_from_each_other_and_from_the_scene_seed() {
        let seeds: std::collections::BTreeSet<u32> = (0..64).map(|k| frame_seed(7, k)).collect();
        assert_eq!(seeds.len(), 64);
        assert!(!seeds.contains(&7));
    }
}
