//! The stack size the driver gives each ray tracing stage of a set
//! (`vkGetRayTracingShaderGroupStackSizeKHR`): what it saves around every trace and callable
//! call the stage makes, for `twinray inspect` to set beside the liveness it computes.
//!
//! One pipeline holds every module asked for, each in a group of its own: a general group for
//! ray generation, miss and callable stages, a triangle group with only its closest-hit or
//! any-hit stage, a procedural group with only its intersection stage. The set's `raygen` is
//! always in it (a pipeline needs a ray generation stage).

use super::pipeline::{descriptor_bindings, stage_descs, Specialisation};
use crate::error::Result;
use crate::sets::{capabilities, Language, ShaderSet, Stage, StageModule};
use crate::vk::context::Context;
use crate::vk::pipeline::{GroupDesc, PipelineDesc, RtPipeline};
use ash::vk;
use std::sync::Arc;
use twinray_shared::bindings as b;

/// A module's stack: bytes, or why there is no figure.
pub type Stack = std::result::Result<u64, String>;

/// The specialisation stacks are sized and modules analysed for (`twinray inspect`): shadows
/// on, stratified shadow samples, M x M samples and the scene features given.
pub fn inspected(samples_per_side: u32, features: u32) -> Specialisation {
    Specialisation::new(true, samples_per_side, b::SHADOW_SAMPLER_STRATIFIED, features)
}

/// The stack of each module called `names` in `set`, with ray generation specialised for
/// `samples_per_side` x `samples_per_side` samples and shadows on, every stage for the
/// `features` bits (`twinray_shared::features`).
pub fn stage_stacks(
    ctx: &Arc<Context>,
    set: &ShaderSet,
    names: &[&str],
    (samples_per_side, features): (u32, u32),
) -> Result<Vec<(String, Stack)>> {
    // A pipeline needs a ray generation stage: the set's, or GLSL's where a folder lacks one.
    let mut modules: Vec<StageModule> = vec![if set.lacks("raygen") {
        ShaderSet::uniform(Language::Glsl).module("raygen")?
    } else {
        set.module("raygen")?
    }];
    let mut out: Vec<(String, Stack)> = Vec::new();
    for &name in names.iter().filter(|n| **n != "raygen") {
        let module = set.module(name)?;
        match refusal(ctx, &module)? {
            Some(why) => out.push((name.to_string(), Err(why))),
            None => modules.push(module),
        }
    }
    let specialised = inspected(samples_per_side, features);
    let spec = specialised.info();
    let stages = stage_descs(&modules, &spec);
    let groups: Vec<(GroupDesc, vk::ShaderGroupShaderKHR)> =
        modules.iter().enumerate().map(|(i, m)| group(m.spec.stage, i as u32)).collect();
    let descs: Vec<GroupDesc> = groups.iter().map(|g| g.0).collect();
    let bindings = descriptor_bindings();
    let depth = set.recursion_depth();
    let desc = PipelineDesc { bindings: &bindings, stages: &stages, groups: &descs, max_recursion_depth: depth };
    let pipeline = RtPipeline::new(ctx, &desc)?;
    ctx.check_validation()?;
    for (n, (m, (_, shader))) in modules.iter().zip(&groups).enumerate() {
        if names.contains(&m.spec.name) {
            out.push((m.spec.name.to_string(), Ok(pipeline.group_stack_bytes(n as u32, *shader))));
        }
    }
    Ok(out)
}

/// The group a module of `stage` at stage index `i` sits in alone, and which of its stages it is.
fn group(stage: Stage, i: u32) -> (GroupDesc, vk::ShaderGroupShaderKHR) {
    let unused = vk::SHADER_UNUSED_KHR;
    match stage {
        Stage::ClosestHit => {
            (GroupDesc::Triangles { closest_hit: i, any_hit: unused }, vk::ShaderGroupShaderKHR::CLOSEST_HIT)
        }
        Stage::AnyHit => (GroupDesc::Triangles { closest_hit: unused, any_hit: i }, vk::ShaderGroupShaderKHR::ANY_HIT),
        Stage::Intersection => (
            GroupDesc::Procedural { intersection: i, closest_hit: unused, any_hit: unused },
            vk::ShaderGroupShaderKHR::INTERSECTION,
        ),
        Stage::Raygen | Stage::Miss | Stage::Callable | Stage::Compute => {
            (GroupDesc::General(i), vk::ShaderGroupShaderKHR::GENERAL)
        }
    }
}

/// Why the module has no stack figure on this device: a compute stage has none; a stage that
/// declares what the device lacks (ray queries on the H100) cannot be compiled there.
fn refusal(ctx: &Context, module: &StageModule) -> Result<Option<String>> {
    if module.spec.stage == Stage::Compute {
        return Ok(Some("a compute stage: no ray tracing stack".into()));
    }
    let info = twinray_shared::spirv_info::parse(&module.spirv)
        .map_err(|e| crate::error::Error::Input(format!("{}: {e}", module.spec.name)))?;
    Ok(capabilities::missing(module.spec.name, &module.origin, &info, &ctx.info))
}
