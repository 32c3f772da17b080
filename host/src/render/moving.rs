//! Rendering the frames of a moving scene. One moving scene's GPU state across frames: the upload (BLASes once, a TLAS rebuilt or
//! updated in place), each set's pipeline, and per frame the rewrite of what moved, the TLAS
//! work between timestamps and the sets' traces. Several renderers (one per TLAS mode) can
//! take turns frame by frame, so that a drift of the GPU's clocks reaches every mode alike.

use super::frames::{check_frames, AsWork, Frame, TlasMode};
use super::layout::LayoutDraw;
use super::output::RenderOptions;
use super::sets::{check_device_limits, made_as_context_says, SetRender, SharedOutputs};
use super::tracing::{self, Trace};
use super::upload::{upload_moving, Movement, UploadedScene};
use crate::error::{Error, Result};
use crate::scene::animation::Moves;
use crate::scene::file::SceneFile;
use crate::scene::{check_size, frame_data, Aabb, BlasDesc, Scene};
use crate::sets::ShaderSet;
use crate::util::activity;
use crate::vk::accel::InstanceRecord;
use crate::vk::commands::OneShot;
use crate::vk::context::Context;
use crate::vk::timing::Timestamps;
use std::ops::Range;
use std::sync::Arc;
use twinray_shared::bindings as b;

/// A moving scene set up for frame-by-frame rendering with one TLAS mode.
pub struct FrameRenderer<'a> {
    ctx: Arc<Context>,
    scene: &'a Scene,
    opts: RenderOptions,
    mode: TlasMode,
    renders: Vec<SetRender>,
    outputs: SharedOutputs,
    uploaded: UploadedScene,
    one_shot: OneShot,
    timer: Option<Timestamps>,
    moves: Moves,
    posed: SceneFile,
    records: Vec<InstanceRecord>,
    /// Each object's bounds in its own space, for the reach of each frame's rays.
    object_bounds: Vec<Aabb>,
    /// Warm-up traces per set, as the first frame's calibration found them.
    warm: Vec<u32>,
    /// Frames rendered so far.
    done: u32,
}

impl<'a> FrameRenderer<'a> {
    /// Uploads `scene` posed at frame `first` and builds each set's pipeline over it.
    pub fn new(
        ctx: &Arc<Context>,
        scene: &'a Scene,
        sets: &[ShaderSet],
        opts: &RenderOptions,
        first: u32,
        mode: TlasMode,
    ) -> Result<Self> {
        check_size(opts.width, opts.height).map_err(Error::Input)?;
        check_device_limits(ctx, opts)?;
        let start = scene.at_frame(first)?;
        let moves = scene.animation.as_ref().map(|a| a.moves()).unwrap_or_default();
        // The meshes a clip poses (skins, morph targets), the ones `at_frame` made anew: their
        // BLASes follow their vertices.
        let posed: Vec<String> = match moves.meshes {
            true => start
                .meshes
                .iter()
                .filter(|(shape, mesh)| !scene.meshes.get(*shape).is_some_and(|m| Arc::ptr_eq(m, mesh)))
                .map(|(shape, _)| shape.clone())
                .collect(),
            false => Vec::new(),
        };
        let bodies = scene.animation.as_ref().and_then(|a| a.bodies());
        let movement = Movement { flags: mode.flags(), posed: &posed, objects: moves.objects, bodies };
        let uploaded = upload_moving(ctx, &start, (opts.width, opts.height), movement)?;
        let outputs = SharedOutputs::new(ctx, opts)?;
        // One place per set: the pipelines in SBT order (`super::layout`).
        let made = made_as_context_says(ctx, sets);
        let renders = SetRender::each(ctx, &uploaded, &outputs, &made, (opts, LayoutDraw::Sbt))?;
        Ok(FrameRenderer {
            ctx: ctx.clone(),
            scene,
            opts: *opts,
            mode,
            renders,
            outputs,
            records: uploaded.instances.clone(),
            object_bounds: uploaded.object_bounds.clone(),
            uploaded,
            one_shot: OneShot::new(ctx)?,
            timer: Timestamps::new(ctx, 1)?,
            moves,
            posed: start.file,
            warm: Vec::new(),
            done: 0,
        })
    }

    /// Renders `frame`, the next of the sequence. The first frame builds the TLAS, then runs
    /// the warm-up traces the options ask for; with `warm_each`, every later frame runs as
    /// many again before its TLAS work, so that the TLAS and trace timings of every frame are
    /// taken on a GPU that is already busy.
    pub fn render(&mut self, frame: u32, warm_each: bool) -> Result<Frame> {
        let i = self.done;
        self.done += 1;
        let moved = self.moves.objects || self.moves.meshes;
        let work = if i == 0 || moved { self.mode.work(i) } else { AsWork::None };
        self.rewrite(frame, i, work)?;
        let ctx = &self.ctx;
        let _doing = activity::doing(format!("frame {frame}"));
        let size = (self.opts.width, self.opts.height);
        let runs = self.opts.runs;
        let (as_ms, traces) = if i == 0 {
            let as_ms = self.tlas_work(work, &[])?;
            self.trace_outputs()?;
            // Warm-up (and its GPU-clock calibration) over the first frame's structures.
            let traces = self
                .renders
                .iter()
                .map(|r| r.timed_trace(ctx, size, (self.opts.warmup, runs)))
                .collect::<Result<Vec<_>>>()?;
            self.warm = traces.iter().map(|t| between_frames(t.warmup, self.opts.warmup)).collect();
            (as_ms, traces)
        } else {
            let cold = self.renders.iter().map(|r| r.timed_trace(ctx, size, (0, runs))).collect::<Result<Vec<_>>>()?;
            let warm: Vec<Trace> = if warm_each {
                cold.iter().zip(&self.warm).map(|(t, &warmup)| Trace { warmup, ..*t }).collect()
            } else {
                Vec::new()
            };
            let as_ms = self.tlas_work(work, &warm)?;
            self.trace_outputs()?;
            (as_ms, cold)
        };
        let _timed = activity::doing("the timed traces");
        tracing::submit(ctx, &self.one_shot, &traces, |_, _| {}, |_, _| {})?;
        let outputs = self
            .renders
            .iter()
            .zip(&traces)
            .map(|(r, t)| r.output(self.scene, &self.opts, t.warmup, self.uploaded.accel))
            .collect::<Result<_>>()?;
        let time = self.scene.time(frame);
        Ok(Frame { index: frame, time, as_work: work, as_ms, outputs })
    }

    /// Each set's output of this frame, poisoned first (see `SetRender::trace_output`).
    fn trace_outputs(&self) -> Result<()> {
        let size = (self.opts.width, self.opts.height);
        self.renders.iter().try_for_each(|r| r.trace_output(&self.ctx, &self.outputs, size))
    }

    /// Poses frame `frame` (the `i`-th) and rewrites what moved: the TLAS instances when the
    /// TLAS is remade, the frame constants when the camera moves, the lights when they do. The
    /// first frame's values went up with the scene.
    fn rewrite(&mut self, frame: u32, i: u32, work: AsWork) -> Result<()> {
        if i == 0 {
            return Ok(());
        }
        self.scene.pose(frame, &mut self.posed);
        let posed = self.scene.file_on_gpu(&self.posed);
        let data = frame_data(&posed, self.opts.width, self.opts.height, &self.object_bounds);
        let resources = &self.uploaded.resources;
        if work != AsWork::None {
            resources.place(&mut self.records, &self.uploaded.data.instances, &data.transforms)?;
        }
        if self.moves.meshes {
            self.rewrite_meshes(frame)?;
        }
        // Moving objects move the scene's bounds, and with them the rays' reach.
        if self.moves.camera || self.moves.objects {
            resources.write(b::BINDING_FRAME, bytemuck::bytes_of(&data.uniform))?;
        }
        if self.moves.lights {
            // Only the scene's lights: the zeros after them, up to MAX_LIGHTS, never change.
            resources.write(b::BINDING_LIGHTS, bytemuck::cast_slice(&data.lights))?;
        }
        Ok(())
    }

    /// Writes the vertices of the meshes the clip poses at `frame` over theirs, for their
    /// BLASes to follow (`tlas_work`).
    fn rewrite_meshes(&self, frame: u32) -> Result<()> {
        let animation = self.scene.animation.as_ref().expect("meshes move only in an animation");
        let resources = &self.uploaded.resources;
        for (shape, mesh) in animation.meshes(frame).map_err(Error::Input)? {
            let Some((_, base, blas, _)) = resources.moving.iter().find(|m| m.0 == shape) else {
                return Err(Error::Input(format!("frame {frame}: {shape} is posed but was not at the first frame")));
            };
            let BlasDesc::Triangles { vertex_count, .. } = self.uploaded.data.blases[*blas] else { continue };
            if mesh.vertices.len() != vertex_count as usize {
                return Err(Error::Input(format!(
                    "frame {frame}: {shape} has {} vertices posed, {vertex_count} at the first frame",
                    mesh.vertices.len()
                )));
            }
            resources.write_vertices(*base, &mesh.vertices)?;
        }
        Ok(())
    }

    /// The warm-up traces `warm`, then the acceleration structures' work between timestamps
    /// (the posed meshes' BLASes, then the TLAS over them): its GPU milliseconds.
    fn tlas_work(&self, work: AsWork, warm: &[Trace]) -> Result<Option<f64>> {
        if work == AsWork::None && warm.is_empty() {
            return Ok(None);
        }
        let tlas = self.uploaded.resources.tlas.borrow();
        let timer = self.timer.as_ref().filter(|_| work != AsWork::None);
        self.one_shot.run(|_, cmd| {
            tracing::record_warmup(&self.ctx, cmd, warm);
            if work != AsWork::None {
                if let Some(t) = timer {
                    t.reset(cmd);
                    t.begin(cmd, 0);
                }
                for (.., blas) in &self.uploaded.resources.moving {
                    blas.record(&self.ctx, cmd, work == AsWork::Update);
                }
                tlas.record(&self.ctx, cmd, work == AsWork::Update);
                if let Some(t) = timer {
                    t.end(cmd, 0);
                }
            }
            Ok(())
        })?;
        Ok(timer.map(|t| t.read_ms()).transpose()?.and_then(|ms| ms.first().copied()))
    }
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
    let count = frames.len() as u64;
    let mut renderer = FrameRenderer::new(ctx, scene, sets, opts, frames.start, mode)?;
    for (i, frame) in frames.enumerate() {
        each(renderer.render(frame, false)?)?;
        crate::util::progress::report("frames", i as u64 + 1, count);
    }
    drop(renderer);
    // Every object of the render is destroyed by now: catch what the layer said about that too.
    ctx.check_validation()
}

/// The warm-up before each later frame: a fifth of the first frame's `first` traces (which
/// filled `MIN_WARM_MS` of GPU time after the idle of building pipelines), at least the
/// `asked` count. A frame follows the last on a GPU busy a moment ago, and 200 ms each (the
/// warm-up floor of the time) kept per-frame times steady (docs/measuring.md, animate-bench).
fn between_frames(first: u32, asked: u32) -> u32 {
    first.div_ceil(5).max(asked.min(first))
}
