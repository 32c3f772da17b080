//! Measuring: every scene with every TLAS mode, frame by frame, and the summary per mode.

use crate::error::Result;
use crate::render::{AsWork, FrameRenderer, RenderOptions, TlasMode};
use crate::scene::Scene;
use crate::shaders::ShaderSet;
use crate::util::progress;
use crate::util::stats::median;
use crate::vk::context::Context;
use serde::Serialize;
use std::sync::Arc;

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
}

/// One frame of one scene and mode.
#[derive(Clone, Debug, Serialize)]
pub struct FrameRow {
    pub instances: usize,
    pub mode: String,
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
    pub trace_ms_first: Option<f64>,
    pub trace_ms_last: Option<f64>,
    /// The last frame's trace time over the same frame's with a TLAS rebuilt for fast trace:
    /// what the mode's TLAS costs in trace time after the scene's full motion.
    pub trace_vs_rebuild_last: Option<f64>,
    /// The same, as the median over every frame.
    pub trace_vs_rebuild_median: Option<f64>,
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
    pub rows: Vec<FrameRow>,
    pub summaries: Vec<ModeSummary>,
}

/// Renders every scene with every mode; `progress` hears of each scene as it starts. The
/// modes take turns frame by frame, in an order that rotates each frame, each after warm-up
/// traces of its own, so that the GPU's clock state reaches every mode alike: measured on the
/// H100 with the modes one after another, trace and TLAS times of one mode jumped 3x together
/// mid-run when the clocks dropped, which a per-mode comparison cannot tell from a slower TLAS.
pub fn run(ctx: &Arc<Context>, config: &AnimateConfig, mut progress: impl FnMut(&str)) -> Result<AnimateReport> {
    let opts = RenderOptions { width: config.width, height: config.height, warmup: config.warmup, runs: config.runs };
    let mut rows = Vec::new();
    for scene in &config.scenes {
        let instances = scene.file.objects.len();
        progress(&format!("{instances} instances, {} frames, modes in turn", config.frames));
        let set = std::slice::from_ref(&config.set);
        let mut renderers = config
            .modes
            .iter()
            .map(|&mode| FrameRenderer::new(ctx, scene, set, &opts, 0, mode))
            .collect::<Result<Vec<_>>>()?;
        for frame in 0..config.frames {
            let n = renderers.len();
            let mut measured = Vec::with_capacity(n);
            for k in 0..n {
                let m = (k + frame as usize) % n;
                let f = renderers[m].render(frame, true)?;
                let out = &f.outputs[0];
                out.written.require(&config.set.to_string(), "pixels", &format!("{} frame {frame}", scene.name()))?;
                measured.push((
                    m,
                    FrameRow {
                        instances,
                        mode: config.modes[m].name(),
                        frame,
                        as_work: f.as_work,
                        as_ms: f.as_ms,
                        trace_ms: out.median_ms(),
                        rays: out.rays.total(),
                    },
                ));
            }
            measured.sort_by_key(|(m, _)| *m);
            rows.extend(measured.into_iter().map(|(_, row)| row));
            progress::report("frames", u64::from(frame + 1), u64::from(config.frames));
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
        rows,
        summaries,
    })
}

/// Per instance count and mode: medians of the AS work by kind, the trace time at the first
/// and last frames, and trace time against the full-rebuild mode's at the same frames.
pub fn summarise(rows: &[FrameRow], modes: &[TlasMode]) -> Vec<ModeSummary> {
    let mut counts: Vec<usize> = rows.iter().map(|r| r.instances).collect();
    counts.dedup();
    let rebuild = TlasMode { kind: crate::render::TlasKind::Rebuild, rebuild_every: 0 }.name();
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
            let ratios: Vec<f64> = frames
                .iter()
                .zip(&reference)
                .filter_map(|(r, b)| Some(r.trace_ms? / b.trace_ms.filter(|&ms| ms > 0.0)?))
                .collect();
            out.push(ModeSummary {
                instances,
                mode: mode.clone(),
                build_ms: as_of(AsWork::Build),
                update_ms: as_of(AsWork::Update),
                as_ms_per_frame: median(&frames.iter().filter_map(|r| r.as_ms).collect::<Vec<_>>()),
                trace_ms_first: frames.first().and_then(|r| r.trace_ms),
                trace_ms_last: frames.last().and_then(|r| r.trace_ms),
                trace_vs_rebuild_last: (!reference.is_empty()).then(|| ratios.last().copied()).flatten(),
                trace_vs_rebuild_median: median(&ratios),
            });
        }
    }
    out
}
