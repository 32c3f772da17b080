//! What a trace needs for one scene, shader set and ray generation stage: the uploaded scene,
//! the pipeline, its descriptors and SBT, and the warm-up that brings GPU clocks up first.

use super::barriers::{transition, STORAGE_IMAGE, UNUSED_IMAGE};
use super::layout::LayoutDraw;
use super::libraries::Libraries;
use super::pipeline::{descriptor_bindings, ScenePipeline};
use super::tracing::Trace;
use super::upload::{upload_shared, SceneResources, UploadedScene};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::sets::ShaderSet;
use crate::vk::buffer::Buffer;
use crate::vk::commands::OneShot;
use crate::vk::context::{Context, PipelineKind};
use crate::vk::descriptors::{DescriptorSet, DescriptorTargets};
use crate::vk::image::StorageImage;
use crate::vk::pipeline::pool_sizes;
use crate::vk::sbt::ShaderBindingTable;
use crate::vk::timing::Timestamps;
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::rc::Rc;
use std::sync::Arc;
use twinray_shared::bindings as b;

/// What a trace needs, built for one scene, shader set and ray generation stage. The caller's
/// extra buffers (hit ids, probe rays and results) must outlive it.
pub(crate) struct Prepared {
    pub one_shot: OneShot,
    pub image: Rc<StorageImage>,
    pub pipeline: ScenePipeline,
    pub descriptors: DescriptorSet,
    /// None for the compute renderer.
    pub sbt: Option<ShaderBindingTable>,
    /// The probe's witness passes (see `pipeline::PROBE_WITNESSES`), those its pipeline has.
    pub witness_sbts: Vec<ShaderBindingTable>,
    _resources: Rc<SceneResources>,
}

/// GPU time warm-up traces take at least, when any are asked for: GPU clocks leave their
/// idle state over hundreds of milliseconds, and a trace timed before they are up runs several
/// times slower (docs/measuring.md, *Where the timing rules come from*).
pub const MIN_WARM_MS: f64 = 1000.0;
const MAX_WARM_TRACES: u32 = 10_000;

/// GPU time the warm-up traces of each place after a render's first take at least, when any
/// are asked for. The clocks are up by then, and a place made in tens of milliseconds (its
/// spacers made from the driver's cache) finds them up (docs/measuring.md). A place whose
/// making took longer warms up for `MIN_WARM_MS` (`placement::LONG_GAP_MS`).
pub const PLACE_WARM_MS: f64 = 20.0;

/// `MIN_WARM_MS`, or the milliseconds in `TWINRAY_MIN_WARM_MS`: for measuring how much
/// warm-up a GPU needs (docs/measuring.md), in every process a bench starts.
pub(crate) fn min_warm_ms() -> Result<f64> {
    warm_ms("TWINRAY_MIN_WARM_MS", MIN_WARM_MS)
}

/// `PLACE_WARM_MS`, or the milliseconds in `TWINRAY_PLACE_WARM_MS`.
pub(crate) fn place_warm_ms() -> Result<f64> {
    warm_ms("TWINRAY_PLACE_WARM_MS", PLACE_WARM_MS)
}

fn warm_ms(variable: &str, default: f64) -> Result<f64> {
    let Ok(text) = std::env::var(variable) else { return Ok(default) };
    let ms = text.trim().parse::<f64>().ok().filter(|ms| ms.is_finite() && *ms >= 0.0);
    ms.ok_or_else(|| Error::Input(format!("{variable} must be milliseconds, 0 or more (got {text:?})")))
}

impl Prepared {
    /// The trace of this pipeline over `launch`: `runs` timed traces after warm-up traces that
    /// are at least `warmup` and, when `warmup` > 0 and the device can time, at least
    /// `MIN_WARM_MS` of GPU time in the same submission (two traces run first to count them).
    pub fn trace<'a>(
        &'a self,
        ctx: &Arc<Context>,
        timestamps: Option<&'a Timestamps>,
        launch: (u32, u32),
        (warmup, runs): (u32, u32),
    ) -> Result<Trace<'a>> {
        self.trace_warmed(ctx, timestamps, launch, (warmup, runs), min_warm_ms()?)
    }

    /// [`Self::trace`] with `warm_ms` of warm-up GPU time in place of `MIN_WARM_MS`.
    pub fn trace_warmed<'a>(
        &'a self,
        ctx: &Arc<Context>,
        timestamps: Option<&'a Timestamps>,
        launch: (u32, u32),
        (warmup, runs): (u32, u32),
        warm_ms: f64,
    ) -> Result<Trace<'a>> {
        let trace = Trace {
            pipeline: &self.pipeline.rt,
            descriptors: &self.descriptors,
            sbt: self.sbt.as_ref(),
            workgroup: self.pipeline.workgroup.unwrap_or((1, 1)),
            timestamps,
            launch,
            warmup,
            runs,
        };
        let Some(one) = (if warmup > 0 && timestamps.is_some() { Timestamps::new(ctx, 1)? } else { None }) else {
            return Ok(trace);
        };
        // The second trace is the one timed: the first may include lazy compilation (lavapipe).
        let first = Trace { timestamps: Some(&one), warmup: 1, runs: 1, ..trace };
        self.one_shot.run_units(2, |device, cmd| {
            transition(device, cmd, self.image.raw, UNUSED_IMAGE, STORAGE_IMAGE);
            first.record(ctx, cmd);
            Ok(())
        })?;
        let ms = one.read_ms()?.first().copied().unwrap_or(warm_ms);
        let needed = (warm_ms / ms.max(1e-6)).ceil().min(f64::from(MAX_WARM_TRACES)) as u32;
        Ok(Trace { warmup: warmup.max(needed), ..trace })
    }
}

/// Uploads the scene and builds the pipeline (with ray generation stage `raygen`), its
/// descriptors (the scene's buffers plus `extra`) and SBT; frame constants for `frame` pixels,
/// output image of `image` pixels.
pub(crate) fn prepare(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    raygen: &'static str,
    (frame, image_size): ((u32, u32), (u32, u32)),
    extra: &[(u32, &Buffer)],
) -> Result<Prepared> {
    Ok(prepare_uploaded(ctx, scene, set, raygen, (frame, image_size), extra)?.1)
}

/// [`prepare`], with the upload kept: a probe moves it between its launches
/// (`UploadedScene::centre`).
pub(crate) fn prepare_uploaded(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    raygen: &'static str,
    (frame, image_size): ((u32, u32), (u32, u32)),
    extra: &[(u32, &Buffer)],
) -> Result<(UploadedScene, Prepared)> {
    let image = Rc::new(StorageImage::new(ctx, image_size.0, image_size.1)?);
    let libraries = Libraries::of(ctx);
    let linking = (ctx.pipeline_kind() == PipelineKind::Libraries).then_some(&libraries);
    let uploaded = upload_shared(ctx, scene, None, frame)?;
    let prepared = prepare_on(ctx, &uploaded, (set, linking), (raygen, LayoutDraw::Sbt), image, extra)?;
    Ok((uploaded, prepared))
}

/// The pipeline of `set` (ray generation stage `raygen`; linked from `libraries` when given,
/// else whole; laid out as `layout` draws) over an uploaded scene, with its descriptors (the scene's
/// buffers, the output `image` and `extra`) and SBT.
pub(crate) fn prepare_on(
    ctx: &Arc<Context>,
    scene: &UploadedScene,
    (set, libraries): (&ShaderSet, Option<&Libraries>),
    (raygen, layout): (&'static str, LayoutDraw),
    image: Rc<StorageImage>,
    extra: &[(u32, &Buffer)],
) -> Result<Prepared> {
    let resources = scene.resources.clone();
    let pipeline = ScenePipeline::new(ctx, set, &scene.data.plan, (raygen, layout), libraries)?;
    let storage = vk::DescriptorType::STORAGE_BUFFER;
    let mut buffers: Vec<_> =
        resources.buffers.borrow().iter().map(|(binding, ty, buffer)| (*binding, buffer.raw, *ty)).collect();
    buffers.extend(extra.iter().map(|(binding, buffer)| (*binding, buffer.raw, storage)));
    let targets = DescriptorTargets {
        tlas: resources.tlas.borrow().accel.raw,
        tlas_binding: b::BINDING_TLAS,
        image_view: image.view,
        image_binding: b::BINDING_IMAGE,
        buffers,
        textures: (b::BINDING_TEXTURES, super::textures::slots(&resources.textures)),
    };
    let descriptors = DescriptorSet::new(ctx, pipeline.rt.set_layout, &pool_sizes(&descriptor_bindings()), &targets)?;
    let table = |records: &[Vec<u32>; 4]| ShaderBindingTable::new(ctx, pipeline.rt.raw, pipeline.group_count, records);
    let sbt = if pipeline.group_count == 0 { None } else { Some(table(&pipeline.sbt_records)?) };
    let witness_sbts = pipeline.witness_records.iter().map(table).collect::<Result<Vec<_>>>()?;
    Ok(Prepared {
        one_shot: OneShot::new(ctx)?,
        image,
        pipeline,
        descriptors,
        sbt,
        witness_sbts,
        _resources: resources,
    })
}

/// A device-local storage buffer of `size` bytes that can be copied out and filled (with the
/// sentinel, before a set writes it).
pub(crate) fn storage_buffer(ctx: &Arc<Context>, name: &str, size: u64) -> Result<Buffer> {
    let usage =
        vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC | vk::BufferUsageFlags::TRANSFER_DST;
    Buffer::new(ctx, name, size, usage, MemoryLocation::GpuOnly)
}
