//! The ray tracing pipeline of a scene, from its plan: ray generation, the primary miss shader,
//! the shadow miss shader only if some light casts shadows, and one hit group per shape kind the
//! scene uses. Shaders come from a resolved shader set; specialisation constants carry the
//! plan's sample count and shadow switch into ray generation.

use super::context::Context;
use crate::error::{Error, Result, VkContext};
use crate::scene::PipelinePlan;
use crate::shader_set::{ShaderSet, Stage, StageModule};
use ash::vk;
use std::sync::Arc;
use twinray_shared::bindings as b;
use twinray_shared::catalog;

pub struct RtPipeline {
    ctx: Arc<Context>,
    pub set_layout: vk::DescriptorSetLayout,
    pub layout: vk::PipelineLayout,
    pub raw: vk::Pipeline,
    /// Groups per SBT region (raygen, miss, hit).
    pub group_counts: [u32; 3],
    /// Names of the modules in the pipeline, in stage order (for tests and reports).
    pub modules: Vec<&'static str>,
}

/// (binding, type, stages) of every descriptor, from the shared binding numbers.
pub fn descriptor_bindings() -> [(u32, vk::DescriptorType, vk::ShaderStageFlags); 12] {
    use vk::DescriptorType as D;
    use vk::ShaderStageFlags as S;
    let hit = S::INTERSECTION_KHR | S::CLOSEST_HIT_KHR;
    [
        (b::BINDING_TLAS, D::ACCELERATION_STRUCTURE_KHR, S::RAYGEN_KHR),
        (b::BINDING_IMAGE, D::STORAGE_IMAGE, S::RAYGEN_KHR),
        (b::BINDING_FRAME, D::UNIFORM_BUFFER, S::RAYGEN_KHR | S::MISS_KHR),
        (b::BINDING_OBJECTS, D::STORAGE_BUFFER, S::CLOSEST_HIT_KHR),
        (b::BINDING_PRIMITIVES, D::STORAGE_BUFFER, hit),
        (b::BINDING_MATERIALS, D::STORAGE_BUFFER, S::CLOSEST_HIT_KHR),
        (b::BINDING_LIGHTS, D::STORAGE_BUFFER, S::RAYGEN_KHR),
        (b::BINDING_HIT_IDS, D::STORAGE_BUFFER, S::RAYGEN_KHR),
        (b::BINDING_VERTICES, D::STORAGE_BUFFER, S::CLOSEST_HIT_KHR),
        (b::BINDING_INDICES, D::STORAGE_BUFFER, S::CLOSEST_HIT_KHR),
        (b::BINDING_PROBE_RAYS, D::STORAGE_BUFFER, S::RAYGEN_KHR),
        (b::BINDING_PROBE_RESULTS, D::STORAGE_BUFFER, S::RAYGEN_KHR),
    ]
}

/// Descriptor pool sizes matching [`descriptor_bindings`].
pub fn pool_sizes() -> Vec<vk::DescriptorPoolSize> {
    descriptor_bindings().iter().map(|&(_, ty, _)| vk::DescriptorPoolSize { ty, descriptor_count: 1 }).collect()
}

/// Module names of a plan's pipeline, each once, in stage order: the ray generation module
/// `raygen` ("raygen" renders, "probe" probes), misses, hit modules.
pub fn plan_modules(plan: &PipelinePlan, raygen: &'static str) -> Vec<&'static str> {
    let mut names = vec![raygen, "miss"];
    if plan.shadows {
        names.push("shadow_miss");
    }
    for group in &plan.hit_groups {
        names.extend(group.intersection_module());
        names.push(group.closest_hit_module());
    }
    let mut seen = Vec::new();
    names.retain(|n| {
        !seen.contains(n) && {
            seen.push(*n);
            true
        }
    });
    names
}

impl RtPipeline {
    pub fn new(ctx: &Arc<Context>, set: &ShaderSet, plan: &PipelinePlan, raygen: &'static str) -> Result<Self> {
        let bindings: Vec<_> = descriptor_bindings()
            .iter()
            .map(|&(binding, ty, stages)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(binding)
                    .descriptor_type(ty)
                    .descriptor_count(1)
                    .stage_flags(stages)
            })
            .collect();
        let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
        // SAFETY: valid create info; destroyed in Drop.
        let set_layout =
            unsafe { ctx.device.create_descriptor_set_layout(&info, None) }.call("vkCreateDescriptorSetLayout")?;
        let names = plan_modules(plan, raygen);
        let misses = if plan.shadows { 2 } else { 1 };
        let mut pipeline = RtPipeline {
            ctx: ctx.clone(),
            set_layout,
            layout: vk::PipelineLayout::null(),
            raw: vk::Pipeline::null(),
            group_counts: [1, misses, plan.hit_groups.len() as u32],
            modules: names.clone(),
        };
        let layouts = [set_layout];
        let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&layouts);
        // SAFETY: valid create info; destroyed in Drop.
        pipeline.layout = unsafe { ctx.device.create_pipeline_layout(&info, None) }.call("vkCreatePipelineLayout")?;
        let modules = names
            .iter()
            .map(|name| {
                let spec = catalog::module(name).ok_or_else(|| Error::Unsupported(format!("no module {name}")))?;
                set.resolve(&spec)
            })
            .collect::<Result<Vec<_>>>()?;
        pipeline.raw = create_pipeline(ctx, pipeline.layout, &modules, plan)?;
        Ok(pipeline)
    }
}

/// Shader modules, destroyed when dropped (after pipeline creation).
struct Modules<'a> {
    ctx: &'a Context,
    raw: Vec<vk::ShaderModule>,
}

impl Drop for Modules<'_> {
    fn drop(&mut self) {
        for &m in &self.raw {
            // SAFETY: the pipeline made from these modules no longer needs them.
            unsafe { self.ctx.device.destroy_shader_module(m, None) };
        }
    }
}

fn create_pipeline(
    ctx: &Context,
    layout: vk::PipelineLayout,
    modules: &[StageModule],
    plan: &PipelinePlan,
) -> Result<vk::Pipeline> {
    let spec_data = [u32::from(plan.shadows), plan.samples_per_side, plan.shadow_sampler];
    let spec_entries = [b::SPEC_SHADOWS, b::SPEC_SAMPLES_PER_SIDE, b::SPEC_SHADOW_SAMPLER]
        .iter()
        .enumerate()
        .map(|(i, &id)| vk::SpecializationMapEntry { constant_id: id, offset: 4 * i as u32, size: 4 })
        .collect::<Vec<_>>();
    let spec = vk::SpecializationInfo::default().map_entries(&spec_entries).data(bytemuck::cast_slice(&spec_data));
    let mut made = Modules { ctx, raw: Vec::new() };
    let mut stages = Vec::new();
    for m in modules {
        let code = ash::util::read_spv(&mut std::io::Cursor::new(m.spirv)).map_err(|e| {
            Error::Unsupported(format!("{} module {} is not SPIR-V: {e}", m.language.name(), m.spec.name))
        })?;
        let info = vk::ShaderModuleCreateInfo::default().code(&code);
        // SAFETY: the code was validated by spirv-val at build time (cargo xtask shaders).
        let module = unsafe { ctx.device.create_shader_module(&info, None) }.call("vkCreateShaderModule")?;
        made.raw.push(module);
        let mut stage =
            vk::PipelineShaderStageCreateInfo::default().stage(stage_flag(m.spec.stage)).module(module).name(&m.entry);
        if m.spec.stage == Stage::Raygen {
            stage = stage.specialization_info(&spec);
        }
        stages.push(stage);
    }
    let index =
        |name: &str| modules.iter().position(|m| m.spec.name == name).map_or(vk::SHADER_UNUSED_KHR, |i| i as u32);
    let general = |shader| {
        vk::RayTracingShaderGroupCreateInfoKHR::default()
            .ty(vk::RayTracingShaderGroupTypeKHR::GENERAL)
            .general_shader(shader)
            .closest_hit_shader(vk::SHADER_UNUSED_KHR)
            .any_hit_shader(vk::SHADER_UNUSED_KHR)
            .intersection_shader(vk::SHADER_UNUSED_KHR)
    };
    // SBT order: raygen, miss (MISS_PRIMARY), shadow miss (MISS_SHADOW), then the hit groups.
    let raygen = modules.iter().position(|m| m.spec.stage == Stage::Raygen).map_or(vk::SHADER_UNUSED_KHR, |i| i as u32);
    let mut groups = vec![general(raygen), general(index("miss"))];
    if plan.shadows {
        groups.push(general(index("shadow_miss")));
    }
    for group in &plan.hit_groups {
        let ty = match group.intersection_module() {
            Some(_) => vk::RayTracingShaderGroupTypeKHR::PROCEDURAL_HIT_GROUP,
            None => vk::RayTracingShaderGroupTypeKHR::TRIANGLES_HIT_GROUP,
        };
        groups.push(
            vk::RayTracingShaderGroupCreateInfoKHR::default()
                .ty(ty)
                .general_shader(vk::SHADER_UNUSED_KHR)
                .closest_hit_shader(index(group.closest_hit_module()))
                .any_hit_shader(vk::SHADER_UNUSED_KHR)
                .intersection_shader(group.intersection_module().map_or(vk::SHADER_UNUSED_KHR, index)),
        );
    }
    let info = [vk::RayTracingPipelineCreateInfoKHR::default()
        .stages(&stages)
        .groups(&groups)
        .max_pipeline_ray_recursion_depth(1)
        .layout(layout)];
    // SAFETY: stages, groups and layout are valid and alive for the call.
    let pipelines = unsafe {
        ctx.rt.create_ray_tracing_pipelines(vk::DeferredOperationKHR::null(), vk::PipelineCache::null(), &info, None)
    }
    .map_err(|(_, result)| Error::Vulkan { call: "vkCreateRayTracingPipelinesKHR", result })?;
    pipelines
        .first()
        .copied()
        .ok_or(Error::Vulkan { call: "vkCreateRayTracingPipelinesKHR", result: vk::Result::ERROR_UNKNOWN })
}

/// The Vulkan stage flag of a twinray stage.
pub fn stage_flag(stage: Stage) -> vk::ShaderStageFlags {
    match stage {
        Stage::Raygen => vk::ShaderStageFlags::RAYGEN_KHR,
        Stage::Miss => vk::ShaderStageFlags::MISS_KHR,
        Stage::Intersection => vk::ShaderStageFlags::INTERSECTION_KHR,
        Stage::ClosestHit => vk::ShaderStageFlags::CLOSEST_HIT_KHR,
    }
}

impl RtPipeline {
    /// Bytes of stack the ray generation stage needs: the state it keeps across each trace
    /// call (the driver's figure; lavapipe reports a constant).
    pub fn raygen_stack_bytes(&self) -> u64 {
        // SAFETY: group 0 is the raygen group, a general group, of this live pipeline.
        unsafe { self.ctx.rt.get_ray_tracing_shader_group_stack_size(self.raw, 0, vk::ShaderGroupShaderKHR::GENERAL) }
    }
}

impl Drop for RtPipeline {
    fn drop(&mut self) {
        // SAFETY: no command buffer using these is pending; null handles are ignored.
        unsafe {
            self.ctx.device.destroy_pipeline(self.raw, None);
            self.ctx.device.destroy_pipeline_layout(self.layout, None);
            self.ctx.device.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}
