//! Probing: trace a list of rays through a scene's ordinary pipeline, with the probe ray
//! generation stage in place of the image one, and read back what each ray hit. The
//! intersection and hit stages are the very ones that render images. A scene rendered by the
//! compute renderer is probed by `probe_query`, which traces as it does.

use crate::error::{Error, Result};
use crate::render::{
    min_warm_ms, place_warm_ms, prepare, sentinel, storage_buffer, submit, transition, Prepared, Trace, Written,
    STORAGE_IMAGE, UNUSED_IMAGE,
};
use crate::scene::{origin, reach, GpuOrigin, Renderer, Scene, PROBE_QUERY};
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
    /// Where the GPU's coordinates were centred for each launch, and its rays; empty where the
    /// scene was probed at world coordinates, in one launch.
    pub launches: Vec<Launched>,
    /// The scene features the stages were specialised for, in any launch (`features` bits).
    pub features: u32,
}

/// One launch of a probe at a local origin (`origin::launches`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Launched {
    /// In the scene's coordinates.
    pub origin: [f32; 3],
    pub rays: usize,
}

impl ProbeOutput {
    /// The probe's records and the witness passes', as `report::evaluate` takes them.
    pub fn records(&self) -> Records<'_> {
        Records {
            results: &self.results,
            witness: self.witness.as_deref(),
            driver: self.driver_witness.as_deref(),
            launches: &self.launches,
            features: self.features,
        }
    }
}

/// A probe's records: one per ray, and those of its witness passes where it had them.
#[derive(Clone, Copy)]
pub struct Records<'a> {
    pub results: &'a [ProbeResult],
    pub witness: Option<&'a [ProbeResult]>,
    pub driver: Option<&'a [ProbeResult]>,
    pub launches: &'a [Launched],
    /// The scene features the stages ran with (`ProbeOutput::features`).
    pub features: u32,
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
/// A scene with a local origin is probed in launches grouped by where the rays start
/// (`origin::launches`), each with the scene centred on its own origin and its rays moved with
/// it; one that asks for the eye (`gpu_origin = "eye"`) in one launch centred there. The
/// results (t, normals, object-space rays) do not depend on it. Each timed pass is the sum of
/// the launches' passes: the GPU time of every ray once.
pub fn probe(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    warmup: u32,
    runs: u32,
) -> Result<ProbeOutput> {
    // The scene as these rays see it: the far-instances feature judges objects from where they
    // start, not from the camera's eye.
    let starting = |rays: &mut dyn Iterator<Item = &ProbeRay>| {
        let starts = reach::enclose(rays.map(|r| r.origin.truncate()));
        starts.map_or_else(|| scene.clone(), |s| scene.starting_in(s))
    };
    let launches = match scene.origin {
        None => {
            let scene = starting(&mut rays.iter());
            return probe_launch(ctx, &scene, set, rays, (warmup, runs), min_warm_ms()?);
        }
        Some(eye) if scene.file.gpu_origin == GpuOrigin::Eye => {
            vec![origin::Launch { origin: eye, rays: (0..rays.len()).collect() }]
        }
        Some(_) => {
            let starts: Vec<_> = rays.iter().map(|r| r.origin.truncate()).collect();
            origin::launches(&starts, &scene.build().world_boxes())
        }
    };
    let mut outputs = Vec::with_capacity(launches.len());
    for (k, launch) in launches.iter().enumerate() {
        let centred = starting(&mut launch.rays.iter().map(|&i| &rays[i])).centred_on(Some(launch.origin)).into_owned();
        let moved = |&i: &usize| {
            let r = rays[i];
            ProbeRay { origin: origin::to_local(r.origin.truncate(), launch.origin).extend(r.origin.w), ..r }
        };
        let local: Vec<ProbeRay> = launch.rays.iter().map(moved).collect();
        // The first launch brings the GPU's clocks up; the later ones find them up.
        let warm_ms = if k == 0 { min_warm_ms()? } else { place_warm_ms()? };
        outputs.push(probe_launch(ctx, &centred, set, &local, (warmup, runs), warm_ms)?);
    }
    Ok(gather(rays.len(), &launches, outputs))
}

/// One launch of `rays` through `scene` as the GPU gets it, every object released after.
fn probe_launch(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    passes: (u32, u32),
    warm_ms: f64,
) -> Result<ProbeOutput> {
    let out = probe_and_release(ctx, scene, set, rays, passes, warm_ms)?;
    // Every object of the probe is destroyed by now: catch what the layer said about that too.
    ctx.check_validation()?;
    Ok(out)
}

/// The launches' outputs as one: every record back at its ray's place, each timed pass the sum
/// of the launches' (the same count in each), a witness only where every launch had it.
fn gather(count: usize, launches: &[origin::Launch], outputs: Vec<ProbeOutput>) -> ProbeOutput {
    let place = |parts: Vec<Option<Vec<ProbeResult>>>| -> Option<Vec<ProbeResult>> {
        let mut all = vec![bytemuck::Zeroable::zeroed(); count];
        for (launch, part) in launches.iter().zip(parts) {
            for (&i, r) in launch.rays.iter().zip(part?) {
                all[i] = r;
            }
        }
        Some(all)
    };
    let runs = outputs.iter().map(|o| o.gpu_ms.len()).min().unwrap_or(0);
    let gpu_ms = (0..runs).map(|k| outputs.iter().map(|o| o.gpu_ms[k]).sum()).collect();
    let raygen_stack_bytes = outputs.iter().map(|o| o.raygen_stack_bytes).max().unwrap_or(0);
    let features = outputs.iter().fold(0, |bits, o| bits | o.features);
    let (mut results, mut witness, mut driver) = (Vec::new(), Vec::new(), Vec::new());
    for o in outputs {
        results.push(Some(o.results));
        witness.push(o.witness);
        driver.push(o.driver_witness);
    }
    ProbeOutput {
        results: place(results).unwrap_or_default(),
        witness: place(witness),
        driver_witness: place(driver),
        gpu_ms,
        raygen_stack_bytes,
        launches: launches.iter().map(|l| Launched { origin: l.origin.into(), rays: l.rays.len() }).collect(),
        features,
    }
}

fn probe_and_release(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    (warmup, runs): (u32, u32),
    warm_ms: f64,
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
    let trace = p.trace_warmed(ctx, timestamps.as_ref(), (count, 1), (warmup, runs), warm_ms)?;
    let results = read_pass(ctx, &p, trace, &results, bytes)?;
    let gpu_ms = timestamps.map(|t| t.read_ms()).transpose()?.unwrap_or_default();
    let raygen_stack_bytes = p.pipeline.raygen_stack_bytes();
    let features = p.pipeline.features;
    Ok(ProbeOutput { results, witness, driver_witness, gpu_ms, raygen_stack_bytes, launches: Vec::new(), features })
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
