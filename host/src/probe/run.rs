//! Probing: trace a list of rays through a scene's ordinary pipeline, with the probe ray
//! generation stage in place of the image one, and read back what each ray hit. The
//! intersection and hit stages are the very ones that render images. A scene rendered by the
//! compute renderer is probed by `probe_query`, which traces as it does.

use crate::error::{Error, Result};
use crate::render::{
    prepare, sentinel, storage_buffer, submit, transition, Prepared, Trace, Written, STORAGE_IMAGE, UNUSED_IMAGE,
};
use crate::scene::{origin, Renderer, Scene, PROBE_QUERY};
use crate::shaders::ShaderSet;
use crate::util::activity;
use crate::vk::buffer::Buffer;
use crate::vk::commands::{memory_barrier, TRACING_STAGES};
use crate::vk::context::Context;
use crate::vk::timing::Timestamps;
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;
use twinray_shared::bindings as b;
pub use twinray_shared::layout::{ProbeRay, ProbeResult};

/// What a probe run produced.
pub struct ProbeOutput {
    /// One per ray, in order.
    pub results: Vec<ProbeResult>,
    /// One per ray, in order, from the witness pass of the stages' object-space ray (see
    /// [`super::split::witness`]); none for a scene without hit groups, or one the compute
    /// renderer renders.
    pub witness: Option<Vec<ProbeResult>>,
    /// The same from the witness pass of the driver's object-space ray.
    pub driver_witness: Option<Vec<ProbeResult>>,
    /// GPU milliseconds of each timed trace of all the rays.
    pub gpu_ms: Vec<f64>,
    /// Stack bytes the probe ray generation stage needs, as the driver reports it.
    pub raygen_stack_bytes: u64,
}

impl ProbeOutput {
    /// The probe's records and the witness passes', as `report::evaluate` takes them.
    pub fn records(&self) -> Records<'_> {
        Records { results: &self.results, witness: self.witness.as_deref(), driver: self.driver_witness.as_deref() }
    }
}

/// A probe's records: one per ray, and those of its witness passes where it had them.
#[derive(Clone, Copy)]
pub struct Records<'a> {
    pub results: &'a [ProbeResult],
    pub witness: Option<&'a [ProbeResult]>,
    pub driver: Option<&'a [ProbeResult]>,
}

/// Whether the stage wrote this record: no word of it still holds the sentinel.
pub fn record_written<T: bytemuck::Pod>(r: &T) -> bool {
    let words: &[u32] = bytemuck::cast_slice(std::slice::from_ref(r));
    !words.iter().any(|&w| sentinel::unwritten(w))
}

/// Whether the probe stage marked the record's ray as one whose hit or miss stage wrote no
/// payload (`PROBE_NO_PAYLOAD`).
pub fn no_payload(r: &ProbeResult) -> bool {
    r.ids.w == b::PROBE_NO_PAYLOAD
}

/// Whether a record can be judged: written by the probe stage, with the payload its ray's
/// hit or miss stage wrote.
pub fn judgeable(r: &ProbeResult) -> bool {
    !no_payload(r) && record_written(r)
}

/// Records never written, rays whose payload no stage wrote, and hits written with a NaN or
/// infinite t or normal.
pub fn count_written(results: &[ProbeResult]) -> Written {
    let no_payload_rays = results.iter().filter(|r| no_payload(r)).count() as u64;
    let unwritten = results.iter().filter(|r| !no_payload(r) && !record_written(*r)).count() as u64;
    let non_finite =
        results.iter().filter(|r| judgeable(r) && r.ids.w != b::NO_HIT && !r.normal_t.is_finite()).count() as u64;
    Written { unwritten, non_finite, no_payload_rays, ..Written::default() }
}

/// The module that probes `scene`: `probe`, through the pipeline's stages; or for a scene the
/// compute renderer renders, `probe_query`, which traces as it does.
pub fn probe_module(scene: &Scene) -> &'static str {
    if scene.file.renderer == Renderer::Compute {
        PROBE_QUERY
    } else {
        "probe"
    }
}

/// Traces `rays` through `scene` with `set`: `warmup` untimed passes, then `runs` timed ones.
/// A scene with a local origin is centred on the rays' mean origin, and the rays moved with it
/// (`scene::origin`); the results (t, normals, object-space rays) do not depend on it.
pub fn probe(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    warmup: u32,
    runs: u32,
) -> Result<ProbeOutput> {
    let scene = scene.centred_on(origin::mean(rays.iter().map(|r| r.origin.truncate())));
    let local: Vec<ProbeRay>;
    let rays = match scene.origin {
        Some(o) => {
            let moved =
                |r: &ProbeRay| ProbeRay { origin: origin::to_local(r.origin.truncate(), o).extend(r.origin.w), ..*r };
            local = rays.iter().map(moved).collect();
            &local
        }
        None => rays,
    };
    let out = probe_and_release(ctx, &scene, set, rays, warmup, runs)?;
    // Every object of the probe is destroyed by now: catch what the layer said about that too.
    ctx.check_validation()?;
    Ok(out)
}

fn probe_and_release(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    warmup: u32,
    runs: u32,
) -> Result<ProbeOutput> {
    let count = u32::try_from(rays.len()).unwrap_or(u32::MAX);
    let module = probe_module(scene);
    // A compute probe runs in workgroups of PROBE_GROUP_SIZE rays, at most 65535 of them in a
    // dispatch (Vulkan's guaranteed maxComputeWorkGroupCount).
    let most = match module {
        PROBE_QUERY => b::PROBE_GROUP_SIZE * 65535,
        _ => ctx.info.max_ray_dispatch_invocation_count,
    };
    if rays.is_empty() || count > most {
        return Err(Error::Input(format!("a probe needs 1..={most} rays on {} (got {})", ctx.info.name, rays.len())));
    }
    let bytes = u64::from(count) * size_of::<ProbeResult>() as u64;
    let buffers = RayBuffers::new(ctx, "probe", bytemuck::cast_slice(rays), bytes)?;
    let p = prepare(ctx, scene, set, module, ((1, 1), (1, 1)), &buffers.extra())?;
    let results = buffers.results;
    let timestamps = Timestamps::new(ctx, runs)?;
    let label = format!("the probe trace of {set} ({})", p.pipeline.modules.join(", "));
    let _doing = activity::doing(label);
    // The witness passes first, untimed, so that the timed traces are the probe's as before.
    let mut witnesses = Vec::new();
    for sbt in &p.witness_sbts {
        let pass = Trace { sbt: Some(sbt), ..p.trace(ctx, None, (count, 1), (0, 1))? };
        witnesses.push(read_pass(ctx, &p, pass, &results, bytes)?);
    }
    let mut witnesses = witnesses.into_iter();
    let (witness, driver_witness) = (witnesses.next(), witnesses.next());
    let trace = p.trace(ctx, timestamps.as_ref(), (count, 1), (warmup, runs))?;
    let results = read_pass(ctx, &p, trace, &results, bytes)?;
    let gpu_ms = timestamps.map(|t| t.read_ms()).transpose()?.unwrap_or_default();
    Ok(ProbeOutput { results, witness, driver_witness, gpu_ms, raygen_stack_bytes: p.pipeline.raygen_stack_bytes() })
}

/// The buffers a pass of chosen rays binds besides the scene's: the rays, the results (of
/// `result_bytes`) and an unused hit-id buffer (the layout binds every binding).
pub(crate) struct RayBuffers {
    rays: Buffer,
    pub results: Buffer,
    unused: Buffer,
}

impl RayBuffers {
    pub fn new(ctx: &Arc<Context>, what: &str, rays: &[u8], result_bytes: u64) -> Result<RayBuffers> {
        Ok(RayBuffers {
            rays: Buffer::with_data(ctx, &format!("{what} rays"), rays, vk::BufferUsageFlags::STORAGE_BUFFER)?,
            results: storage_buffer(ctx, &format!("{what} results"), result_bytes)?,
            unused: storage_buffer(ctx, "unused hit ids", 64)?,
        })
    }

    /// The bindings `prepare` takes.
    pub fn extra(&self) -> [(u32, &Buffer); 3] {
        [
            (b::BINDING_HIT_IDS, &self.unused),
            (b::BINDING_PROBE_RAYS, &self.rays),
            (b::BINDING_PROBE_RESULTS, &self.results),
        ]
    }
}

/// Runs `trace` over `results`, poisoned first, and reads back the records it wrote: every
/// trace writes the same records, so what the stage never writes still holds the sentinel.
pub(crate) fn read_pass<T: bytemuck::Pod>(
    ctx: &Arc<Context>,
    p: &Prepared,
    trace: Trace,
    results: &Buffer,
    bytes: u64,
) -> Result<Vec<T>> {
    let readback =
        Buffer::new(ctx, "probe readback", bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)?;
    let before = |device: &ash::Device, cmd| {
        transition(device, cmd, p.image.raw, UNUSED_IMAGE, STORAGE_IMAGE);
        sentinel::poison_buffers(device, cmd, &[results]);
    };
    submit(ctx, &p.one_shot, &[trace], before, |device, cmd| {
        let written = (TRACING_STAGES, vk::AccessFlags::SHADER_WRITE);
        memory_barrier(device, cmd, written, (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_READ));
        let region = [vk::BufferCopy::default().size(bytes)];
        // SAFETY: cmd is recording; both buffers hold `bytes`.
        unsafe { device.cmd_copy_buffer(cmd, results.raw, readback.raw, &region) };
        let copied = (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_WRITE);
        memory_barrier(device, cmd, copied, (vk::PipelineStageFlags::HOST, vk::AccessFlags::HOST_READ));
    })?;
    Ok(bytemuck::pod_collect_to_vec(&readback.mapped()?[..bytes as usize]))
}
