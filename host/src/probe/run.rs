//! Probing: trace a list of rays through a scene's ordinary pipeline, with the probe ray
//! generation stage in place of the image one, and read back what each ray hit. The
//! intersection and hit stages are the very ones that render images. A scene rendered by the
//! compute renderer is probed by `probe_query`, which traces as it does.

use crate::error::{Error, Result};
use crate::render::{
    min_warm_ms, place_warm_ms, prepare_uploaded, sentinel, storage_buffer, submit, transition, Prepared, Trace,
    Written, STORAGE_IMAGE, UNUSED_IMAGE,
};
use crate::scene::launches::{self, Launch, LaunchRay, Placed};
use crate::scene::{origin, reach, GpuOrigin, Renderer, Scene, PROBE_QUERY};
use crate::sets::ShaderSet;
use crate::util::activity;
use crate::vk::buffer::Buffer;
use crate::vk::commands::{memory_barrier, TRACING_STAGES};
use crate::vk::context::Context;
use crate::vk::timing::Timestamps;
use ash::vk;
use glam::Vec3;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;
use twinray_shared::bindings as b;
use twinray_shared::features;
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

/// One launch of a probe at a local origin (`launches::launches`).
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
/// A scene with a local origin is probed in launches, each ray launched with the GPU's
/// coordinates centred where it meets what it can hit (`launches::launches`), its start moved
/// exactly; one that asks for the eye (`gpu_origin = "eye"`) in one launch centred there. The
/// scene is uploaded and the pipeline made once; each launch rebuilds the TLAS over instances
/// moved to its origin (`UploadedScene::centre`). The results (t, normals, object-space rays) do not
/// depend on it. Each timed pass is the sum of the launches' passes: the GPU time of every ray
/// once.
pub fn probe(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    warmup: u32,
    runs: u32,
) -> Result<ProbeOutput> {
    let (scene, launches) = plan(scene, rays);
    let out = probe_launches(ctx, &scene, set, rays, &launches, (warmup, runs), true)?;
    // Every object of the probe is destroyed by now: catch what the layer said about that too.
    ctx.check_validation()?;
    Ok(out)
}

/// The rays `each` of `rays`, each launched alone at its own start (as a launch of one ray at
/// the origins `probe` chooses would be), with the stages specialised as `probe` specialises
/// them for all of `rays`: what the chosen launches are checked against
/// (`origins::check`). One untimed pass, no witness; the records in the order of `each`.
pub fn probe_alone(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    each: &[usize],
) -> Result<Vec<ProbeResult>> {
    let (scene, _) = plan(scene, rays);
    let launches: Vec<Launch> =
        each.iter().map(|&i| Launch { origin: rays[i].origin.truncate(), rays: vec![i] }).collect();
    let out = probe_launches(ctx, &scene, set, rays, &launches, (0, 1), false)?;
    ctx.check_validation()?;
    Ok(each.iter().map(|&i| out.results[i]).collect())
}

/// The scene as `rays` see it and their launches. The far-instances feature is judged from
/// where rays start as well as from where objects stand, around each launch's origin; the one
/// pipeline of every launch has it where any launch needs it.
fn plan(scene: &Scene, rays: &[ProbeRay]) -> (Scene, Vec<Launch>) {
    let starts = |rays: &mut dyn Iterator<Item = &ProbeRay>| reach::enclose(rays.map(|r| r.origin.truncate()));
    let all = |origin: Vec3| vec![Launch { origin, rays: (0..rays.len()).collect() }];
    let starting = starts(&mut rays.iter()).map_or_else(|| scene.clone(), |s| scene.starting_in(s));
    match scene.origin {
        None => return (starting, all(Vec3::ZERO)),
        Some(eye) if scene.file.gpu_origin == GpuOrigin::Eye => return (starting, all(eye)),
        Some(_) => {}
    }
    // The instances as written: a build places them in the scene's coordinates, wherever the
    // GPU's are centred.
    let data = scene.build();
    let placed: Vec<Placed> = (data.world_boxes().into_iter().zip(&data.instances))
        .map(|(bounds, i)| Placed { bounds, translation: i.object_to_world.w_axis.truncate() })
        .collect();
    let launch_ray = |r: &ProbeRay| LaunchRay {
        origin: r.origin.truncate(),
        direction: r.direction.truncate(),
        t_min: r.origin.w,
        t_max: r.direction.w,
    };
    let launches = launches::launches(&rays.iter().map(launch_ray).collect::<Vec<_>>(), &placed);
    let mut scene = starting.centred_on(launches.first().map(|l| l.origin)).into_owned();
    if scene.file.features.is_none() {
        let far = scene.animation.is_some()
            || launches.iter().any(|l| data.far_at(l.origin, starts(&mut l.rays.iter().map(|&i| &rays[i])).as_ref()));
        let bits = (data.plan.features & !features::FAR_INSTANCES) | if far { features::FAR_INSTANCES } else { 0 };
        let names = features::FEATURES.iter().filter(|f| bits & f.bit != 0).map(|f| f.name.to_string());
        scene.file.features = Some(names.collect());
    }
    (scene, launches)
}

/// Each launch of `rays` through `scene` (centred at the first launch's origin) with `set`, over
/// one upload and pipeline; the outputs gathered back in the rays' order.
fn probe_launches(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    rays: &[ProbeRay],
    launches: &[Launch],
    (warmup, runs): (u32, u32),
    witness: bool,
) -> Result<ProbeOutput> {
    let module = probe_module(scene);
    // A compute probe runs in workgroups of PROBE_GROUP_SIZE rays, at most 65535 of them in a
    // dispatch (Vulkan's guaranteed maxComputeWorkGroupCount).
    let most = match module {
        PROBE_QUERY => b::PROBE_GROUP_SIZE * 65535,
        _ => ctx.info.max_ray_dispatch_invocation_count,
    };
    let largest = launches.iter().map(|l| l.rays.len()).max().unwrap_or(0);
    if rays.is_empty() || largest > most as usize {
        return Err(Error::Input(format!("a probe needs 1..={most} rays on {} (got {})", ctx.info.name, rays.len())));
    }
    let record = size_of::<ProbeResult>() as u64;
    let mut buffers =
        RayBuffers::new(ctx, "probe", &vec![0; largest * size_of::<ProbeRay>()], largest as u64 * record)?;
    let (mut uploaded, p) = prepare_uploaded(ctx, scene, set, module, ((1, 1), (1, 1)), &buffers.extra())?;
    let timestamps = Timestamps::new(ctx, runs)?;
    let label = format!("the probe trace of {set} ({})", p.pipeline.modules.join(", "));
    let _doing = activity::doing(label);
    let mut outputs = Vec::with_capacity(launches.len());
    for (k, launch) in launches.iter().enumerate() {
        if k > 0 {
            uploaded.centre(ctx, &p.one_shot, &scene.centred_on(Some(launch.origin)), (1, 1))?;
        }
        let moved = |&i: &usize| {
            let r = rays[i];
            ProbeRay { origin: origin::to_local(r.origin.truncate(), launch.origin).extend(r.origin.w), ..r }
        };
        let local: Vec<ProbeRay> = launch.rays.iter().map(moved).collect();
        buffers.rays.write(bytemuck::cast_slice(&local))?;
        // The first launch brings the GPU's clocks up; the later ones find them up.
        let warm_ms = if k == 0 { min_warm_ms()? } else { place_warm_ms()? };
        let timing = (timestamps.as_ref(), warm_ms);
        outputs.push(launch_pass(ctx, &p, (&buffers.results, local.len() as u32), (warmup, runs), timing, witness)?);
    }
    let mut out = gather(rays.len(), launches, outputs);
    out.raygen_stack_bytes = p.pipeline.raygen_stack_bytes();
    out.features = p.pipeline.features;
    // One launch at the world origin is no local origin.
    if launches.iter().all(|l| l.origin == Vec3::ZERO) {
        out.launches.clear();
    }
    Ok(out)
}

/// One launch's passes over the `count` rays in the ray buffer: the witness passes first (where
/// `witness` asks for them), untimed, so that the timed traces are the probe's as before, then
/// the timed ones.
fn launch_pass(
    ctx: &Arc<Context>,
    p: &Prepared,
    (results, count): (&Buffer, u32),
    passes: (u32, u32),
    (timestamps, warm_ms): (Option<&Timestamps>, f64),
    witness: bool,
) -> Result<ProbeOutput> {
    let bytes = u64::from(count) * size_of::<ProbeResult>() as u64;
    let mut witnesses = Vec::new();
    for sbt in p.witness_sbts.iter().filter(|_| witness) {
        let pass = Trace { sbt: Some(sbt), ..p.trace(ctx, None, (count, 1), (0, 1))? };
        witnesses.push(read_pass(ctx, p, pass, results, bytes)?);
    }
    let mut witnesses = witnesses.into_iter();
    let (witness, driver_witness) = (witnesses.next(), witnesses.next());
    let trace = p.trace_warmed(ctx, timestamps, (count, 1), passes, warm_ms)?;
    let results = read_pass(ctx, p, trace, results, bytes)?;
    let gpu_ms = timestamps.map(|t| t.read_ms()).transpose()?.unwrap_or_default();
    Ok(ProbeOutput {
        results,
        witness,
        driver_witness,
        gpu_ms,
        raygen_stack_bytes: 0,
        launches: Vec::new(),
        features: 0,
    })
}

/// The launches' outputs as one: every record back at its ray's place, each timed pass the sum
/// of the launches' (the same count in each), a witness only where every launch had it.
fn gather(count: usize, launches: &[Launch], outputs: Vec<ProbeOutput>) -> ProbeOutput {
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
        raygen_stack_bytes: 0,
        launches: launches.iter().map(|l| Launched { origin: l.origin.into(), rays: l.rays.len() }).collect(),
        features: 0,
    }
}

/// The buffers a pass of chosen rays binds besides the scene's: the rays, the results (of
/// `result_bytes`) and an unused hit-id buffer (the layout binds every binding).
pub(crate) struct RayBuffers {
    pub rays: Buffer,
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
