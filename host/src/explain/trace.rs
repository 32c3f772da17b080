//! A pixel's rays traced through a set's real stages: the `explain` ray generation stage
//! traces each as the renderer traces rays of its kind (the very functions `raygen` calls),
//! through the scene's own hit groups, any-hit cutouts, misses and callables; `explain_query`
//! traces them inline where the renderer does (`renderer = "compute"`, and the shadow rays of
//! `shadow_method = "query"`).

use crate::error::{Error, Result};
use crate::probe::run::{read_pass, record_written, RayBuffers};
use crate::render::prepare;
use crate::scene::{PipelinePlan, Scene, EXPLAIN, EXPLAIN_QUERY};
use crate::sets::ShaderSet;
use crate::vk::context::Context;
use std::sync::Arc;
use twinray_shared::bindings as b;
pub use twinray_shared::layout::{ExplainRay, ExplainResult};

/// The module that traces rays of `kind` (`EXPLAIN_PRIMARY` or `EXPLAIN_SHADOW`) as the scene's
/// renderer does.
pub fn explain_module(plan: &PipelinePlan, kind: u32) -> &'static str {
    if plan.compute || (kind == b::EXPLAIN_SHADOW && plan.shadow_query) {
        EXPLAIN_QUERY
    } else {
        EXPLAIN
    }
}

/// Traces `rays`, all of one kind, through `scene` (whose pipeline plan is `plan`; with frame
/// constants for an image of `size`) with `set`; one result per ray. An error if the stage left
/// a record unwritten.
pub fn trace(
    ctx: &Arc<Context>,
    (scene, plan): (&Scene, &PipelinePlan),
    set: &ShaderSet,
    size: (u32, u32),
    rays: &[ExplainRay],
) -> Result<Vec<ExplainResult>> {
    let Some(first) = rays.first() else { return Ok(Vec::new()) };
    let kind = first.kind.x;
    debug_assert!(rays.iter().all(|r| r.kind.x == kind), "one kind of ray per trace");
    let module = explain_module(plan, kind);
    if set.lacks(module) {
        return Err(Error::Input(format!(
            "shader set {set} has no {module} module, which explain traces with (a folder built before explain \
             existed): rebuild the folder, or copy {module}.spv in from spirv/rust or spirv/glsl"
        )));
    }
    let results = trace_and_release(ctx, scene, set, (size, module), rays)?;
    ctx.check_validation()?;
    // A primary ray's payload may come back poisoned (its hit or miss stage wrote none): the
    // explain stage still wrote the record, whose `occluded` it always writes.
    if let Some(i) = results.iter().position(|r| !record_written(&r.occluded)) {
        return Err(Error::Output(format!(
            "{set}'s {module} stage left the result of ray {i} (of {}) unwritten",
            rays.len()
        )));
    }
    Ok(results)
}

fn trace_and_release(
    ctx: &Arc<Context>,
    scene: &Scene,
    set: &ShaderSet,
    (size, module): ((u32, u32), &'static str),
    rays: &[ExplainRay],
) -> Result<Vec<ExplainResult>> {
    let count = rays.len() as u32;
    let bytes = u64::from(count) * size_of::<ExplainResult>() as u64;
    let buffers = RayBuffers::new(ctx, "explain", bytemuck::cast_slice(rays), bytes)?;
    let p = prepare(ctx, scene, set, module, (size, (1, 1)), &buffers.extra())?;
    let trace = p.trace(ctx, None, (count, 1), (0, 1))?;
    read_pass(ctx, &p, trace, &buffers.results, bytes)
}
