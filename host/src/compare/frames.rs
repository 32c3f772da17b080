//! `compare --frames`: two sets over the frames of a moving scene, each frame judged against
//! the scene's parity tolerance, and the worst frame named.

use super::diff::{diff, verdict, ImageDiff};
use super::edges::set_apart;
use super::pixels::{named_pixels, pixel_lines, NamedPixel};
use crate::error::Result;
use crate::explain::no_payload;
use crate::render::{render_frames, AsWork, Frame, RayCounts, RenderOptions, RenderOutput, TlasMode};
use crate::scene::{Parity, Scene};
use crate::sets::ShaderSet;
use crate::vk::context::Context;
use serde::Serialize;
use std::ops::Range;
use std::sync::Arc;

/// One frame's figures, as `compare --frames --json` prints them.
#[derive(Clone, Debug, Serialize)]
pub struct FrameFigures {
    pub frame: u32,
    /// Seconds into the animation.
    pub time: f32,
    pub as_work: AsWork,
    /// GPU milliseconds of the frame's TLAS work (shared by both sets).
    pub as_ms: Option<f64>,
    /// Median GPU milliseconds of each set's timed traces of the frame.
    pub trace_ms_a: Option<f64>,
    pub trace_ms_b: Option<f64>,
    pub rays_a: RayCounts,
    pub rays_b: RayCounts,
    #[serde(flatten)]
    pub diff: ImageDiff,
    pub pass: bool,
    pub failures: Vec<String>,
    /// The pixels that differ most and the hit mismatches of this frame, a few, with their
    /// `twinray explain --frame` lines (as a single-frame compare names them).
    pub pixels: Vec<NamedPixel>,
}

/// Every frame's figures and the verdict on the sequence.
#[derive(Clone, Debug, Serialize)]
pub struct FramesReport {
    pub scene: String,
    pub device: String,
    pub width: u32,
    pub height: u32,
    pub set_a: String,
    pub set_b: String,
    pub tlas: String,
    pub pixel_threshold: u8,
    pub frames: Vec<FrameFigures>,
    /// The frame closest to (or furthest past) the tolerance: see [`badness`].
    pub worst_frame: Option<u32>,
    /// Frames outside the tolerance.
    pub failed_frames: Vec<u32>,
    pub pass: bool,
}

/// How far a frame's differences go towards the tolerance: the largest of each measured
/// fraction over its limit (1 is at the limit). A hit mismatch away from every silhouette, or
/// a pixel not written or not finite, which fail any frame, count as infinitely bad.
pub fn badness(d: &ImageDiff, parity: &Parity, pixels: u64) -> f64 {
    if d.hit_mismatches_off_silhouette > 0 || !d.written_a.is_clean() || !d.written_b.is_clean() {
        return f64::INFINITY;
    }
    let fraction = |n: u64| n as f64 / pixels.max(1) as f64;
    let over = |value: f64, limit: f64| {
        if limit > 0.0 {
            value / limit
        } else if value > 0.0 {
            f64::INFINITY
        } else {
            0.0
        }
    };
    over(d.color.rmse, parity.max_rmse)
        .max(over(fraction(d.color.pixels_over_threshold), parity.max_pixels_over_threshold))
        .max(over(fraction(d.hit_mismatches), parity.max_hit_mismatches))
}

/// Renders frames `frames` of `scene` with both sets over the same TLAS, and judges each;
/// `each` sees every frame's figures and both renders as they complete.
pub fn compare_frames(
    ctx: &Arc<Context>,
    scene: &Scene,
    (set_a, set_b): (&ShaderSet, &ShaderSet),
    opts: &RenderOptions,
    frames: Range<u32>,
    mode: TlasMode,
    mut each: impl FnMut(&FrameFigures, &RenderOutput, &RenderOutput) -> Result<()>,
) -> Result<FramesReport> {
    let parity = scene.file.parity;
    let pixels = u64::from(opts.width) * u64::from(opts.height);
    let sets = (set_a.to_string(), set_b.to_string());
    let mut figures = Vec::new();
    let mut worst: Option<(f64, u32)> = None;
    render_frames(ctx, scene, &[set_a.clone(), set_b.clone()], opts, frames, mode, |frame: Frame| {
        let [a, b] = &frame.outputs[..] else { return Ok(()) };
        let mut d = diff(a, b, parity.pixel_threshold);
        let no_payload = !(a.no_payload.is_empty() && b.no_payload.is_empty());
        // The frame posed on the host for the f64 reference only where it has a question to
        // answer: the renderer posed its meshes already.
        let posed = match d.hit_mismatches > 0 || no_payload {
            true => Some(scene.at_frame(frame.index)?),
            false => None,
        };
        if let Some(posed) = &posed {
            set_apart(&mut d, posed, a, b);
        }
        let bad = badness(&d, &parity, pixels);
        if worst.is_none_or(|(w, _)| bad > w) {
            worst = Some((bad, frame.index));
        }
        let mut failures = verdict(&d, &parity, pixels);
        if let (Some(posed), true) = (&posed, no_payload) {
            failures.extend(no_payload::render_lines(posed, a, "set a"));
            failures.extend(no_payload::render_lines(posed, b, "set b"));
        }
        let threshold = (parity.pixel_threshold, &d);
        let named = named_pixels(scene, (a, b), threshold, (&sets.0, &sets.1), Some(frame.index));
        let row = FrameFigures {
            frame: frame.index,
            time: frame.time,
            as_work: frame.as_work,
            as_ms: frame.as_ms,
            trace_ms_a: a.median_ms(),
            trace_ms_b: b.median_ms(),
            rays_a: a.rays,
            rays_b: b.rays,
            diff: d,
            pass: failures.is_empty(),
            failures,
            pixels: named,
        };
        each(&row, a, b)?;
        figures.push(row);
        Ok(())
    })?;
    let failed_frames: Vec<u32> = figures.iter().filter(|f| !f.pass).map(|f| f.frame).collect();
    Ok(FramesReport {
        scene: scene.name().to_string(),
        device: ctx.info.name.clone(),
        width: opts.width,
        height: opts.height,
        set_a: set_a.to_string(),
        set_b: set_b.to_string(),
        tlas: mode.name(),
        pixel_threshold: parity.pixel_threshold,
        frames: figures,
        worst_frame: worst.map(|w| w.1),
        pass: failed_frames.is_empty(),
        failed_frames,
    })
}

impl FramesReport {
    /// The text `compare --frames` prints: one line per frame, then the worst frame and verdict.
    pub fn summary(&self) -> String {
        let ms = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.3}"));
        let mut s = format!(
            "scene {} {}x{} on {}, a = {}, b = {}, TLAS {}\n{:>6} {:>7} {:>8} {:>9} {:>9} {:>9} {:>9} {:>8}  verdict\n",
            self.scene,
            self.width,
            self.height,
            self.device,
            self.set_a,
            self.set_b,
            self.tlas,
            "frame",
            "AS",
            "AS ms",
            "a ms",
            "b ms",
            "rmse",
            "px over",
            "hits"
        );
        for f in &self.frames {
            let work = match f.as_work {
                AsWork::Build => "build",
                AsWork::Update => "update",
                AsWork::None => "-",
            };
            s += &format!(
                "{:>6} {:>7} {:>8} {:>9} {:>9} {:>9.6} {:>9} {:>8}  {}\n",
                f.frame,
                work,
                ms(f.as_ms),
                ms(f.trace_ms_a),
                ms(f.trace_ms_b),
                f.diff.color.rmse,
                f.diff.color.pixels_over_threshold,
                f.diff.hit_mismatches,
                if f.pass { "pass".to_string() } else { format!("FAIL: {}", f.failures.join("; ")) }
            );
            s += &pixel_lines(&f.pixels, "         ");
        }
        if let Some(w) = self.worst_frame.and_then(|w| self.frames.iter().find(|f| f.frame == w)) {
            s += &format!(
                "  worst frame {}: rmse {:.6}, {} pixels over {} steps, {} hit mismatches\n",
                w.frame,
                w.diff.color.rmse,
                w.diff.color.pixels_over_threshold,
                self.pixel_threshold,
                w.diff.hit_mismatches
            );
        }
        if self.pass {
            s += &format!("  PASS: all {} frames within the scene's parity tolerance\n", self.frames.len());
        } else {
            s += &format!("  FAIL: frames {:?} outside the scene's parity tolerance\n", self.failed_frames);
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compare::diff::ColorDiff;

    fn diff(rmse: f64, over: u64, hits: u64, off: u64) -> ImageDiff {
        let color = ColorDiff { rmse, psnr: 0.0, max_abs_diff: 0, pixels_over_threshold: over };
        let clean = crate::render::Written::default();
        ImageDiff {
            color,
            hit_mismatches: hits,
            hit_mismatches_off_silhouette: off,
            internal_edges: 0,
            internal_edge_pixels: Vec::new(),
            alpha_edges: 0,
            alpha_edge_pixels: Vec::new(),
            written_a: clean,
            written_b: clean,
        }
    }

    #[test]
    fn badness_is_the_largest_fraction_of_a_limit() {
        let parity = Parity::default();
        let pixels = 10_000;
        assert_eq!(badness(&diff(0.0, 0, 0, 0), &parity, pixels), 0.0);
        assert!((badness(&diff(0.005, 0, 0, 0), &parity, pixels) - 0.5).abs() < 1e-12);
        // 40 of 10,000 pixels over is 0.004, twice the 0.002 allowed.
        assert!((badness(&diff(0.001, 40, 0, 0), &parity, pixels) - 2.0).abs() < 1e-12);
        assert!((badness(&diff(0.001, 0, 10, 0), &parity, pixels) - 0.5).abs() < 1e-12);
        assert!(badness(&diff(0.0, 0, 1, 1), &parity, pixels).is_infinite(), "off a silhouette fails any frame");
    }
}
