//! What a render produces, and reading it back from the GPU's bytes.

use super::placement::PlacementTimes;
use super::sentinel;
pub use super::upload::AccelStats;
use crate::util::interval::RatioInterval;
use crate::util::srgb::{self, ToneMap};
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
    /// Timed traces per placement (at least one trace always runs).
    pub runs: u32,
    /// Rounds of placements: in each, every set is timed once at a place of its own (see
    /// `render::placement`), with its own warm-up and timed traces; at least one.
    pub placements: u32,
    /// The number of the render's first round: round `r` of the render times set `i` at
    /// `placement::place(first_placement + r, i, sets)`. Each process of `--processes` starts
    /// further on, so that no two processes time the same places; 0 elsewhere.
    pub first_placement: u32,
}

impl RenderOptions {
    /// One placement of `runs` timed traces after `warmup` untimed ones.
    pub fn once(width: u32, height: u32, warmup: u32, runs: u32) -> Self {
        RenderOptions { width, height, warmup, runs, placements: 1, first_placement: 0 }
    }
}

/// What a render produced.
pub struct RenderOutput {
    pub width: u32,
    pub height: u32,
    /// Row-major RGBA8, top row first: `linear` clamped to [0, 1] and rounded to 8 bits, still
    /// linear: what parity's steps are counted in. Pictures are [`RenderOutput::picture`].
    pub rgba: Vec<u8>,
    /// Row-major RGB mean radiance per pixel, in f32, as ray generation wrote it.
    pub linear: Vec<[f32; 3]>,
    /// Per pixel, what the first primary ray hit: object index << 32 | primitive index, or
    /// [`NO_HIT_ID`].
    pub hit_ids: Vec<u64>,
    /// GPU milliseconds of each timed trace, every placement's; empty when the device cannot time.
    pub gpu_ms: Vec<f64>,
    /// The median of each placement's timed traces, and where the set was in its order.
    pub placements: PlacementTimes,
    /// Rays one trace traced.
    pub rays: RayCounts,
    /// Untimed traces before the timed ones: the asked-for count, raised to fill `MIN_WARM_MS`.
    pub warmup_traces: u32,
    /// Stack bytes the ray generation stage needs (see `RtPipeline::raygen_stack_bytes_of`).
    pub raygen_stack_bytes: u64,
    /// What the set left unwritten, or wrote as NaN or infinity.
    pub written: Written,
    /// Pixels with primary rays whose hit or miss stage wrote no payload, for naming the stage
    /// (`explain::no_payload`).
    pub no_payload: Vec<NoPayloadPixel>,
    /// The scene's acceleration structures, as uploaded for this render.
    pub accel: AccelStats,
}

/// What a set left of the sentinel its outputs started as (see `render::sentinel`), and
/// what it wrote that is not a finite number. Anything but zeros fails a render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Written {
    /// Pixels (or probe rays) with any output word still holding the sentinel.
    pub unwritten: u64,
    /// Of the pixels: those whose colour was never written, and those whose hit ids (first hit,
    /// shadow-ray count) were not.
    pub unwritten_color: u64,
    pub unwritten_ids: u64,
    /// Pixels (or probe rays that hit) written with a NaN or an infinity (not counting pixels
    /// with rays that got no payload, which ray generation writes as NaN).
    pub non_finite: u64,
    /// Primary rays (or probe rays) that came back with the payload ray generation poisoned:
    /// their hit or miss stage wrote no payload. See `RenderOutput::no_payload` for which.
    pub no_payload_rays: u64,
    /// Pixels with such rays.
    pub no_payload_pixels: u64,
}

impl Written {
    /// Whether every output was written, with finite numbers.
    pub fn is_clean(&self) -> bool {
        self.unwritten == 0 && self.non_finite == 0 && self.no_payload_rays == 0
    }

    /// An error naming `doing` and the set when anything was left unwritten or non-finite:
    /// for measurements that cannot go on without the output (references, bench rows).
    pub fn require(&self, set: &str, items: &str, doing: &str) -> crate::error::Result<()> {
        let problems = self.problems(set, items);
        if problems.is_empty() {
            Ok(())
        } else {
            Err(crate::error::Error::Output(format!("{doing}: {}", problems.join("; "))))
        }
    }

    /// One line per problem, naming the set: "3072 pixels not written by glsl,raygen=noop.spv
    /// (colour 3072, hit ids 3072)", "12 pixels non-finite in rust". `items` is "pixels" or
    /// "rays".
    pub fn problems(&self, set: &str, items: &str) -> Vec<String> {
        let mut lines = Vec::new();
        if self.unwritten > 0 {
            let detail = if items == "pixels" {
                format!(" (colour {}, hit ids {})", self.unwritten_color, self.unwritten_ids)
            } else {
                String::new()
            };
            lines.push(format!("{} {items} not written by {set}{detail}", self.unwritten));
        }
        if self.non_finite > 0 {
            lines.push(format!("{} {items} non-finite in {set}", self.non_finite));
        }
        if self.no_payload_rays > 0 {
            let pixels =
                if items == "pixels" { format!(" in {} pixels", self.no_payload_pixels) } else { String::new() };
            lines.push(format!(
                "{} rays{pixels} whose hit or miss stage wrote no payload in {set} (ray generation poisoned it before \
                 the trace; it came back unchanged)",
                self.no_payload_rays
            ));
        }
        lines
    }
}

/// Rays of one trace of an image, by kind. Neither is measured by twinray: primary rays are
/// the scene's count (pixels times samples, what a correct ray generation stage traces), and
/// shadow rays are what the ray generation stage counted itself as it traced them (pixels
/// whose count it never wrote add none). JSON carries where each comes from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    pub primary: u64,
    pub shadow: u64,
}

/// Where [`RayCounts::primary`] comes from, in reports.
pub const PRIMARY_FROM: &str = "the scene: pixels x samples";
/// Where [`RayCounts::shadow`] comes from, in reports.
pub const SHADOW_FROM: &str = "ray generation's own count";

impl serde::Serialize for RayCounts {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut s = serializer.serialize_struct("RayCounts", 4)?;
        s.serialize_field("primary", &self.primary)?;
        s.serialize_field("shadow", &self.shadow)?;
        s.serialize_field("primary_from", PRIMARY_FROM)?;
        s.serialize_field("shadow_from", SHADOW_FROM)?;
        s.end()
    }
}

impl std::fmt::Display for RayCounts {
    /// "3072 primary rays (the scene's) + 904 shadow rays (as ray generation counted them)".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} primary rays (the scene's) + {} shadow (as ray generation counted them)",
            self.primary, self.shadow
        )
    }
}

impl RayCounts {
    /// Primary and shadow rays together.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow
    }
}

impl RenderOutput {
    /// The image as a PNG holds it: sRGB-encoded, through the process's `--tone-map`.
    pub fn picture(&self) -> Vec<u8> {
        to_picture(&self.linear)
    }

    /// Adds one place's timed traces: their median, the set's position in the round, the
    /// place (see `render::placement`), and the traces to the pooled ones.
    pub(crate) fn record_place(&mut self, gpu_ms: &[f64], position: u32, place: u64) {
        if let Some(ms) = median(gpu_ms) {
            self.placements.median_ms.push(ms);
            self.placements.position.push(position);
            self.placements.place.push(place);
        }
        self.gpu_ms.extend_from_slice(gpu_ms);
    }

    /// Median GPU time: the median of the placements' medians (of the traces when no
    /// placement was recorded), so that a placement with more traces weighs no more.
    pub fn median_ms(&self) -> Option<f64> {
        median(&self.placements.median_ms).or_else(|| median(&self.gpu_ms))
    }

    /// Median and interquartile range of the timed traces of every placement pooled: how the
    /// traces spread, not how uncertain a ratio of two sets is (see `ratio_to`).
    pub fn spread(&self) -> Option<Spread> {
        Spread::of(&self.gpu_ms)
    }

    /// This set's time against `other`'s (rendered in the same placements), with its 95%
    /// interval over placements.
    pub fn ratio_to(&self, other: &RenderOutput) -> Option<RatioInterval> {
        self.placements.ratio_to(&other.placements)
    }

    /// Millions of rays per second at the median GPU time, of the rays [`RayCounts`] counts;
    /// none when the set left pixels unwritten, since it did not trace the scene's rays.
    pub fn mrays_per_s(&self) -> Option<f64> {
        let traced = self.written.unwritten == 0;
        self.median_ms().filter(|&ms| ms > 0.0 && traced).map(|ms| self.rays.total() as f64 / (ms * 1e3))
    }
}

/// What one set's render left in the image and hit-id readbacks.
pub(crate) struct ReadBack {
    pub linear: Vec<[f32; 3]>,
    pub hit_ids: Vec<u64>,
    /// Shadow rays the pixels counted (pixels whose count is unwritten add none).
    pub shadow: u64,
    pub written: Written,
    pub no_payload: Vec<NoPayloadPixel>,
}

/// A pixel with primary rays whose hit or miss stage wrote no payload.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoPayloadPixel {
    /// Row-major pixel index.
    pub pixel: u32,
    /// The sample index of its first such ray.
    pub first_sample: u32,
    /// How many of its primary rays got no payload.
    pub rays: u32,
}

/// Reads an rgba32f image and the hit-id words of the same pixels ([`b::HIT_IDS_PER_PIXEL`]
/// each: object, primitive, shadow-ray count, rays with no payload), counting what still holds
/// the sentinel and the rays whose payload came back poisoned.
pub(crate) fn read_back(image: &[u8], ids: &[u8]) -> ReadBack {
    let floats: &[u32] = bytemuck::cast_slice(image);
    let words: &[u32] = bytemuck::cast_slice(ids);
    let per_pixel = b::HIT_IDS_PER_PIXEL as usize;
    let mut out = ReadBack {
        linear: Vec::new(),
        hit_ids: Vec::new(),
        shadow: 0,
        written: Written::default(),
        no_payload: Vec::new(),
    };
    for (i, (p, w)) in floats.chunks_exact(4).zip(words.chunks_exact(per_pixel)).enumerate() {
        let color_unwritten = p.iter().any(|&x| sentinel::unwritten(x));
        let ids_unwritten = w.iter().any(|&x| sentinel::unwritten(x));
        let rgba = [p[0], p[1], p[2], p[3]].map(f32::from_bits);
        let no_payload = if ids_unwritten { 0 } else { w[3] };
        let written = &mut out.written;
        written.unwritten += u64::from(color_unwritten || ids_unwritten);
        written.unwritten_color += u64::from(color_unwritten);
        written.unwritten_ids += u64::from(ids_unwritten);
        let finite = rgba.iter().all(|x| x.is_finite());
        written.non_finite += u64::from(!color_unwritten && !finite && no_payload == 0);
        if no_payload != 0 {
            let rays = no_payload & ((1 << b::NO_PAYLOAD_FIRST_SHIFT) - 1);
            written.no_payload_pixels += 1;
            written.no_payload_rays += u64::from(rays);
            let first_sample = no_payload >> b::NO_PAYLOAD_FIRST_SHIFT;
            out.no_payload.push(NoPayloadPixel { pixel: i as u32, first_sample, rays });
        }
        out.linear.push([rgba[0], rgba[1], rgba[2]]);
        out.hit_ids.push(hit_id(w[0], w[1]));
        out.shadow += if sentinel::unwritten(w[2]) { 0 } else { u64::from(w[2]) };
    }
    out
}

/// The hit id of `object` and `primitive` as `RenderOutput::hit_ids` holds it; a miss (both
/// `NO_HIT`) is [`NO_HIT_ID`].
pub fn hit_id(object: u32, primitive: u32) -> u64 {
    (u64::from(object) << 32) | u64::from(primitive)
}

/// Colour of pixels that are not a finite number (never written, or NaN or infinite) in the
/// PNGs twinray writes: magenta, which no scene's lighting makes by itself so plainly.
pub const NOT_A_NUMBER_RGB: [u8; 3] = [255, 0, 255];

/// 8-bit RGBA of linear RGB, sRGB-encoded as PNG viewers read it: each channel through `tone`,
/// then the sRGB transfer function, alpha 255; a pixel with a NaN or an infinity is
/// [`NOT_A_NUMBER_RGB`]. What every PNG of radiance holds; metrics use [`to_rgba8`].
pub fn to_srgb8(linear: &[[f32; 3]], tone: ToneMap) -> Vec<u8> {
    rgba8_by(linear, |v| srgb::encode(tone.apply(v)))
}

/// [`to_srgb8`] through the process's `--tone-map`: what a PNG of radiance holds.
pub fn to_picture(linear: &[[f32; 3]]) -> Vec<u8> {
    to_srgb8(linear, srgb::tone_map())
}

/// 8-bit RGBA of linear RGB, still linear: clamped to [0, 1], rounded to nearest, alpha 255;
/// a pixel with a NaN or an infinity is [`NOT_A_NUMBER_RGB`]. The steps parity is counted in
/// (`RenderOutput::rgba`), never written as a picture.
pub fn to_rgba8(linear: &[[f32; 3]]) -> Vec<u8> {
    rgba8_by(linear, |v| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8)
}

/// 8-bit RGBA of linear RGB, each finite channel through `byte`, alpha 255; a pixel with a NaN
/// or an infinity is [`NOT_A_NUMBER_RGB`].
fn rgba8_by(linear: &[[f32; 3]], byte: impl Fn(f32) -> u8) -> Vec<u8> {
    linear
        .iter()
        .flat_map(|p| {
            let [r, g, b] = if p.iter().all(|v| v.is_finite()) { p.map(&byte) } else { NOT_A_NUMBER_RGB };
            [r, g, b, 255]
        })
        .collect()
}
