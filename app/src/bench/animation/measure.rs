//! Measuring: every scene with every TLAS mode, frame by frame, and the summary per mode.

use serde::Serialize;
use std::sync::Arc;
use twinray_host::error::Result;
use twinray_host::render::{placement, AsWork, FrameRenderer, RenderOptions, TlasMode};
use twinray_host::scene::Scene;
use twinray_host::sets::ShaderSet;
use twinray_host::util::interval::RatioInterval;
use twinray_host::util::progress;
use twinray_host::util::stats::median;
use twinray_host::vk::context::Context;

/// What to measure.
#[derive(Clone, Debug)]
pub struct AnimateConfig {
    /// The scene at each instance count (see [`super::resize_grid`]).
    pub scenes: Vec<Scene>,
    pub set: ShaderSet,
    pub modes: Vec<TlasMode>,
    /// Frames 0..frames of each scene.
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    pub warmup: u32,
    pub runs: u32,
    /// Times the whole animation is rendered, each mode's pipeline made afresh each time in
    /// an order of its own (see `render::placement`); each ratio's interval is over them.
    pub placements: u32,
}

/// One frame of one scene and mode.
#[derive(Clone, Debug, Serialize)]
pub struct FrameRow {
    pub instances: usize,
    pub mode: String,
    /// Which rendering of the animation (0-based; see `AnimateConfig::placements`).
    pub placement: u32,
    pub frame: u32,
    pub as_work: AsWork,
    pub as_ms: Option<f64>,
    /// Median of the frame's timed traces.
    pub trace_ms: Option<f64>,
    pub rays: u64,
}

/// One scene and mode over all its frames.
#[derive(Clone, Debug, Serialize)]
pub struct ModeSummary {
    pub instances: usize,
    pub mode: String,
    /// Median GPU ms of the frames' full builds (the first frame's included) and updates.
    pub build_ms: Option<f64>,
    pub update_ms: Option<f64>,
    /// Median AS ms over every frame: what the mode costs per frame.
    pub as_ms_per_frame: Option<f64>,
    /// The first placement's trace time at the first and the last frame.
    pub trace_ms_first: Option<f64>,
    pub trace_ms_last: Option<f64>,
    /// The last frame's trace time over the same frame's with a TLAS rebuilt for fast trace:
    /// what the mode's TLAS costs in trace time after the scene's full motion; one ratio per
    /// placement, with the interval over them.
    pub trace_vs_rebuild_last: Option<RatioInterval>,
    /// The same, of each placement's median ratio over every frame.
    pub trace_vs_rebuild_median: Option<RatioInterval>,
}

/// Everything the bench measured.
#[derive(Clone, Debug, Serialize)]
pub struct AnimateReport {
    pub device: String,
    pub cpu_threads: Option<u32>,
    pub scene: String,
    pub set: String,
    pub width: u32,
    pub height: u32,
    pub frames: u32,
    pub runs: u32,
    pub warmup: u32,
    pub placements: u32,
    pub rows: Vec<FrameRow>,
    pub summaries: Vec<ModeSummary>,
}

/// Renders every scene with every mode, once per placement; `progress` hears of each scene as
/// it starts. The modes take turns frame by frame, in an order that rotates each frame, each
/// after warm-up traces of its own, so that the GPU's clock state reaches every mode alike:
/// measured on the H100 with the modes one after another, trace and TLAS times of one mode
/// jumped 3x together mid-run when the clocks dropped, which a per-mode comparison cannot tell
/// from a slower TLAS. Each mode has its own pipeline, so each placement makes them afresh:
/// where the driver put one mode's code would otherwise pass for its TLAS's cost.
pub fn run(ctx: &Arc<Context>, config: &AnimateConfig, mut progress: impl FnMut(&str)) -> Result<AnimateReport> {
    let (width, height, warmup, runs) = (config.width, config.height, config.warmup, config.runs);
    let opts = RenderOptions::once(width, height, warmup, runs);
    let mut rows = Vec::new();
    for scene in &config.scenes {
        let instances = scene.file.objects.len();
        for (p, order) in placement::orders(config.modes.len(), 0, config.placements).iter().enumerate() {
            progress(&format!(
                "{instances} instances, {} frames, modes in turn (placement {} of {})",
                config.frames,
                p + 1,
                config.placements
            ));
            rows.extend(animate(ctx, scene, config, &opts, (p as u32, order))?);
        }
    }
    ctx.check_validation()?;
    let summaries = summarise(&rows, &config.modes);
    Ok(AnimateReport {
        device: ctx.info.name.clone(),
        cpu_threads: ctx.info.cpu_threads,
        scene: config.scenes.first().map_or_else(String::new, |s| s.name().to_string()),
        set: config.set.to_string(),
        width: config.width,
        height: config.height,
        frames: config.frames,
        runs: config.runs,
        warmup: config.warmup,
        placements: config.placements,
        rows,
        summaries,
    })
}

/// The frames of one placement of `scene`: renderers made in `order` (indices of the modes).
fn animate(
    ctx: &Arc<Context>,
    scene: &Scene,
    config: &AnimateConfig,
    opts: &RenderOptions,
    (placement, order): (u32, &[usize]),
) -> Result<Vec<FrameRow>> {
    let instances = scene.file.objects.len();
    let set = std::slice::from_ref(&config.set);
    let mut renderers = Vec::with_capacity(order.len());
    for &m in order {
        renderers.push((m, FrameRenderer::new(ctx, scene, set, opts, 0, config.modes[m])?));
    }
    let mut rows = Vec::new();
    for frame in 0..config.frames {
        let n = renderers.len();
        let mut measured = Vec::with_capacity(n);
        for k in 0..n {
            let (m, renderer) = &mut renderers[(k + frame as usize) % n];
            let f = renderer.render(frame, true)?;
            let out = &f.outputs[0];
            out.written.require(&config.set.to_string(), "pixels", &format!("{} frame {frame}", scene.name()))?;
            let (as_work, as_ms, trace_ms, rays) = (f.as_work, f.as_ms, out.median_ms(), out.rays.total());
            let mode = config.modes[*m].name();
            measured.push((*m, FrameRow { instances, mode, placement, frame, as_work, as_ms, trace_ms, rays }));
        }
        measured.sort_by_key(|(m, _)| *m);
        rows.extend(measured.into_iter().map(|(_, row)| row));
        progress::report("frames", u64::from(frame + 1), u64::from(config.frames));
    }
    Ok(rows)
}

/// Per instance count and mode: medians of the AS work by kind, the trace time at the first
/// and last frames, and trace time against the full-rebuild mode's at the same frames.
pub fn summarise(rows: &[FrameRow], modes: &[TlasMode]) -> Vec<ModeSummary> {
    let mut counts: Vec<usize> = rows.iter().map(|r| r.instances).collect();
    counts.dedup();
    let rebuild = TlasMode { kind: twinray_host::render::TlasKind::Rebuild, rebuild_every: 0 }.name();
    let mut out = Vec::new();
    for &instances in &counts {
        let of = |mode: &str| -> Vec<&FrameRow> {
            rows.iter().filter(|r| r.instances == instances && r.mode == mode).collect()
        };
        let reference = of(&rebuild);
        for mode in modes.iter().map(|m| m.name()) {
            let frames = of(&mode);
            let as_of = |work: AsWork| {
                median(&frames.iter().filter(|r| r.as_work == work).filter_map(|r| r.as_ms).collect::<Vec<_>>())
            };
            // Per placement: the median ratio over its frames, and its last frame's ratio.
            let mut medians = Vec::new();
            let mut lasts = Vec::new();
            for p in placements(&frames) {
                let ratios: Vec<f64> = frames
                    .iter()
                    .filter(|r| r.placement == p)
                    .filter_map(|r| {
                        let b = reference.iter().find(|b| b.placement == p && b.frame == r.frame)?;
                        Some(r.trace_ms? / b.trace_ms.filter(|&ms| ms > 0.0)?)
                    })
                    .collect();
                medians.extend(median(&ratios).map(f64::ln));
                lasts.extend(ratios.last().map(|r| r.ln()));
            }
            let (first, last) = (
                frames.iter().filter(|r| r.placement == 0).min_by_key(|r| r.frame),
                frames.iter().filter(|r| r.placement == 0).max_by_key(|r| r.frame),
            );
            out.push(ModeSummary {
                instances,
                mode: mode.clone(),
                build_ms: as_of(AsWork::Build),
                update_ms: as_of(AsWork::Update),
                as_ms_per_frame: median(&frames.iter().filter_map(|r| r.as_ms).collect::<Vec<_>>()),
                trace_ms_first: first.and_then(|r| r.trace_ms),
                trace_ms_last: last.and_then(|r| r.trace_ms),
                trace_vs_rebuild_last: RatioInterval::of_logs(&lasts),
                trace_vs_rebuild_median: RatioInterval::of_logs(&medians),
            });
        }
    }
    out
}

/// The placements `rows` come from, in order.
fn placements(rows: &[&FrameRow]) -> Vec<u32> {
    let mut all: Vec<u32> = rows.iter().map(|r| r.placement).collect();
    all.sort_unstable();
    all.dedup();
    all
}
