//! Comparing two renders of one scene: image error, hit/miss agreement, a difference image a
//! person can read at a glance, and the verdict against the scene's parity tolerance.

use crate::render::{RenderOutput, Written, NOT_A_NUMBER_RGB, NO_HIT_ID};
use crate::scene::Parity;
use serde::Serialize;

/// Colour differences between two RGBA8 images of the same size (alpha ignored).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ColorDiff {
    /// Root mean square difference over the RGB channels, in [0, 1].
    pub rmse: f64,
    /// Peak signal-to-noise ratio in dB; infinite (JSON null) when the images are identical.
    pub psnr: f64,
    /// Largest difference of any channel, in 8-bit steps.
    pub max_abs_diff: u8,
    /// Pixels where some channel differs by more than the threshold.
    pub pixels_over_threshold: u64,
}

/// Image and hit-id differences between two renders of the same size.
#[derive(Clone, Debug, Serialize)]
pub struct ImageDiff {
    /// Over every pixel but those at a cutout's alpha cutoff (`alpha_edge_pixels`), where the
    /// two sets may rightly show two surfaces.
    #[serde(flatten)]
    pub color: ColorDiff,
    /// Pixels whose primary rays hit different primitives (or one hit and one missed).
    pub hit_mismatches: u64,
    /// Of those, pixels not on a silhouette in either image: these should never happen.
    pub hit_mismatches_off_silhouette: u64,
    /// Pixels whose primary rays hit two triangles of one mesh instance on the edge they share
    /// (`compare::edges`): either answer is right, so they are not hit mismatches.
    pub internal_edges: u64,
    /// Those pixels (row-major indices, rising).
    #[serde(skip)]
    pub internal_edge_pixels: Vec<usize>,
    /// Pixels where one set kept a hit on a cutout that the f64 reference finds within
    /// rounding of its alpha's cutoff, and the other set's hit lies behind it or it missed
    /// (`compare::edges`): either answer is right, so they are not hit mismatches.
    pub alpha_edges: u64,
    /// Those pixels (row-major indices, rising).
    #[serde(skip)]
    pub alpha_edge_pixels: Vec<usize>,
    /// What each set left unwritten or wrote non-finite; anything fails the comparison.
    pub written_a: Written,
    pub written_b: Written,
}

impl ImageDiff {
    /// Whether pixel `i`'s hit mismatch is set apart: either set's answer is right there.
    pub fn is_set_apart(&self, i: usize) -> bool {
        self.internal_edge_pixels.binary_search(&i).is_ok() || self.alpha_edge_pixels.binary_search(&i).is_ok()
    }
}

/// `ImageDiff` judged against a scene's tolerance.
pub fn verdict(diff: &ImageDiff, parity: &Parity, pixels: u64) -> Vec<String> {
    let fraction = |n: u64| n as f64 / pixels.max(1) as f64;
    let mut failures = diff.written_a.problems("set a", "pixels");
    failures.extend(diff.written_b.problems("set b", "pixels"));
    failures.extend(color_verdict(&diff.color, parity, pixels));
    if fraction(diff.hit_mismatches) > parity.max_hit_mismatches {
        failures.push(format!("{} hit mismatches (> {} of all)", diff.hit_mismatches, parity.max_hit_mismatches));
    }
    if diff.hit_mismatches_off_silhouette > 0 {
        failures.push(format!("{} hit mismatches away from any silhouette", diff.hit_mismatches_off_silhouette));
    }
    failures
}

/// The colour part of [`verdict`], for comparisons without hit ids (golden images).
pub fn color_verdict(diff: &ColorDiff, parity: &Parity, pixels: u64) -> Vec<String> {
    let mut failures = Vec::new();
    if diff.rmse > parity.max_rmse {
        failures.push(format!("rmse {:.6} > {}", diff.rmse, parity.max_rmse));
    }
    if diff.pixels_over_threshold as f64 / pixels.max(1) as f64 > parity.max_pixels_over_threshold {
        failures.push(format!(
            "{} pixels differ by more than {} steps (> {} of all)",
            diff.pixels_over_threshold, parity.pixel_threshold, parity.max_pixels_over_threshold
        ));
    }
    failures
}

/// Colour and hit-id differences of two renders of one size.
pub fn diff(a: &RenderOutput, b: &RenderOutput, pixel_threshold: u8) -> ImageDiff {
    let (hit_mismatches, hit_mismatches_off_silhouette) = hit_mismatches(a, b);
    ImageDiff {
        color: color_diff(&a.rgba, &b.rgba, pixel_threshold),
        hit_mismatches,
        hit_mismatches_off_silhouette,
        internal_edges: 0,
        internal_edge_pixels: Vec::new(),
        alpha_edges: 0,
        alpha_edge_pixels: Vec::new(),
        written_a: a.written,
        written_b: b.written,
    }
}

/// Colour error of RGBA8 image `b` against `a`.
pub fn color_diff(a: &[u8], b: &[u8], pixel_threshold: u8) -> ColorDiff {
    color_diff_except(a, b, pixel_threshold, &[])
}

/// [`color_diff`] over every pixel but those of `apart` (rising pixel indices).
pub fn color_diff_except(a: &[u8], b: &[u8], pixel_threshold: u8, apart: &[usize]) -> ColorDiff {
    let mut sum_sq = 0.0f64;
    let mut max_abs = 0u8;
    let mut over = 0u64;
    let pixels = a.chunks_exact(4).zip(b.chunks_exact(4)).enumerate();
    for (_, (pa, pb)) in pixels.filter(|(i, _)| apart.binary_search(i).is_err()) {
        let d = channel_diff(pa, pb);
        for c in 0..3 {
            let x = f64::from(pa[c]) / 255.0 - f64::from(pb[c]) / 255.0;
            sum_sq += x * x;
        }
        max_abs = max_abs.max(d);
        over += u64::from(d > pixel_threshold);
    }
    let samples = ((a.len() / 4 - apart.len()) * 3).max(1) as f64;
    let rmse = (sum_sq / samples).sqrt();
    ColorDiff {
        rmse,
        psnr: if rmse > 0.0 { -20.0 * rmse.log10() } else { f64::INFINITY },
        max_abs_diff: max_abs,
        pixels_over_threshold: over,
    }
}

/// Largest RGB channel difference of two pixels.
fn channel_diff(pa: &[u8], pb: &[u8]) -> u8 {
    (0..3).map(|c| pa[c].abs_diff(pb[c])).max().unwrap_or(0)
}

fn hit_mismatches(a: &RenderOutput, b: &RenderOutput) -> (u64, u64) {
    let (w, h) = (a.width as usize, a.height as usize);
    let mut total = 0;
    let mut off = 0;
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if a.hit_ids[i] != b.hit_ids[i] {
                total += 1;
                if !on_silhouette(&a.hit_ids, w, h, x, y) && !on_silhouette(&b.hit_ids, w, h, x, y) {
                    off += 1;
                }
            }
        }
    }
    (total, off)
}

/// True when a pixel of the 3x3 neighbourhood of (x, y) saw something else.
pub(super) fn on_silhouette(ids: &[u64], w: usize, h: usize, x: usize, y: usize) -> bool {
    let id = ids[y * w + x];
    (y.saturating_sub(1)..=(y + 1).min(h - 1))
        .any(|ny| (x.saturating_sub(1)..=(x + 1).min(w - 1)).any(|nx| ids[ny * w + nx] != id))
}

/// Legend of [`diff_image`], printed beside it.
pub const DIFF_LEGEND: &str = "dim grey = equal, red = 1 step, yellow = 8, white = 16+, cyan = hit mismatch, \
     blue = edge inside a mesh (either triangle is right), violet = alpha at its cutoff (either is right), \
     magenta = not written or not finite";

/// RGBA8 difference image: image A in dim grey for context; differing pixels as a heat map
/// (bright red for one 8-bit step, through yellow at 8, to white at 16 or more); hit/miss or
/// primitive mismatches in cyan, those on an edge inside a mesh (`ImageDiff::internal_edge_pixels`)
/// in blue, those at a cutout's alpha cutoff (`ImageDiff::alpha_edge_pixels`) in violet; pixels
/// either set left unwritten or wrote as NaN or infinity in magenta. Even a one-step difference
/// stands out against the grey.
pub fn diff_image(a: &RenderOutput, b: &RenderOutput, apart: &ImageDiff) -> Vec<u8> {
    let finite = |o: &RenderOutput, i: usize| o.linear.get(i).is_none_or(|p| p.iter().all(|v| v.is_finite()));
    let mut out = Vec::with_capacity(a.rgba.len());
    for (i, (pa, pb)) in a.rgba.chunks_exact(4).zip(b.rgba.chunks_exact(4)).enumerate() {
        let d = channel_diff(pa, pb);
        let rgb = if !finite(a, i) || !finite(b, i) {
            NOT_A_NUMBER_RGB
        } else if a.hit_ids[i] != b.hit_ids[i] && apart.internal_edge_pixels.binary_search(&i).is_ok() {
            [60, 90, 200]
        } else if a.hit_ids[i] != b.hit_ids[i] && apart.alpha_edge_pixels.binary_search(&i).is_ok() {
            [150, 80, 220]
        } else if a.hit_ids[i] != b.hit_ids[i] {
            [0, 255, 255]
        } else if d > 0 {
            heat((f32::from(d) / 16.0).min(1.0))
        } else {
            let grey = ((u16::from(pa[0]) + u16::from(pa[1]) + u16::from(pa[2])) / 12) as u8;
            [grey; 3]
        };
        out.extend_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
    }
    out
}

/// Ramp from red (t near 0) through yellow (t = 0.5) to white (t = 1).
fn heat(t: f32) -> [u8; 3] {
    let g = (t * 2.0).clamp(0.0, 1.0);
    let b = (t * 2.0 - 1.0).clamp(0.0, 1.0);
    [255, (g * 255.0) as u8, (b * 255.0) as u8]
}

/// Pixels whose primary ray hit something.
pub fn hit_count(output: &RenderOutput) -> u64 {
    output.hit_ids.iter().filter(|&&id| id != NO_HIT_ID).count() as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn output(rgba: Vec<u8>, hit_ids: Vec<u64>, width: u32) -> RenderOutput {
        let height = hit_ids.len() as u32 / width;
        RenderOutput {
            width,
            height,
            rgba,
            linear: vec![],
            hit_ids,
            gpu_ms: vec![],
            placements: Default::default(),
            rays: Default::default(),
            warmup_traces: 0,
            raygen_stack_bytes: 0,
            written: Written::default(),
            no_payload: vec![],
            accel: Default::default(),
        }
    }

    #[test]
    fn identical_images_have_zero_error() {
        let a = output(vec![10; 16], vec![1, 2, 3, NO_HIT_ID], 2);
        let d = diff(&a, &a, 1);
        assert_eq!((d.color.rmse, d.color.max_abs_diff, d.hit_mismatches), (0.0, 0, 0));
        assert!(d.color.psnr.is_infinite());
    }

    #[test]
    fn counts_channel_differences_and_mismatches() {
        let a = output(vec![0; 16], vec![1; 4], 2);
        let mut rgba = vec![0; 16];
        rgba[0] = 5; // pixel 0, red, 5 steps
        rgba[5] = 1; // pixel 1, green, 1 step
        let b = output(rgba, vec![1, 1, 1, 2], 2);
        let d = diff(&a, &b, 2);
        assert_eq!(d.color.max_abs_diff, 5);
        assert_eq!(d.color.pixels_over_threshold, 1);
        assert_eq!(d.hit_mismatches, 1);
        // In a 2x2 image every pixel touches the one that differs in b: all on a silhouette.
        assert_eq!(d.hit_mismatches_off_silhouette, 0);
        let want = ((25.0 + 1.0) / (255.0f64 * 255.0) / 12.0).sqrt();
        assert!((d.color.rmse - want).abs() < 1e-12);
    }

    #[test]
    fn mismatch_inside_a_uniform_region_is_off_silhouette() {
        let a = output(vec![0; 4 * 9], vec![7; 9], 3);
        let mut ids = vec![7; 9];
        ids[4] = 8;
        let b = output(vec![0; 4 * 9], ids, 3);
        // The centre pixel differs; in b its neighbours differ from it, so it is a silhouette there.
        assert_eq!(diff(&a, &b, 0).hit_mismatches_off_silhouette, 0);
        let c = output(vec![0; 4 * 9], vec![8; 9], 3);
        assert_eq!(diff(&a, &c, 0).hit_mismatches_off_silhouette, 9);
    }

    #[test]
    fn verdict_names_each_failure() {
        let parity =
            Parity { max_rmse: 0.01, pixel_threshold: 2, max_pixels_over_threshold: 0.0, max_hit_mismatches: 0.5 };
        let color = ColorDiff { rmse: 0.02, psnr: 34.0, max_abs_diff: 9, pixels_over_threshold: 1 };
        let clean = Written::default();
        let d = ImageDiff {
            color,
            hit_mismatches: 1,
            hit_mismatches_off_silhouette: 1,
            internal_edges: 0,
            internal_edge_pixels: Vec::new(),
            alpha_edges: 0,
            alpha_edge_pixels: Vec::new(),
            written_a: clean,
            written_b: clean,
        };
        let f = verdict(&d, &parity, 4);
        assert_eq!(f.len(), 3, "{f:?}");
        let good = ColorDiff { rmse: 0.0, pixels_over_threshold: 0, ..color };
        let ok = ImageDiff { color: good, hit_mismatches: 1, hit_mismatches_off_silhouette: 0, ..d.clone() };
        assert!(verdict(&ok, &parity, 4).is_empty());
        let half = Written { unwritten: 2, unwritten_color: 2, non_finite: 1, ..Written::default() };
        let broken = ImageDiff { written_b: half, ..ok };
        let f = verdict(&broken, &parity, 4);
        assert_eq!(f, ["2 pixels not written by set b (colour 2, hit ids 0)", "1 pixels non-finite in set b"]);
    }
}
