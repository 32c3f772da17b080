//! Rendering a scene with one or more shader sets over one upload of the scene and one output
//! image, once per placement (see `placement`), each set built and timed in turn.

use super::barriers::{transition, COPY_SOURCE, STORAGE_IMAGE};
use super::layout::LayoutDraw;
use super::libraries::Libraries;
use super::output::{read_back, to_rgba8, AccelStats, RayCounts, RenderOptions, RenderOutput};
use super::placement;
use super::prepare::{min_warm_ms, prepare_on, storage_buffer, Prepared};
use super::sentinel;
use super::tracing::{self, Trace};
use super::upload::{upload_shared, UploadedScene};
use crate::error::{Error, Result};
use crate::scene::{check_size, Scene, SceneData};
use crate::sets::ShaderSet;
use crate::util::{activity, progress};
use crate::vk::buffer::Buffer;
use crate::vk::commands::memory_barrier;
use crate::vk::context::{Context, PipelineKind};
use crate::vk::image::{StorageImage, PIXEL_BYTES};
use crate::vk::timing::Timestamps;
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::rc::Rc;
use std::sync::Arc;
use twinray_shared::bindings as b;

/// Renders `scene` with one set.
pub fn render(ctx: &Arc<Context>, scene: &Scene, set: &ShaderSet, opts: &RenderOptions) -> Result<RenderOutput> {
    let mut outputs = render_sets(ctx, scene, std::slice::from_ref(set), opts)?;
    Ok(outputs.remove(0))
}

/// [`render`], taking the scene: its meshes are freed as soon as the buffers the stages read
/// hold them, before the acceleration structures are built, so that a large model is held
/// once, not twice, at the render's peak memory (on a device whose memory is the host's, as
/// lavapipe's, three times, with the structures). What needs the meshes afterwards (the f64
/// reference) loads the scene again.
pub fn render_owned(
    ctx: &Arc<Context>,
    mut scene: Scene,
    set: &ShaderSet,
    opts: &RenderOptions,
) -> Result<RenderOutput> {
    let data = scene.on_gpu().build();
    scene.meshes.clear();
    let made = made_as_context_says(ctx, std::slice::from_ref(set));
    let mut outputs = render_made_over(ctx, (&scene, Some(data)), &made, opts)?;
    Ok(outputs.remove(0))
}

/// Renders `scene` with each of `sets` over the same acceleration structures and outputs, once
/// per placement (`opts.placements`, see `placement`): over a fresh upload, each set's
/// pipeline, SBT and descriptors made, traced and released in turn, in that placement's
/// order. Each set's timed traces are pooled, and each placement's median kept apart, for the
/// ratio's interval. With several placements, a first one is a warm-up whose times are
/// dropped (see `placement`). Images and hit ids are the first placement's.
pub fn render_sets(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[ShaderSet],
    opts: &RenderOptions,
) -> Result<Vec<RenderOutput>> {
    render_made(ctx, scene, &made_as_context_says(ctx, sets), opts)
}

/// Each set with the way the context makes pipelines.
pub(crate) fn made_as_context_says(ctx: &Context, sets: &[ShaderSet]) -> Vec<(ShaderSet, PipelineKind)> {
    sets.iter().map(|s| (s.clone(), ctx.pipeline_kind())).collect()
}

/// [`render_sets`] with each set's pipeline made its own way, whole or linked (what
/// `pipeline-bench` times linking by).
///
/// One upload of the scene and one set of outputs serve every set. The sets are timed in
/// rounds (`opts.placements`), each round every set once at a place of its own
/// (`placement::place`), in that round's order: its spacers made, its pipeline built, traced
/// alone for its output the first time, warmed up, timed and released with its spacers. The
/// GPU's clocks are brought up once, by a warm-up of at least `MIN_WARM_MS` whose times are
/// dropped (with several rounds: a place of its own before the first; with one: the first
/// place's warm-up), unless the GPU ended warmed traces moments ago; every place warms up as
/// `placement::warm_floor` says. Images and
/// hit ids are each set's first place's.
pub fn render_made(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[(ShaderSet, PipelineKind)],
    opts: &RenderOptions,
) -> Result<Vec<RenderOutput>> {
    render_made_over(ctx, (scene, None), sets, opts)
}

/// [`render_made`] of `scene`, or of `data` where given (built from `scene` before it gave up its
/// meshes: see [`render_owned`]).
fn render_made_over(
    ctx: &Arc<Context>,
    (scene, data): (&Scene, Option<SceneData>),
    sets: &[(ShaderSet, PipelineKind)],
    opts: &RenderOptions,
) -> Result<Vec<RenderOutput>> {
    check_size(opts.width, opts.height).map_err(Error::Input)?;
    check_device_limits(ctx, opts)?;
    let orders = placement::orders(sets.len(), opts.first_placement, opts.placements);
    let rows = placement::design(sets.len()).len();
    if opts.placements > 1 && !(opts.placements as usize).is_multiple_of(rows) {
        log::warn!(
            "{} placements of {} sets: the orders balance every set's position and predecessor only over a multiple of {rows} placements, so a ratio may owe something to the sets' order",
            opts.placements,
            sets.len()
        );
    }
    let size = (opts.width, opts.height);
    let uploaded = upload_shared(ctx, scene, data, size)?;
    let outputs = SharedOutputs::new(ctx, opts)?;
    // With several rounds, the clocks are brought up first, at a place of its own, unless
    // this GPU ended warmed traces moments ago (the last device's, with `--alone-in devices`).
    let warmed = opts.warmup > 0;
    if warmed && opts.placements > 1 && placement::idle_ms(ctx) > placement::LONG_GAP_MS {
        warm_up(ctx, (&uploaded, &outputs), &sets[orders[0][0]], opts)?;
        placement::note_warm(ctx);
    }
    let mut outputs_of: Vec<Option<RenderOutput>> = (0..sets.len()).map(|_| None).collect();
    let total = (orders.len() * sets.len()) as u64;
    for (round, order) in orders.iter().enumerate() {
        let round = opts.first_placement + round as u32;
        for (position, &i) in order.iter().enumerate() {
            let place = placement::place(round, i, sets.len());
            let _doing = (total > 1).then(|| activity::doing(format!("round {round}: {} at place {place}", sets[i].0)));
            let spacers: Vec<_> = placement::spacer_sets(place, sets.len()).iter().map(|&k| sets[k].clone()).collect();
            let at = (spacers.as_slice(), false, LayoutDraw::Place(place));
            let placed = Placed::new(ctx, (&uploaded, &outputs), &sets[i], at, opts)?;
            let render = &placed.render;
            let first = outputs_of[i].is_none();
            if first {
                render.trace_output(ctx, &outputs, size)?;
            }
            let warm_ms = placement::warm_floor(ctx)?;
            let trace = render.timed_trace_after(ctx, size, (opts.warmup, opts.runs), warm_ms)?;
            let _timing = activity::doing(format!("the timed traces of {}", render.label));
            tracing::submit(ctx, &render.prepared.one_shot, &[trace], |_, _| {}, |_, _| {})?;
            if warmed {
                placement::note_warm(ctx);
            }
            let slot = &mut outputs_of[i];
            if first {
                let mut out = render.output(scene, opts, trace.warmup, uploaded.accel)?;
                out.gpu_ms.clear();
                *slot = Some(out);
            }
            if let Some(out) = slot {
                out.record_place(&render.times()?, position as u32, place);
            }
            if total > 1 {
                let done = (round - opts.first_placement) as usize * sets.len() + position + 1;
                progress::report("placements", done as u64, total);
            }
        }
    }
    // Every object of the render is destroyed by now: catch what the layer said about that too.
    ctx.check_validation()?;
    outputs_of
        .into_iter()
        .collect::<Option<Vec<_>>>()
        .ok_or_else(|| Error::Unsupported("a round of the render left a set out".into()))
}

/// Brings the GPU's clocks up: `set` built and traced for at least `MIN_WARM_MS`, its times
/// dropped.
fn warm_up(
    ctx: &Arc<Context>,
    (scene, outputs): (&UploadedScene, &SharedOutputs),
    set: &(ShaderSet, PipelineKind),
    opts: &RenderOptions,
) -> Result<()> {
    let _doing = activity::doing("warming up the GPU");
    let render = SetRender::each(ctx, scene, outputs, std::slice::from_ref(set), (opts, LayoutDraw::Sbt))?.remove(0);
    let trace = render.timed_trace_after(ctx, (opts.width, opts.height), (opts.warmup.max(1), 1), min_warm_ms()?)?;
    tracing::submit(ctx, &render.prepared.one_shot, &[trace], |_, _| {}, |_, _| {})
}

/// A set built at a place: the place's spacers made and kept (salted copies when asked), then
/// the set's pipeline, laid out as the place draws (`super::layout`), its SBT and descriptors;
/// with the wall milliseconds the making took, in which the GPU idled.
pub(super) struct Placed {
    pub render: SetRender,
    pub made_ms: f64,
    _spacers: placement::Spacers,
}

impl Placed {
    pub fn new(
        ctx: &Arc<Context>,
        (scene, outputs): (&UploadedScene, &SharedOutputs),
        set: &(ShaderSet, PipelineKind),
        (spacers, salted, layout): (&[(ShaderSet, PipelineKind)], bool, LayoutDraw),
        opts: &RenderOptions,
    ) -> Result<Placed> {
        let start = std::time::Instant::now();
        let spacers = placement::Spacers::new(ctx, scene, spacers, salted)?;
        let render = SetRender::each(ctx, scene, outputs, std::slice::from_ref(set), (opts, layout))?.remove(0);
        Ok(Placed { render, made_ms: start.elapsed().as_secs_f64() * 1e3, _spacers: spacers })
    }
}

/// The outputs every set of a render writes in turn (one image, one hit-id buffer), so that
/// the sets' GPU times differ only by their pipelines; and the device-local buffer the
/// image's sentinel is copied from (through host-visible memory, the copy cost 1.04 ms per set
/// at 1920x1080 on the H100).
pub(super) struct SharedOutputs {
    pub image: Rc<StorageImage>,
    pub hit_ids: Buffer,
    poison: Buffer,
    unused: Buffer,
}

impl SharedOutputs {
    /// Sized to the launch, `opts.width` x `opts.height`: the renderers write the image and
    /// the hit ids at their pixel unchecked (a length read before the first trace costs every
    /// frame), so no trace may launch more pixels than these cover.
    pub fn new(ctx: &Arc<Context>, opts: &RenderOptions) -> Result<Self> {
        let pixels = u64::from(opts.width) * u64::from(opts.height);
        Ok(SharedOutputs {
            image: Rc::new(StorageImage::new(ctx, opts.width, opts.height)?),
            hit_ids: storage_buffer(ctx, "hit ids", pixels * u64::from(b::HIT_IDS_PER_PIXEL) * 4)?,
            poison: storage_buffer(ctx, "image sentinel", pixels * PIXEL_BYTES)?,
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
pub(super) struct SetRender {
    pub prepared: Prepared,
    pub timestamps: Option<Timestamps>,
    /// The set and the stages of its pipeline, for what a deadline or a crash names.
    pub label: String,
    image_readback: Buffer,
    ids_readback: Buffer,
}

impl SetRender {
    /// One per set, over the same scene and outputs, the linked ones linked from one set of
    /// libraries, so that each module compiles once; each laid out as `layout` draws.
    pub fn each(
        ctx: &Arc<Context>,
        scene: &UploadedScene,
        outputs: &SharedOutputs,
        sets: &[(ShaderSet, PipelineKind)],
        (opts, layout): (&RenderOptions, LayoutDraw),
    ) -> Result<Vec<Self>> {
        let libraries = Libraries::of(ctx);
        sets.iter()
            .map(|(set, kind)| {
                let linking = (*kind == PipelineKind::Libraries).then_some(&libraries);
                SetRender::new(ctx, scene, outputs, (set, linking, layout), opts)
            })
            .collect()
    }

    fn new(
        ctx: &Arc<Context>,
        scene: &UploadedScene,
        outputs: &SharedOutputs,
        (set, linking, layout): (&ShaderSet, Option<&Libraries>, LayoutDraw),
        opts: &RenderOptions,
    ) -> Result<Self> {
        let image = outputs.image.clone();
        let pixels = u64::from(opts.width) * u64::from(opts.height);
        let readback =
            |name, bytes| Buffer::new(ctx, name, bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu);
        let raygen = (scene.data.plan.render_raygen(), layout);
        let prepared = prepare_on(ctx, scene, (set, linking), raygen, image, &outputs.extra())?;
        Ok(SetRender {
            label: format!("{} ({})", set, set.describe_modules(&prepared.pipeline.modules)),
            prepared,
            timestamps: Timestamps::new(ctx, opts.runs)?,
            image_readback: readback("image readback", pixels * PIXEL_BYTES)?,
            ids_readback: readback("hit id readback", outputs.hit_ids.size)?,
        })
    }

    /// The set's output, in a submission of its own: the image and hit ids filled with the
    /// sentinel, one trace of this set alone, both copied out. A stage that never returns is
    /// then named with its set; what the set did not write still holds the sentinel.
    pub fn trace_output(&self, ctx: &Arc<Context>, outputs: &SharedOutputs, size: (u32, u32)) -> Result<()> {
        let _doing = activity::doing(format!("the trace of {}", self.label));
        let trace = self.prepared.trace(ctx, None, size, (0, 1))?;
        self.prepared.one_shot.run(|device, cmd| {
            sentinel::poison_image(device, cmd, &outputs.image, &outputs.poison);
            sentinel::poison_buffers(device, cmd, &[&outputs.hit_ids]);
            trace.once(ctx, cmd);
            let written = (STORAGE_IMAGE.1, STORAGE_IMAGE.2);
            memory_barrier(device, cmd, written, (COPY_SOURCE.1, COPY_SOURCE.2));
            transition(device, cmd, outputs.image.raw, STORAGE_IMAGE, COPY_SOURCE);
            copy_out(device, cmd, &outputs.image, &self.image_readback, &outputs.hit_ids, &self.ids_readback);
            // Later traces write the image in its storage layout.
            transition(device, cmd, outputs.image.raw, COPY_SOURCE, STORAGE_IMAGE);
            let copied = (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_WRITE);
            memory_barrier(device, cmd, copied, (vk::PipelineStageFlags::HOST, vk::AccessFlags::HOST_READ));
            Ok(())
        })
    }

    /// This set's timed traces: `runs` after at least `warmup` warm-up ones (see
    /// `Prepared::trace`, whose calibration trace runs here, naming the set).
    pub fn timed_trace(&self, ctx: &Arc<Context>, size: (u32, u32), (warmup, runs): (u32, u32)) -> Result<Trace<'_>> {
        self.timed_trace_after(ctx, size, (warmup, runs), min_warm_ms()?)
    }

    /// [`Self::timed_trace`] with warm-up traces of at least `warm_ms` of GPU time when
    /// `warmup` > 0.
    pub fn timed_trace_after(
        &self,
        ctx: &Arc<Context>,
        size: (u32, u32),
        (warmup, runs): (u32, u32),
        warm_ms: f64,
    ) -> Result<Trace<'_>> {
        let _doing = activity::doing(format!("warming up {}", self.label));
        self.prepared.trace_warmed(ctx, self.timestamps.as_ref(), size, (warmup, runs), warm_ms)
    }

    /// The GPU milliseconds of each timed trace of the last submission (none when the device
    /// cannot time).
    pub fn times(&self) -> Result<Vec<f64>> {
        Ok(self.timestamps.as_ref().map(|t| t.read_ms()).transpose()?.unwrap_or_default())
    }

    pub fn output(
        &self,
        scene: &Scene,
        opts: &RenderOptions,
        warmup_traces: u32,
        accel: AccelStats,
    ) -> Result<RenderOutput> {
        let gpu_ms = self.times()?;
        let pixels = u64::from(opts.width) * u64::from(opts.height);
        let image = &self.image_readback.mapped()?[..(pixels * PIXEL_BYTES) as usize];
        let read = read_back(image, &self.ids_readback.mapped()?[..self.ids_readback.size as usize]);
        let samples = u64::from(scene.file.image.samples).pow(2);
        Ok(RenderOutput {
            width: opts.width,
            height: opts.height,
            rgba: to_rgba8(&read.linear),
            linear: read.linear,
            hit_ids: read.hit_ids,
            gpu_ms,
            placements: Default::default(),
            rays: RayCounts { primary: pixels * samples, shadow: read.shadow },
            warmup_traces,
            raygen_stack_bytes: self.prepared.pipeline.raygen_stack_bytes(),
            written: read.written,
            no_payload: read.no_payload,
            accel,
        })
    }
}

pub(super) fn check_device_limits(ctx: &Context, opts: &RenderOptions) -> Result<()> {
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

fn copy_out(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    image: &StorageImage,
    image_dst: &Buffer,
    ids: &Buffer,
    ids_dst: &Buffer,
) {
    let region = [image.whole_copy()];
    let ids_region = [vk::BufferCopy::default().size(ids.size)];
    // SAFETY: cmd is recording; sizes match (PIXEL_BYTES per pixel on both sides).
    unsafe {
        device.cmd_copy_image_to_buffer(cmd, image.raw, COPY_SOURCE.0, image_dst.raw, &region);
        device.cmd_copy_buffer(cmd, ids.raw, ids_dst.raw, &ids_region);
    }
}
