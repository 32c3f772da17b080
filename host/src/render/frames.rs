//! Rendering the frames of a moving scene with one or more shader sets. BLASes are built once;
//! per frame only what moved is rewritten (instance transforms, lights, frame constants) and
//! the TLAS is rebuilt or updated in place, in its own submission between timestamps, so the
//! acceleration-structure time and each set's trace time are measured apart.

use super::barriers::{transition, STORAGE_IMAGE, UNUSED_IMAGE};
use super::output::{RenderOptions, RenderOutput};
use super::sets::{check_device_limits, copy_outputs, SetRender, SharedOutputs};
use super::tracing::{self, Trace};
use super::upload::upload_moving;
use crate::error::{Error, Result};
use crate::scene::{check_size, frame_data, Scene};
use crate::shaders::ShaderSet;
use crate::util::progress;
use crate::vk::accel::TlasFlags;
use crate::vk::commands::OneShot;
use crate::vk::context::Context;
use crate::vk::timing::Timestamps;
use serde::Serialize;
use std::ops::Range;
use std::sync::Arc;
use twinray_shared::bindings as b;

/// How the TLAS is remade when objects move (`--tlas`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum TlasKind {
    /// A full build every frame, preferring fast trace.
    Rebuild,
    /// A full build every frame, preferring fast build.
    FastBuild,
    /// An in-place update (refit) every frame, with a full build every `rebuild_every` frames.
    Update,
}

/// How the TLAS follows moving objects from frame to frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct TlasMode {
    pub kind: TlasKind,
    /// For `Update`: a full build every this many frames of the sequence (0: only the first).
    pub rebuild_every: u32,
}

/// What `--tlas` and `--rebuild-every` give when left out.
pub const DEFAULT_TLAS: TlasMode = TlasMode { kind: TlasKind::Update, rebuild_every: 30 };

impl TlasMode {
    /// As the command line writes it: "update (rebuild every 30)".
    pub fn name(self) -> String {
        match self.kind {
            TlasKind::Rebuild => "rebuild".into(),
            TlasKind::FastBuild => "fast-build".into(),
            TlasKind::Update if self.rebuild_every == 0 => "update".into(),
            TlasKind::Update => format!("update (rebuild every {})", self.rebuild_every),
        }
    }

    fn flags(self) -> TlasFlags {
        match self.kind {
            TlasKind::Rebuild => TlasFlags::FastTrace,
            TlasKind::FastBuild => TlasFlags::FastBuild,
            TlasKind::Update => TlasFlags::Updatable,
        }
    }

    /// The AS work of the `i`-th frame of a sequence (counted from 0) when objects move.
    fn work(self, i: u32) -> AsWork {
        let rebuild =
            i == 0 || self.kind != TlasKind::Update || (self.rebuild_every > 0 && i.is_multiple_of(self.rebuild_every));
        if rebuild {
            AsWork::Build
        } else {
            AsWork::Update
        }
    }
}

/// The acceleration-structure work a frame did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AsWork {
    /// A full TLAS build.
    Build,
    /// An in-place TLAS update.
    Update,
    /// Nothing: no object moved since the last frame.
    None,
}

/// One rendered frame.
pub struct Frame {
    pub index: u32,
    /// Seconds into the animation.
    pub time: f32,
    pub as_work: AsWork,
    /// GPU milliseconds of the frame's TLAS work; `None` without work or timestamps.
    pub as_ms: Option<f64>,
    /// One output per set, in the order of the sets.
    pub outputs: Vec<RenderOutput>,
}

/// Renders frames `frames` of `scene` with each of `sets` over one upload, handing each frame
/// to `each` as it completes. Warm-up traces run before the first frame only; each frame's
/// timed traces are interleaved between the sets as `render_sets` does.
pub fn render_frames(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[ShaderSet],
    opts: &RenderOptions,
    frames: Range<u32>,
    mode: TlasMode,
    mut each: impl FnMut(Frame) -> Result<()>,
) -> Result<()> {
    check_frames(scene, &frames)?;
    check_size(opts.width, opts.height).map_err(Error::Input)?;
    check_device_limits(ctx, opts)?;
    let size = (opts.width, opts.height);
    let first = scene.at_frame(frames.start);
    let uploaded = upload_moving(ctx, &first, size, mode.flags())?;
    let outputs = SharedOutputs::new(ctx, opts)?;
    let renders =
        sets.iter().map(|set| SetRender::new(ctx, &uploaded, &outputs, set, opts)).collect::<Result<Vec<_>>>()?;
    let one_shot = OneShot::new(ctx)?;
    let timer = Timestamps::new(ctx, 1)?;
    let moves = scene.animation.as_ref().map(|a| a.moves()).unwrap_or_default();
    let mut posed = first.file.clone();
    let mut records = uploaded.instances.clone();
    let mut traces: Vec<Trace> = Vec::new();
    let count = frames.len() as u32;
    for (i, frame) in frames.clone().enumerate() {
        let i = i as u32;
        scene.pose(frame, &mut posed);
        let data = frame_data(&posed, opts.width, opts.height);
        let resources = &uploaded.resources;
        let work = if i == 0 || moves.objects { mode.work(i) } else { AsWork::None };
        if work != AsWork::None && i > 0 {
            for (record, instance) in records.iter_mut().zip(&uploaded.data.instances) {
                record.object_to_world = data.transforms[instance.object as usize];
            }
            resources.tlas.borrow_mut().write(&records)?;
        }
        // The first frame's values went up with the scene; later, only what moves is rewritten.
        if i > 0 && moves.camera {
            resources.write(b::BINDING_FRAME, bytemuck::bytes_of(&data.uniform))?;
        }
        if i > 0 && moves.lights {
            resources.write(b::BINDING_LIGHTS, bytemuck::cast_slice(&data.lights))?;
        }
        let as_ms = if work == AsWork::None {
            None
        } else {
            let tlas = resources.tlas.borrow();
            one_shot.run(|_, cmd| {
                if let Some(t) = &timer {
                    t.reset(cmd);
                    t.begin(cmd, 0);
                }
                tlas.record(ctx, cmd, work == AsWork::Update);
                if let Some(t) = &timer {
                    t.end(cmd, 0);
                }
                Ok(())
            })?;
            timer.as_ref().map(|t| t.read_ms()).transpose()?.and_then(|ms| ms.first().copied())
        };
        traces = if i == 0 {
            // Warm-up (and its GPU-clock calibration) once, over the first frame's structures.
            let warmup = (opts.warmup, opts.runs);
            renders.iter().map(|r| r.prepared.trace(ctx, r.timestamps.as_ref(), size, warmup)).collect::<Result<_>>()?
        } else {
            traces.iter().map(|t| Trace { warmup: 0, ..*t }).collect()
        };
        let before = |device: &ash::Device, cmd| {
            if i == 0 {
                transition(device, cmd, outputs.image.raw, UNUSED_IMAGE, STORAGE_IMAGE);
            }
        };
        let after = |device: &ash::Device, cmd| copy_outputs(ctx, device, cmd, &outputs, &renders, &traces);
        tracing::submit(ctx, &one_shot, &traces, before, after)?;
        let rendered =
            renders.iter().zip(&traces).map(|(r, t)| r.output(scene, opts, t.warmup)).collect::<Result<_>>()?;
        let time = scene.animation.as_ref().map_or(0.0, |a| a.time(frame));
        each(Frame { index: frame, time, as_work: work, as_ms, outputs: rendered })?;
        progress::report("frames", u64::from(i + 1), u64::from(count));
    }
    ctx.check_validation()
}

/// A frame range must be non-empty and within the scene's frames.
pub fn check_frames(scene: &Scene, frames: &Range<u32>) -> Result<()> {
    let total = scene.frame_count();
    if frames.is_empty() || frames.end > total {
        let still = if scene.animation.is_none() { " (a still scene has one frame, 0)" } else { "" };
        return Err(Error::Input(format!(
            "frames {}..{}: {} has frames 0..{total}{still}; a range needs at least one of them",
            frames.start,
            frames.end,
            scene.name()
        )));
    }
    Ok(())
}

/// A range of frames as the command line writes it: `A..B` (B excluded), `A..=B`, `A`, or
/// `all`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameRange {
    All,
    /// First frame and one past the last.
    Span(u32, u32),
}

impl std::str::FromStr for FrameRange {
    type Err = String;

    fn from_str(text: &str) -> std::result::Result<Self, String> {
        let number = |s: &str| {
            s.trim()
                .parse::<u32>()
                .map_err(|_| format!("{text:?}: expected A..B, A..=B, A or all (frames counted from 0)"))
        };
        let text = text.trim();
        if text == "all" {
            return Ok(FrameRange::All);
        }
        let (start, end) = if let Some((a, b)) = text.split_once("..=") {
            (number(a)?, number(b)?.checked_add(1).ok_or_else(|| format!("{text:?}: too large"))?)
        } else if let Some((a, b)) = text.split_once("..") {
            (number(a)?, number(b)?)
        } else {
            let a = number(text)?;
            (a, a.saturating_add(1))
        };
        if end <= start {
            return Err(format!("{text:?}: an empty range (the end is excluded in A..B; A..=B includes it)"));
        }
        Ok(FrameRange::Span(start, end))
    }
}

impl FrameRange {
    /// The frames of `scene` this range names, checked against its frame count.
    pub fn of(self, scene: &Scene) -> Result<Range<u32>> {
        let frames = match self {
            FrameRange::All => 0..scene.frame_count(),
            FrameRange::Span(a, b) => a..b,
        };
        check_frames(scene, &frames)?;
        Ok(frames)
    }
}
