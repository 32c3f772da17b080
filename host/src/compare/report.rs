//! `compare`: render one scene with two shader sets, measure how they differ in image and in
//! GPU time, judge that against the scene's tolerance, and write the images.

use super::diff::{diff_image, verdict, ImageDiff};
use super::edges::scene_diff;
use super::pixels::{named_pixels, pixel_lines, NamedPixel};
use crate::error::{Error, Result};
use crate::explain::no_payload;
use crate::render::isolated::{render_timed, AloneIn, Isolation};
use crate::render::{PlacementTimes, RayCounts, RenderOptions, RenderOutput};
use crate::scene::Scene;
use crate::sets::ShaderSet;
use crate::util::interval::RatioInterval;
use crate::util::output::write_png;
use crate::util::stats::Spread;
use crate::vk::context::Context;
use serde::Serialize;
use std::path::Path;
use std::sync::Arc;

/// The result of comparing set `a` against set `b`; serialised as `compare --json` prints it.
#[derive(Clone, Debug, Serialize)]
pub struct CompareReport {
    pub scene: String,
    pub device: String,
    pub width: u32,
    pub height: u32,
    pub set_a: String,
    pub set_b: String,
    #[serde(flatten)]
    pub diff: ImageDiff,
    pub pixel_threshold: u8,
    /// Median GPU milliseconds of each set (the median of its placements' medians); null when
    /// the device cannot time.
    pub gpu_ms_a: Option<f64>,
    pub gpu_ms_b: Option<f64>,
    /// A's time over B's: the geometric mean of the placements' ratios (`timing.ratio`).
    pub ratio: Option<f64>,
    /// The ratio with its 95% interval over placements, and the verdict in words.
    pub timing: Option<Timing>,
    /// Each set's placement medians and positions.
    pub placements_a: PlacementTimes,
    pub placements_b: PlacementTimes,
    /// Median and interquartile range of each set's timed traces, every placement pooled: how
    /// the traces spread, not how uncertain the ratio is.
    pub spread_a: Option<Spread>,
    pub spread_b: Option<Spread>,
    /// Rays each set traced in one trace (shadow rays may differ where the sets' hits do).
    pub rays_a: RayCounts,
    pub rays_b: RayCounts,
    /// Millions of rays per second at the median time.
    pub mrays_per_s_a: Option<f64>,
    pub mrays_per_s_b: Option<f64>,
    /// Threads of a CPU device (lavapipe); null on GPUs.
    pub cpu_threads: Option<u32>,
    /// Untimed traces each set ran before its timed ones (at least `warmup`, and at least
    /// `MIN_WARM_MS` of GPU time when `warmup` > 0).
    pub warmup_traces_a: u32,
    pub warmup_traces_b: u32,
    /// Stack bytes each set's ray generation stage needs, as the driver reports it.
    pub raygen_stack_bytes_a: u64,
    pub raygen_stack_bytes_b: u64,
    /// Timed traces per set in each placement (after `warmup` untimed ones), and placements.
    pub runs: u32,
    pub warmup: u32,
    pub placements: u32,
    /// Processes each set was timed alone in (`--processes`), the ratio's interval taken over
    /// them; 0: both sets timed in this process, the interval over placements.
    pub processes: u32,
    /// What those were: child processes or fresh devices in this one (`--alone-in`).
    pub alone_in: AloneIn,
    /// Whether B is a salted copy of A (`compare --a X --b X`): the null control.
    pub null_control: bool,
    /// The pixels that differ most and the hit mismatches, a few, with their `twinray explain`
    /// lines.
    pub pixels: Vec<NamedPixel>,
    pub pass: bool,
    /// Why `pass` is false, one line per broken tolerance.
    pub failures: Vec<String>,
}

/// A's GPU time over B's with its interval over placements, and what it resolves in words.
#[derive(Clone, Debug, Serialize)]
pub struct Timing {
    #[serde(flatten)]
    pub interval: RatioInterval,
    /// "a slower by 3.1% (95% CI 1.2% to 5.0%)" or "no difference resolved (95% CI ...)".
    pub verdict: String,
}

/// Both renders and the report on them.
pub struct Comparison {
    pub a: RenderOutput,
    pub b: RenderOutput,
    pub report: CompareReport,
}

/// Renders `scene` with both sets (see `render_sets`) and compares them against its tolerance.
/// With `isolation`, the sets' times are those of each set alone in processes of its own (the
/// renders here give only the images).
pub fn compare_sets(
    ctx: &Arc<Context>,
    scene: &Scene,
    (set_a, set_b): (&ShaderSet, &ShaderSet),
    opts: &RenderOptions,
    isolation: Option<&Isolation>,
) -> Result<Comparison> {
    let named_sets = (set_a.to_string(), set_b.to_string());
    // The same set twice is timed as two copies built apart: the null control.
    let sets = ShaderSet::distinct(&[set_a.clone(), set_b.clone()]);
    let set_b = &sets[1];
    let [a, b]: [RenderOutput; 2] = render_timed(ctx, scene, &sets, opts, isolation)?
        .try_into()
        .map_err(|_| Error::Unsupported("a render of two sets returned another count".into()))?;
    let parity = scene.file.parity;
    let diff = scene_diff(scene, &a, &b);
    let threshold = (parity.pixel_threshold, &diff);
    let pixels = named_pixels(scene, (&a, &b), threshold, (&named_sets.0, &named_sets.1), None);
    let mut failures = verdict(&diff, &parity, u64::from(opts.width) * u64::from(opts.height));
    failures.extend(no_payload::render_lines(scene, &a, "set a"));
    failures.extend(no_payload::render_lines(scene, &b, "set b"));
    let (gpu_ms_a, gpu_ms_b) = (a.median_ms(), b.median_ms());
    let interval = a.ratio_to(&b);
    let report = CompareReport {
        scene: scene.name().to_string(),
        device: ctx.info.name.clone(),
        width: opts.width,
        height: opts.height,
        set_a: set_a.to_string(),
        set_b: set_b.to_string(),
        diff,
        pixel_threshold: parity.pixel_threshold,
        gpu_ms_a,
        gpu_ms_b,
        ratio: interval.map(|i| i.ratio),
        timing: interval.map(|interval| Timing { interval, verdict: interval.verdict("a") }),
        placements_a: a.placements.clone(),
        placements_b: b.placements.clone(),
        spread_a: a.spread(),
        spread_b: b.spread(),
        rays_a: a.rays,
        rays_b: b.rays,
        mrays_per_s_a: a.mrays_per_s(),
        mrays_per_s_b: b.mrays_per_s(),
        cpu_threads: ctx.info.cpu_threads,
        warmup_traces_a: a.warmup_traces,
        warmup_traces_b: b.warmup_traces,
        raygen_stack_bytes_a: a.raygen_stack_bytes,
        raygen_stack_bytes_b: b.raygen_stack_bytes,
        runs: opts.runs,
        warmup: opts.warmup,
        placements: opts.placements,
        processes: isolation.map_or(0, |i| i.processes),
        alone_in: isolation.map_or(AloneIn::Processes, |i| i.alone_in),
        null_control: set_b.original() == *set_a,
        pixels,
        pass: failures.is_empty(),
        failures,
    };
    Ok(Comparison { a, b, report })
}

impl Comparison {
    /// Writes `a.png`, `b.png` and `diff.png` into `dir`, creating it if needed.
    pub fn write_images(&self, dir: &Path) -> Result<()> {
        std::fs::create_dir_all(dir).map_err(|source| Error::Io { what: "creating", path: dir.into(), source })?;
        let (w, h) = (self.a.width, self.a.height);
        write_png(&dir.join("a.png"), w, h, &self.a.picture())?;
        write_png(&dir.join("b.png"), w, h, &self.b.picture())?;
        write_png(&dir.join("diff.png"), w, h, &diff_image(&self.a, &self.b, &self.report.diff))
    }
}

impl CompareReport {
    /// The human-readable summary `compare` prints.
    pub fn summary(&self) -> String {
        let timing = |ms: Option<f64>, spread: Option<Spread>, rate: Option<f64>, rays: RayCounts| {
            let ms =
                ms.zip(spread).map_or("n/a".to_string(), |(m, s)| format!("{m:.3} ms (traces' IQR {:.3})", s.iqr()));
            let rate = rate.map_or(String::new(), |r| format!(", {r:.1} Mrays/s"));
            format!("GPU {ms}{rate} of {rays}")
        };
        let threads = self.cpu_threads.map_or(String::new(), |t| format!(", {t} threads"));
        let null = if self.null_control { " (b is a salted copy of a: the null control)" } else { "" };
        let timed = if self.processes > 0 {
            let (n, p, r, w) = (self.processes, self.placements, self.runs, self.warmup);
            let on = self.alone_in.plural();
            format!("each set alone in {n} {on} of {p} placements of {r} timed traces after {w} untimed")
        } else {
            let (p, r, wa, wb) = (self.placements, self.runs, self.warmup_traces_a, self.warmup_traces_b);
            format!("{p} placements of {r} timed traces after {wa}/{wb} untimed")
        };
        let mut s = format!(
            "scene {} {}x{} on {}{threads}, {timed}\n  a = {:<28} {}\n  b = {:<28} {}{null}\n  time a/b {}, raygen stack {} / {} bytes\n",
            self.scene,
            self.width,
            self.height,
            self.device,
            self.set_a,
            timing(self.gpu_ms_a, self.spread_a, self.mrays_per_s_a, self.rays_a),
            self.set_b,
            timing(self.gpu_ms_b, self.spread_b, self.mrays_per_s_b, self.rays_b),
            self.timing.as_ref().map_or("n/a".into(), |t| format!("{:.3}: {}", t.interval.ratio, t.verdict)),
            self.raygen_stack_bytes_a,
            self.raygen_stack_bytes_b,
        );
        s += &self.placements_a.spread_line("  ", "a");
        s += &self.placements_b.spread_line("  ", "b");
        s += &self.placements_a.retimed_lines("  ", "set a");
        s += &self.placements_b.retimed_lines("  ", "set b");
        for (set, written) in [(&self.set_a, &self.diff.written_a), (&self.set_b, &self.diff.written_b)] {
            for problem in written.problems(set, "pixels") {
                s += &format!("  {problem} (magenta in diff.png)\n");
            }
        }
        let pixels = (u64::from(self.width) * u64::from(self.height)).max(1) as f64;
        let pct = |n: u64| 100.0 * n as f64 / pixels;
        let d = &self.diff.color;
        s += &format!(
            "  rmse {:.6}  psnr {}  max diff {} steps\n  pixels over {} steps: {} ({:.3}%)\n  hit mismatches: {} ({:.3}%), {} off silhouette; set apart: {} on edges inside a mesh, {} at a cutout's alpha cutoff\n",
            d.rmse,
            if d.psnr.is_finite() { format!("{:.1} dB", d.psnr) } else { "inf".into() },
            d.max_abs_diff,
            self.pixel_threshold,
            d.pixels_over_threshold,
            pct(d.pixels_over_threshold),
            self.diff.hit_mismatches,
            pct(self.diff.hit_mismatches),
            self.diff.hit_mismatches_off_silhouette,
            self.diff.internal_edges,
            self.diff.alpha_edges,
        );
        if self.diff.alpha_edges > 0 {
            s += "  (the colour figures leave out the pixels at a cutout's alpha cutoff: violet in diff.png)\n";
        }
        s += &pixel_lines(&self.pixels, "  ");
        if self.pass {
            s += "  PASS: within the scene's parity tolerance\n";
        } else {
            s += &format!("  FAIL: {}\n", self.failures.join("; "));
        }
        s
    }
}
