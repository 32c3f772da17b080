//! Recording traces: each pipeline's warm-up traces, then its timed traces interleaved with
//! every other pipeline's. Timed trace k of each pipeline runs before trace k+1 of any, so a
//! drift of the GPU's clocks over the submission reaches every pipeline alike (docs/measuring.md,
//! *Where the timing rules come from*).

use crate::error::Result;
use crate::util::progress;
use crate::vk::commands::{memory_barrier, OneShot, TRACING_STAGES};
use crate::vk::context::Context;
use crate::vk::descriptors::DescriptorSet;
use crate::vk::pipeline::RtPipeline;
use crate::vk::sbt::ShaderBindingTable;
use crate::vk::timing::Timestamps;
use ash::vk;
use twinray_shared::bindings as b;

/// What one pipeline's traces need.
#[derive(Clone, Copy)]
pub(crate) struct Trace<'a> {
    pub pipeline: &'a RtPipeline,
    pub descriptors: &'a DescriptorSet,
    /// The SBT of a ray tracing pipeline; none for a compute pipeline, which is dispatched in
    /// workgroups of `workgroup` over the launch.
    pub sbt: Option<&'a ShaderBindingTable>,
    pub workgroup: (u32, u32),
    pub timestamps: Option<&'a Timestamps>,
    /// Launch width and height.
    pub launch: (u32, u32),
    pub warmup: u32,
    pub runs: u32,
}

impl Trace<'_> {
    /// This trace's warm-up traces, then its timed traces (at least one trace always runs).
    pub fn record(&self, ctx: &Context, cmd: vk::CommandBuffer) {
        record(ctx, cmd, std::slice::from_ref(self));
    }

    /// One untimed trace, after all earlier traces' writes.
    pub fn once(&self, ctx: &Context, cmd: vk::CommandBuffer) {
        self.bind(ctx, cmd);
        self.trace(ctx, cmd, None);
    }

    fn bind(&self, ctx: &Context, cmd: vk::CommandBuffer) {
        let bind = self.pipeline.bind_point;
        let set = [self.descriptors.raw];
        // SAFETY: cmd is recording; pipeline and set are alive until the submit completes.
        unsafe {
            ctx.device.cmd_bind_pipeline(cmd, bind, self.pipeline.raw);
            ctx.device.cmd_bind_descriptor_sets(cmd, bind, self.pipeline.layout, b::DESCRIPTOR_SET, &set, &[]);
        }
    }

    /// One trace after all earlier traces' writes, between timestamps `timed` when given.
    fn trace(&self, ctx: &Context, cmd: vk::CommandBuffer, timed: Option<u32>) {
        let rt = (TRACING_STAGES, vk::AccessFlags::SHADER_WRITE);
        memory_barrier(&ctx.device, cmd, rt, (rt.0, vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::SHADER_READ));
        let timed = timed.and_then(|k| self.timestamps.map(|t| (t, k)));
        if let Some((t, k)) = timed {
            t.begin(cmd, k);
        }
        if let Some(sbt) = self.sbt {
            // SAFETY: the SBT regions point into a live buffer laid out for this pipeline.
            unsafe {
                ctx.rt.cmd_trace_rays(
                    cmd,
                    &sbt.raygen,
                    &sbt.miss,
                    &sbt.hit,
                    &sbt.callable,
                    self.launch.0,
                    self.launch.1,
                    1,
                )
            };
        } else {
            let (x, y) = (self.launch.0.div_ceil(self.workgroup.0), self.launch.1.div_ceil(self.workgroup.1));
            // SAFETY: a compute pipeline is bound, with its descriptor set.
            unsafe { ctx.device.cmd_dispatch(cmd, x, y, 1) };
        }
        if let Some((t, k)) = timed {
            t.end(cmd, k);
        }
    }
}

/// Timed rounds recorded in one submission. Longer work is split over several submissions,
/// with progress reported between them; up to this many, one submission as always.
pub(crate) const ROUNDS_PER_SUBMIT: u32 = 100;

/// Every trace's warm-up traces, one pipeline after the other, then round k of the timed
/// traces: timed trace k of each pipeline in turn. Every trace waits for the previous one.
pub(crate) fn record(ctx: &Context, cmd: vk::CommandBuffer, traces: &[Trace]) {
    record_warmup(ctx, cmd, traces);
    record_rounds(ctx, cmd, traces, 0..rounds(traces));
}

/// Timestamps reset, then every trace's warm-up traces.
pub(crate) fn record_warmup(ctx: &Context, cmd: vk::CommandBuffer, traces: &[Trace]) {
    for t in traces.iter().filter_map(|t| t.timestamps) {
        t.reset(cmd);
    }
    for trace in traces {
        trace.bind(ctx, cmd);
        for _ in 0..trace.warmup {
            trace.trace(ctx, cmd, None);
        }
    }
}

fn rounds(traces: &[Trace]) -> u32 {
    traces.iter().map(|t| t.runs.max(1)).max().unwrap_or(0)
}

/// Rounds `range` of the timed traces (see `record`).
fn record_rounds(ctx: &Context, cmd: vk::CommandBuffer, traces: &[Trace], range: std::ops::Range<u32>) {
    // A lone pipeline stays bound from its warm-up, but not into another command buffer.
    if let [only] = traces {
        only.bind(ctx, cmd);
    }
    for k in range {
        for trace in traces.iter().filter(|t| k < t.runs.max(1)) {
            if traces.len() > 1 {
                trace.bind(ctx, cmd);
            }
            trace.trace(ctx, cmd, Some(k).filter(|&k| k < trace.runs));
        }
    }
}

/// Records and submits `before`, the traces (as `record` orders them) and `after`: in one
/// submission up to `ROUNDS_PER_SUBMIT` timed rounds, else the rounds in batches of that many,
/// reporting progress after each. Each submission may take the GPU timeout once per trace in it.
pub(crate) fn submit(
    ctx: &Context,
    one_shot: &OneShot,
    traces: &[Trace],
    before: impl FnOnce(&ash::Device, vk::CommandBuffer),
    after: impl FnOnce(&ash::Device, vk::CommandBuffer),
) -> Result<()> {
    let rounds = rounds(traces);
    let warmups: u32 = traces.iter().map(|t| t.warmup).fold(0, u32::saturating_add);
    let timed = |range: std::ops::Range<u32>| {
        traces.iter().map(|t| range.clone().filter(|&k| k < t.runs.max(1)).count() as u32).fold(0, u32::saturating_add)
    };
    if rounds <= ROUNDS_PER_SUBMIT {
        return one_shot.run_units(warmups.saturating_add(timed(0..rounds)), |device, cmd| {
            before(device, cmd);
            record(ctx, cmd, traces);
            after(device, cmd);
            Ok(())
        });
    }
    one_shot.run_units(warmups, |device, cmd| {
        before(device, cmd);
        record_warmup(ctx, cmd, traces);
        Ok(())
    })?;
    let mut done = 0;
    while done < rounds {
        let end = (done + ROUNDS_PER_SUBMIT).min(rounds);
        one_shot.run_units(timed(done..end), |_, cmd| {
            record_rounds(ctx, cmd, traces, done..end);
            Ok(())
        })?;
        progress::report("timed traces", u64::from(end), u64::from(rounds));
        done = end;
    }
    one_shot.run(|device, cmd| {
        after(device, cmd);
        Ok(())
    })
}
