//! Rendering a scene with a shader set: build the acceleration structures, pipeline and SBT,
//! trace (warm-up runs, then timed runs between timestamps), read back colour and hit ids.

use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::shader_set::ShaderSet;
use crate::tracing::{self, Trace};
use crate::upload::{upload_shared, SceneResources, UploadedScene};
use crate::vk::buffer::Buffer;
use crate::vk::commands::{memory_barrier, OneShot};
use crate::vk::context::Context;
use crate::vk::descriptors::{DescriptorSet, DescriptorTargets};
use crate::vk::image::{StorageImage, COLOR_RANGE};
use crate::vk::pipeline::{pool_sizes, RtPipeline};
use crate::vk::sbt::ShaderBindingTable;
use crate::vk::timing::Timestamps;
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::rc::Rc;
use std::sync::Arc;
use twinray_shared::bindings as b;

/// `RenderOutput::hit_ids` of a pixel whose first primary ray hit nothing.
pub const NO_HIT_ID: u64 = u64::MAX;

/// Largest image side, and largest pixel count, twinray accepts before asking the device.
pub const MAX_SIDE: u32 = 16384;
pub const MAX_PIXELS: u64 = 8192 * 8192;

/// Checks an image size against twinray's own limits.
pub fn check_size(width: u32, height: u32) -> std::result::Result<(), String> {
    if width == 0 || height == 0 {
        return Err(format!("image size {width}x{height}: width and height must be at least 1"));
    }
    if width > MAX_SIDE || height > MAX_SIDE || u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(format!(
            "image size {width}x{height} is too large (at most {MAX_SIDE} per side and {MAX_PIXELS} pixels)"
        ));
    }
    Ok(())
}

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
    pub fn total(&self) -> u64 {
        self.primary + self.shadow
    }
}

impl RenderOutput {
    /// Median GPU time of the timed traces.
    pub fn median_ms(&self) -> Option<f64> {
        crate::stats::median(&self.gpu_ms)
    }

    /// Median and interquartile range of the timed traces.
    pub fn spread(&self) -> Option<crate::stats::Spread> {
        crate::stats::Spread::of(&self.gpu_ms)
    }

    /// Millions of rays per second at the median GPU time.
    pub fn mrays_per_s(&self) -> Option<f64> {
        self.median_ms().filter(|&ms| ms > 0.0).map(|ms| self.rays.total() as f64 / (ms * 1e3))
    }
}

pub fn render(ctx: &Arc<Context>, scene: &Scene, set: &ShaderSet, opts: &RenderOptions) -> Result<RenderOutput> {
    let mut outputs = render_sets(ctx, scene, std::slice::from_ref(set), opts)?;
    Ok(outputs.remove(0))
}

/// Renders `scene` with each of `sets` over the same acceleration structures and outputs,
/// timed interleaved (see `tracing`). When several timed runs are asked for, it renders once
/// per rotation of the sets' order, so that each set is built and traced first once, and pools
/// each set's timed traces: on the H200, a pipeline's time moved by up to 7% with the order the
/// pipelines were built in, the same way in every repeat (lights at 16 spp: Rust/GLSL 1.03 with
/// GLSL built first, 1.14 with Rust first). Images and hit ids are the first rotation's.
pub fn render_sets(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[ShaderSet],
    opts: &RenderOptions,
) -> Result<Vec<RenderOutput>> {
    let mut outputs = render_and_release(ctx, scene, sets, opts)?;
    let rotations = if opts.runs > 1 { sets.len() } else { 1 };
    for shift in 1..rotations {
        let rotated: Vec<_> = sets.iter().cycle().skip(shift).take(sets.len()).copied().collect();
        for (k, out) in render_and_release(ctx, scene, &rotated, opts)?.into_iter().enumerate() {
            outputs[(k + shift) % sets.len()].gpu_ms.extend(out.gpu_ms);
        }
    }
    // Every object of the render is destroyed by now: catch what the layer said about that too.
    ctx.check_validation()?;
    Ok(outputs)
}

/// What a trace needs, built for one scene, shader set and ray generation stage. The caller's
/// extra buffers (hit ids, probe rays and results) must outlive it.
pub(crate) struct Prepared {
    pub one_shot: OneShot,
    pub image: Rc<StorageImage>,
    pub pipeline: RtPipeline,
    pub descriptors: DescriptorSet,
    pub sbt: ShaderBindingTable,
    _resources: Rc<SceneResources>,
}

/// GPU time warm-up traces take at least, when any are asked for: GPU clocks leave their
/// idle state over tens of milliseconds. Measured on the H200 with 3 warm-up traces of a few
/// ms: the same configuration timed 1x in one run and 2-3x in the next, with a tight IQR
/// each time (the clock was stable within a run, but in another state).
pub const MIN_WARM_MS: f64 = 200.0;
const MAX_WARM_TRACES: u32 = 10_000;

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
        let trace = Trace {
            pipeline: &self.pipeline,
            descriptors: &self.descriptors,
            sbt: &self.sbt,
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
        self.one_shot.run(|device, cmd| {
            transition(device, cmd, self.image.raw, UNUSED_IMAGE, STORAGE_IMAGE);
            first.record(ctx, cmd);
            Ok(())
        })?;
        let ms = one.read_ms()?.first().copied().unwrap_or(MIN_WARM_MS);
        let needed = (MIN_WARM_MS / ms.max(1e-6)).ceil().min(f64::from(MAX_WARM_TRACES)) as u32;
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
    let image = Rc::new(StorageImage::new(ctx, image_size.0, image_size.1)?);
    prepare_on(ctx, &upload_shared(ctx, scene, frame)?, set, raygen, image, extra)
}

/// The pipeline of `set` (ray generation stage `raygen`) over an uploaded scene, with its
/// descriptors (the scene's buffers, the output `image` and `extra`) and SBT.
pub(crate) fn prepare_on(
    ctx: &Arc<Context>,
    scene: &UploadedScene,
    set: &ShaderSet,
    raygen: &'static str,
    image: Rc<StorageImage>,
    extra: &[(u32, &Buffer)],
) -> Result<Prepared> {
    let resources = scene.resources.clone();
    let pipeline = RtPipeline::new(ctx, set, &scene.data.plan, raygen)?;
    let storage = vk::DescriptorType::STORAGE_BUFFER;
    let mut buffers: Vec<_> =
        resources.buffers.iter().map(|(binding, ty, buffer)| (*binding, buffer.raw, *ty)).collect();
    buffers.extend(extra.iter().map(|(binding, buffer)| (*binding, buffer.raw, storage)));
    let targets = DescriptorTargets {
        tlas: resources.tlas.raw,
        tlas_binding: b::BINDING_TLAS,
        image_view: image.view,
        image_binding: b::BINDING_IMAGE,
        buffers,
    };
    let descriptors = DescriptorSet::new(ctx, pipeline.set_layout, &pool_sizes(), &targets)?;
    let sbt = ShaderBindingTable::new(ctx, pipeline.raw, pipeline.group_counts)?;
    Ok(Prepared { one_shot: OneShot::new(ctx)?, image, pipeline, descriptors, sbt, _resources: resources })
}

/// A device-local storage buffer of `size` bytes that can be copied out.
pub(crate) fn storage_buffer(ctx: &Arc<Context>, name: &str, size: u64) -> Result<Buffer> {
    let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC;
    Buffer::new(ctx, name, size, usage, MemoryLocation::GpuOnly)
}

/// The outputs every set of a render writes in turn (one image, one hit-id buffer), so that
/// the sets' GPU times differ only by their pipelines.
struct SharedOutputs {
    image: Rc<StorageImage>,
    hit_ids: Buffer,
    unused: Buffer,
}

impl SharedOutputs {
    fn new(ctx: &Arc<Context>, opts: &RenderOptions) -> Result<Self> {
        let pixels = u64::from(opts.width) * u64::from(opts.height);
        Ok(SharedOutputs {
            image: Rc::new(StorageImage::new(ctx, opts.width, opts.height)?),
            hit_ids: storage_buffer(ctx, "hit ids", pixels * u64::from(b::HIT_IDS_PER_PIXEL) * 4)?,
            unused: storage_buffer(ctx, "unused probe buffer", 64)?,
        })
    }

    fn extra(&self) -> [(u32, &Buffer); 3] {
        [
            (b::BINDING_HIT_IDS, &self.hit_ids),
            (b::BINDING_PROBE_RAYS, &self.unused),
            (b::BINDING_PROBE_RESULTS, &self.unused),
        ]
    }
}

/// One set's pipeline over the shared scene and outputs, with its timestamps and readbacks.
struct SetRender {
    prepared: Prepared,
    timestamps: Option<Timestamps>,
    image_readback: Buffer,
    ids_readback: Buffer,
}

impl SetRender {
    fn new(
        ctx: &Arc<Context>,
        scene: &UploadedScene,
        outputs: &SharedOutputs,
        set: &ShaderSet,
        opts: &RenderOptions,
    ) -> Result<Self> {
        let image = outputs.image.clone();
        let pixels = u64::from(opts.width) * u64::from(opts.height);
        let readback =
            |name, bytes| Buffer::new(ctx, name, bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu);
        Ok(SetRender {
            prepared: prepare_on(ctx, scene, set, "raygen", image, &outputs.extra())?,
            timestamps: Timestamps::new(ctx, opts.runs)?,
            image_readback: readback("image readback", pixels * crate::vk::image::PIXEL_BYTES)?,
            ids_readback: readback("hit id readback", outputs.hit_ids.size)?,
        })
    }

    fn output(&self, scene: &Scene, opts: &RenderOptions, warmup_traces: u32) -> Result<RenderOutput> {
        let gpu_ms = self.timestamps.as_ref().map(|t| t.read_ms()).transpose()?.unwrap_or_default();
        let (hit_ids, shadow) = read_ids(&self.ids_readback.mapped()?[..self.ids_readback.size as usize]);
        let linear = read_linear(&self.image_readback.mapped()?[..self.image_readback.size as usize]);
        let pixels = u64::from(opts.width) * u64::from(opts.height);
        let samples = u64::from(scene.file.image.samples).pow(2);
        Ok(RenderOutput {
            width: opts.width,
            height: opts.height,
            rgba: to_rgba8(&linear),
            linear,
            hit_ids,
            gpu_ms,
            rays: RayCounts { primary: pixels * samples, shadow },
            warmup_traces,
            raygen_stack_bytes: self.prepared.pipeline.raygen_stack_bytes(),
        })
    }
}

fn render_and_release(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[ShaderSet],
    opts: &RenderOptions,
) -> Result<Vec<RenderOutput>> {
    check_size(opts.width, opts.height).map_err(Error::Input)?;
    check_device_limits(ctx, opts)?;
    let size = (opts.width, opts.height);
    let uploaded = upload_shared(ctx, scene, size)?;
    let outputs = SharedOutputs::new(ctx, opts)?;
    let renders =
        sets.iter().map(|set| SetRender::new(ctx, &uploaded, &outputs, set, opts)).collect::<Result<Vec<_>>>()?;
    let traces = renders
        .iter()
        .map(|r| r.prepared.trace(ctx, r.timestamps.as_ref(), size, (opts.warmup, opts.runs)))
        .collect::<Result<Vec<_>>>()?;
    let Some(first) = renders.first() else { return Ok(Vec::new()) };
    first.prepared.one_shot.run(|device, cmd| {
        transition(device, cmd, outputs.image.raw, UNUSED_IMAGE, STORAGE_IMAGE);
        tracing::record(ctx, cmd, &traces);
        // Each set's output: one more trace of it, copied out before the next set's overwrites it.
        for (r, trace) in renders.iter().zip(&traces) {
            trace.once(ctx, cmd);
            let written = (STORAGE_IMAGE.1, STORAGE_IMAGE.2);
            memory_barrier(device, cmd, written, (COPY_SOURCE.1, COPY_SOURCE.2));
            transition(device, cmd, outputs.image.raw, STORAGE_IMAGE, COPY_SOURCE);
            copy_out(device, cmd, &outputs.image, &r.image_readback, &outputs.hit_ids, &r.ids_readback);
            transition(device, cmd, outputs.image.raw, COPY_SOURCE, STORAGE_IMAGE);
        }
        let copied = (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_WRITE);
        memory_barrier(device, cmd, copied, (vk::PipelineStageFlags::HOST, vk::AccessFlags::HOST_READ));
        Ok(())
    })?;
    renders.iter().zip(&traces).map(|(r, t)| r.output(scene, opts, t.warmup)).collect()
}

/// RGB of each rgba32f pixel.
fn read_linear(bytes: &[u8]) -> Vec<[f32; 3]> {
    let floats: &[f32] = bytemuck::cast_slice(bytes);
    floats.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect()
}

/// 8-bit RGBA of linear RGB: clamped to [0, 1], rounded to nearest (NaN becomes 0), alpha 255.
pub fn to_rgba8(linear: &[[f32; 3]]) -> Vec<u8> {
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    linear.iter().flat_map(|p| [byte(p[0]), byte(p[1]), byte(p[2]), 255]).collect()
}

/// Per pixel the first hit (object << 32 | primitive), and the sum of the pixels' shadow rays.
fn read_ids(bytes: &[u8]) -> (Vec<u64>, u64) {
    let word = |p: &[u8], i: usize| u32::from_le_bytes([p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]]);
    let per_pixel = 4 * b::HIT_IDS_PER_PIXEL as usize;
    let ids = bytes.chunks_exact(per_pixel).map(|p| u64::from(word(p, 0)) << 32 | u64::from(word(p, 1))).collect();
    let shadow = bytes.chunks_exact(per_pixel).map(|p| u64::from(word(p, 2))).sum();
    (ids, shadow)
}

/// The output image's layout before the first trace, and while traces write it.
pub(crate) const UNUSED_IMAGE: (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags) =
    (vk::ImageLayout::UNDEFINED, vk::PipelineStageFlags::TOP_OF_PIPE, vk::AccessFlags::empty());
pub(crate) const STORAGE_IMAGE: (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags) =
    (vk::ImageLayout::GENERAL, vk::PipelineStageFlags::RAY_TRACING_SHADER_KHR, vk::AccessFlags::SHADER_WRITE);

/// The output image's layout while it is copied out.
const COPY_SOURCE: (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags) =
    (vk::ImageLayout::TRANSFER_SRC_OPTIMAL, vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_READ);

fn check_device_limits(ctx: &Context, opts: &RenderOptions) -> Result<()> {
    let info = &ctx.info;
    let invocations = u64::from(opts.width) * u64::from(opts.height);
    if opts.width.max(opts.height) > info.max_image_dimension_2d
        || invocations > u64::from(info.max_ray_dispatch_invocation_count)
    {
        return Err(Error::Input(format!(
            "image size {}x{} exceeds what {} allows (image side {}, ray dispatch {} invocations)",
            opts.width, opts.height, info.name, info.max_image_dimension_2d, info.max_ray_dispatch_invocation_count
        )));
    }
    Ok(())
}

/// Layout transition of the output image, with the access and stage masks of both sides.
pub(crate) fn transition(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    image: vk::Image,
    (old_layout, src_stage, src_access): (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags),
    (new_layout, dst_stage, dst_access): (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags),
) {
    let barrier = [vk::ImageMemoryBarrier::default()
        .src_access_mask(src_access)
        .dst_access_mask(dst_access)
        .old_layout(old_layout)
        .new_layout(new_layout)
        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .image(image)
        .subresource_range(COLOR_RANGE)];
    // SAFETY: cmd is recording; the image is alive.
    unsafe { device.cmd_pipeline_barrier(cmd, src_stage, dst_stage, vk::DependencyFlags::empty(), &[], &[], &barrier) };
}

fn copy_out(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    image: &StorageImage,
    image_dst: &Buffer,
    ids: &Buffer,
    ids_dst: &Buffer,
) {
    let region = [vk::BufferImageCopy::default()
        .image_subresource(vk::ImageSubresourceLayers {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            mip_level: 0,
            base_array_layer: 0,
            layer_count: 1,
        })
        .image_extent(image.extent.into())];
    let ids_region = [vk::BufferCopy::default().size(ids.size)];
    // SAFETY: cmd is recording; sizes match (PIXEL_BYTES per pixel on both sides).
    unsafe {
        device.cmd_copy_image_to_buffer(cmd, image.raw, COPY_SOURCE.0, image_dst.raw, &region);
        device.cmd_copy_buffer(cmd, ids.raw, ids_dst.raw, &ids_region);
    }
}
