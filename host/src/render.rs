//! Rendering a scene with a shader set: build the acceleration structures, pipeline and SBT,
//! trace (warm-up runs, then timed runs between timestamps), read back colour and hit ids.

use crate::error::{Error, Result};
use crate::scene::BlasDesc;
use crate::scene::{Scene, SceneData};
use crate::shader_set::ShaderSet;
use crate::vk::accel::{build_aabb_blas, build_tlas, build_triangle_blas, AccelStruct, InstanceRecord};
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

/// The scene's GPU data; kept alive until the trace has completed.
struct SceneResources {
    _blases: Vec<AccelStruct>,
    tlas: AccelStruct,
    /// (binding, buffer) of every storage and uniform buffer the scene provides.
    buffers: Vec<(u32, vk::DescriptorType, Buffer)>,
}

pub fn render(ctx: &Arc<Context>, scene: &Scene, set: &ShaderSet, opts: &RenderOptions) -> Result<RenderOutput> {
    let output = render_and_release(ctx, scene, set, opts)?;
    // Every object of the render is destroyed by now: catch what the layer said about that too.
    ctx.check_validation()?;
    Ok(output)
}

/// What a trace needs, built for one scene, shader set and ray generation stage. The caller's
/// extra buffers (hit ids, probe rays and results) must outlive it.
pub(crate) struct Prepared {
    pub one_shot: OneShot,
    pub image: StorageImage,
    pub pipeline: RtPipeline,
    pub descriptors: DescriptorSet,
    pub sbt: ShaderBindingTable,
    _resources: SceneResources,
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
    let one_shot = OneShot::new(ctx)?;
    let data = scene.build();
    let resources = upload_scene(ctx, &one_shot, scene, &data, frame)?;
    let image = StorageImage::new(ctx, image_size.0, image_size.1)?;
    let pipeline = RtPipeline::new(ctx, set, &data.plan, raygen)?;
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
    Ok(Prepared { one_shot, image, pipeline, descriptors, sbt, _resources: resources })
}

/// A device-local storage buffer of `size` bytes that can be copied out.
pub(crate) fn storage_buffer(ctx: &Arc<Context>, name: &str, size: u64) -> Result<Buffer> {
    let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC;
    Buffer::new(ctx, name, size, usage, MemoryLocation::GpuOnly)
}

fn render_and_release(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    opts: &RenderOptions,
) -> Result<RenderOutput> {
    check_size(opts.width, opts.height).map_err(Error::Input)?;
    check_device_limits(ctx, opts)?;
    let pixels = u64::from(opts.width) * u64::from(opts.height);
    let ids_bytes = pixels * u64::from(b::HIT_IDS_PER_PIXEL) * 4;
    let hit_ids = storage_buffer(ctx, "hit ids", ids_bytes)?;
    let unused = storage_buffer(ctx, "unused probe buffer", 64)?;
    let extra = [(b::BINDING_HIT_IDS, &hit_ids), (b::BINDING_PROBE_RAYS, &unused), (b::BINDING_PROBE_RESULTS, &unused)];
    let size = (opts.width, opts.height);
    let p = prepare(ctx, scene, set, "raygen", (size, size), &extra)?;
    let timestamps = Timestamps::new(ctx, opts.runs)?;
    let readback_usage = vk::BufferUsageFlags::TRANSFER_DST;
    let image_bytes = pixels * crate::vk::image::PIXEL_BYTES;
    let image_readback = Buffer::new(ctx, "image readback", image_bytes, readback_usage, MemoryLocation::GpuToCpu)?;
    let ids_readback = Buffer::new(ctx, "hit id readback", ids_bytes, readback_usage, MemoryLocation::GpuToCpu)?;
    let trace = p.trace(ctx, timestamps.as_ref(), size, (opts.warmup, opts.runs))?;
    let image = &p.image;
    p.one_shot.run(|device, cmd| {
        let rt = vk::PipelineStageFlags::RAY_TRACING_SHADER_KHR;
        let copy_src =
            (vk::ImageLayout::TRANSFER_SRC_OPTIMAL, vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_READ);
        transition(device, cmd, image.raw, UNUSED_IMAGE, STORAGE_IMAGE);
        trace.record(ctx, cmd);
        transition(device, cmd, image.raw, STORAGE_IMAGE, copy_src);
        let written = (rt, vk::AccessFlags::SHADER_WRITE);
        memory_barrier(device, cmd, written, (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_READ));
        copy_out(device, cmd, image, &image_readback, &hit_ids, &ids_readback);
        let copied = (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_WRITE);
        memory_barrier(device, cmd, copied, (vk::PipelineStageFlags::HOST, vk::AccessFlags::HOST_READ));
        Ok(())
    })?;
    let warmup_traces = trace.warmup;
    let gpu_ms = timestamps.as_ref().map(|t| t.read_ms()).transpose()?.unwrap_or_default();
    let (hit_ids, shadow) = read_ids(&ids_readback.mapped()?[..ids_bytes as usize]);
    let linear = read_linear(&image_readback.mapped()?[..image_bytes as usize]);
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
    })
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

fn upload_scene(
    ctx: &Arc<Context>,
    one_shot: &OneShot,
    scene: &Scene,
    data: &SceneData,
    (width, height): (u32, u32),
) -> Result<SceneResources> {
    // Meshes are read by the BLAS builds and by the triangle closest-hit stage.
    let mesh_usage = vk::BufferUsageFlags::STORAGE_BUFFER
        | vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
        | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
    let vertices = upload_with(ctx, "vertices", bytemuck::cast_slice(&data.vertices), mesh_usage)?;
    let indices = upload_with(ctx, "indices", bytemuck::cast_slice(&data.indices), mesh_usage)?;
    let (vertex_address, index_address) = (vertices.device_address(), indices.device_address());
    let blases = data
        .blases
        .iter()
        .map(|blas| match blas {
            BlasDesc::Aabbs(aabbs) => build_aabb_blas(ctx, one_shot, aabbs),
            BlasDesc::Triangles { vertex_base, vertex_count, index_base, index_count } => build_triangle_blas(
                ctx,
                one_shot,
                vertex_address + u64::from(*vertex_base) * size_of::<twinray_shared::layout::Vertex>() as u64,
                *vertex_count,
                index_address + u64::from(*index_base) * 4,
                *index_count,
            ),
        })
        .collect::<Result<Vec<_>>>()?;
    let instances: Vec<_> = data
        .instances
        .iter()
        .map(|i| InstanceRecord {
            object_to_world: i.object_to_world,
            custom_index: i.custom_index,
            mask: i.mask,
            sbt_offset: i.hit_group,
            blas_address: blases[i.blas].address,
        })
        .collect();
    let tlas = build_tlas(ctx, one_shot, &instances)?;
    let frame = scene.frame_uniform(width, height);
    let storage = vk::DescriptorType::STORAGE_BUFFER;
    let buffers = vec![
        (b::BINDING_FRAME, vk::DescriptorType::UNIFORM_BUFFER, upload(ctx, "frame", bytemuck::bytes_of(&frame))?),
        (b::BINDING_OBJECTS, storage, upload(ctx, "objects", bytemuck::cast_slice(&data.objects))?),
        (b::BINDING_PRIMITIVES, storage, upload(ctx, "primitives", bytemuck::cast_slice(&data.primitives))?),
        (b::BINDING_MATERIALS, storage, upload(ctx, "materials", bytemuck::cast_slice(&data.materials))?),
        (b::BINDING_LIGHTS, storage, upload(ctx, "lights", bytemuck::cast_slice(&data.lights))?),
        (b::BINDING_VERTICES, storage, vertices),
        (b::BINDING_INDICES, storage, indices),
    ];
    Ok(SceneResources { _blases: blases, tlas, buffers })
}

/// A host-visible buffer usable as a uniform or storage buffer; an empty slice still gets a
/// (zeroed) element's worth of memory, so every binding has a valid buffer.
fn upload(ctx: &Arc<Context>, name: &str, bytes: &[u8]) -> Result<Buffer> {
    upload_with(ctx, name, bytes, vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::UNIFORM_BUFFER)
}

fn upload_with(ctx: &Arc<Context>, name: &str, bytes: &[u8], usage: vk::BufferUsageFlags) -> Result<Buffer> {
    if bytes.is_empty() {
        return Buffer::with_data(ctx, name, &[0; 256], usage);
    }
    Buffer::with_data(ctx, name, bytes, usage)
}

/// What one trace command needs.
#[derive(Clone, Copy)]
pub(crate) struct Trace<'a> {
    pub pipeline: &'a RtPipeline,
    pub descriptors: &'a DescriptorSet,
    pub sbt: &'a ShaderBindingTable,
    pub timestamps: Option<&'a Timestamps>,
    /// Launch width and height.
    pub launch: (u32, u32),
    pub warmup: u32,
    pub runs: u32,
}

impl Trace<'_> {
    /// Warm-up traces, then timed traces, each waiting for the previous one's writes.
    pub fn record(&self, ctx: &Context, cmd: vk::CommandBuffer) {
        let device = &ctx.device;
        let bind = vk::PipelineBindPoint::RAY_TRACING_KHR;
        if let Some(t) = self.timestamps {
            t.reset(cmd);
        }
        // SAFETY: cmd is recording; pipeline and set are alive until the submit completes.
        unsafe {
            device.cmd_bind_pipeline(cmd, bind, self.pipeline.raw);
            device.cmd_bind_descriptor_sets(
                cmd,
                bind,
                self.pipeline.layout,
                b::DESCRIPTOR_SET,
                &[self.descriptors.raw],
                &[],
            );
        }
        let total = self.warmup + self.runs.max(1);
        for i in 0..total {
            if i > 0 {
                let rt = (vk::PipelineStageFlags::RAY_TRACING_SHADER_KHR, vk::AccessFlags::SHADER_WRITE);
                memory_barrier(device, cmd, rt, (rt.0, vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::SHADER_READ));
            }
            let timed = i.checked_sub(self.warmup).filter(|_| self.timestamps.is_some());
            if let (Some(t), Some(k)) = (self.timestamps, timed) {
                t.begin(cmd, k);
            }
            // SAFETY: the SBT regions point into a live buffer laid out for this pipeline.
            unsafe {
                ctx.rt.cmd_trace_rays(
                    cmd,
                    &self.sbt.raygen,
                    &self.sbt.miss,
                    &self.sbt.hit,
                    &Default::default(),
                    self.launch.0,
                    self.launch.1,
                    1,
                )
            };
            if let (Some(t), Some(k)) = (self.timestamps, timed) {
                t.end(cmd, k);
            }
        }
    }
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
        device.cmd_copy_image_to_buffer(cmd, image.raw, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, image_dst.raw, &region);
        device.cmd_copy_buffer(cmd, ids.raw, ids_dst.raw, &ids_region);
    }
}
