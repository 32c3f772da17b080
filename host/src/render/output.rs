//! What a render produces, and reading it back from the GPU's bytes.

use crate::util::stats::{median, Spread};
use twinray_shared::bindings as b;

/// `RenderOutput::hit_ids` of a pixel whose first primary ray hit nothing.
pub const NO_HIT_ID: u64 = u64::MAX;

/// Image size and trace counts of a render.
#[derive(Clone, Copy, Debug)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    /// Untimed traces before the timed ones.
    pub warmup: u32,
    /// Timed traces (at least one trace always runs).
    pub runs: u32,
}

/// What a render produced.
pub struct RenderOutput {
    pub width: u32,
    pub height: u32,
    /// Row-major RGBA8, top row first: `linear` clamped to [0, 1] and rounded to 8 bits.
    pub rgba: Vec<u8>,
    /// Row-major RGB mean radiance per pixel, in f32, as ray generation wrote it.
    pub linear: Vec<[f32; 3]>,
    /// Per pixel, what the first primary ray hit: object index << 32 | primitive index, or
    /// [`NO_HIT_ID`].
    pub hit_ids: Vec<u64>,
    /// GPU milliseconds of each timed trace; empty when the device cannot time.
    pub gpu_ms: Vec<f64>,
    /// Rays one trace traced.
    pub rays: RayCounts,
    /// Untimed traces before the timed ones: the asked-for count, raised to fill `MIN_WARM_MS`.
    pub warmup_traces: u32,
    /// Stack bytes the ray generation stage needs (see `RtPipeline::raygen_stack_bytes`).
    pub raygen_stack_bytes: u64,
}

/// Rays traced by one trace of an image, by kind: primary rays are pixels times samples,
/// shadow rays are counted by ray generation as it traces them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct RayCounts {
    pub primary: u64,
    pub shadow: u64,
}

impl RayCounts {
    /// Primary and shadow rays together.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow
    }
}

impl RenderOutput {
    /// Median GPU time of the timed traces.
    pub fn median_ms(&self) -> Option<f64> {
        median(&self.gpu_ms)
    }

    /// Median and interquartile range of the timed traces.
    pub fn spread(&self) -> Option<Spread> {
        Spread::of(&self.gpu_ms)
    }

    /// Millions of rays per second at the median GPU time.
    pub fn mrays_per_s(&self) -> Option<f64> {
        self.median_ms().filter(|&ms| ms > 0.0).map(|ms| self.rays.total() as f64 / (ms * 1e3))
    }
}

/// RGB of each rgba32f pixel.
pub(crate) fn read_linear(bytes: &[u8]) -> Vec<[f32; 3]> {
    let floats: &[f32] = bytemuck::cast_slice(bytes);
    floats.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect()
}

/// 8-bit RGBA of linear RGB: clamped to [0, 1], rounded to nearest (NaN becomes 0), alpha 255.
pub fn to_rgba8(linear: &[[f32; 3]]) -> Vec<u8> {
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    linear.iter().flat_map(|p| [byte(p[0]), byte(p[1]), byte(p[2]), 255]).collect()
}

/// Per pixel the first hit (object << 32 | primitive), and the sum of the pixels' shadow rays.
pub(crate) fn read_ids(bytes: &[u8]) -> (Vec<u64>, u64) {
    let word = |p: &[u8], i: usize| u32::from_le_bytes([p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]]);
    let per_pixel = 4 * b::HIT_IDS_PER_PIXEL as usize;
    let ids = bytes.chunks_exact(per_pixel).map(|p| u64::from(word(p, 0)) << 32 | u64::from(word(p, 1))).collect();
    let shadow = bytes.chunks_exact(per_pixel).map(|p| u64::from(word(p, 2))).sum();
    (ids, shadow)
}
