//! The ray tracing pipeline of the sphere scene: its descriptor set layout, pipeline layout,
//! and groups (raygen, miss, one procedural hit group) built from a resolved shader set.

use super::context::Context;
use crate::error::{Error, Result, VkContext};
use crate::shader_set::{ShaderSet, Stage, StageModule, MODULES};
use ash::vk;
use std::sync::Arc;
use twinray_shared::bindings as b;

/// Groups per SBT region (raygen, miss, hit), in the order of `twinray_shared::bindings::GROUP_*`.
pub const GROUP_COUNTS: [u32; 3] = [1, 1, 1];

pub struct RtPipeline {
    ctx: Arc<Context>,
    pub set_layout: vk::DescriptorSetLayout,
    pub layout: vk::PipelineLayout,
    pub raw: vk::Pipeline,
}

/// (binding, type, stages) of every descriptor, from the shared binding numbers.
pub fn descriptor_bindings() -> [(u32, vk::DescriptorType, vk::ShaderStageFlags); 5] {
    use vk::ShaderStageFlags as S;
    [
        (b::BINDING_TLAS, vk::DescriptorType::ACCELERATION_STRUCTURE_KHR, S::RAYGEN_KHR),
        (b::BINDING_IMAGE, vk::DescriptorType::STORAGE_IMAGE, S::RAYGEN_KHR),
        (b::BINDING_CAMERA, vk::DescriptorType::UNIFORM_BUFFER, S::RAYGEN_KHR),
        (b::BINDING_SPHERES, vk::DescriptorType::STORAGE_BUFFER, S::INTERSECTION_KHR | S::CLOSEST_HIT_KHR),
        (b::BINDING_HIT_IDS, vk::DescriptorType::STORAGE_BUFFER, S::RAYGEN_KHR),
    ]
}

/// Descriptor pool sizes matching [`descriptor_bindings`].
pub fn pool_sizes() -> Vec<vk::DescriptorPoolSize> {
    descriptor_bindings().iter().map(|&(_, ty, _)| vk::DescriptorPoolSize { ty, descriptor_count: 1 }).collect()
}

impl RtPipeline {
    pub fn new(ctx: &Arc<Context>, set: &ShaderSet) -> Result<Self> {
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
        let mut pipeline =
            RtPipeline { ctx: ctx.clone(), set_layout, layout: vk::PipelineLayout::null(), raw: vk::Pipeline::null() };
        let layouts = [set_layout];
        let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&layouts);
        // SAFETY: valid create info; destroyed in Drop.
        pipeline.layout = unsafe { ctx.device.create_pipeline_layout(&info, None) }.call("vkCreatePipelineLayout")?;
        let modules = MODULES.iter().map(|spec| set.resolve(spec)).collect::<Result<Vec<_>>>()?;
        pipeline.raw = create_pipeline(ctx, pipeline.layout, &modules)?;
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

fn create_pipeline(ctx: &Context, layout: vk::PipelineLayout, modules: &[StageModule]) -> Result<vk::Pipeline> {
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
        stages.push(
            vk::PipelineShaderStageCreateInfo::default().stage(stage_flag(m.spec.stage)).module(module).name(&m.entry),
        );
    }
    let index = |stage: Stage| modules.iter().position(|m| m.spec.stage == stage).map(|i| i as u32);
    let (Some(raygen), Some(miss), Some(intersection), Some(closest_hit)) =
        (index(Stage::Raygen), index(Stage::Miss), index(Stage::Intersection), index(Stage::ClosestHit))
    else {
        return Err(Error::Unsupported("the shader set lacks a stage".into()));
    };
    let general = |shader| {
        vk::RayTracingShaderGroupCreateInfoKHR::default()
            .ty(vk::RayTracingShaderGroupTypeKHR::GENERAL)
            .general_shader(shader)
            .closest_hit_shader(vk::SHADER_UNUSED_KHR)
            .any_hit_shader(vk::SHADER_UNUSED_KHR)
            .intersection_shader(vk::SHADER_UNUSED_KHR)
    };
    // Order fixed by twinray_shared::bindings::GROUP_*.
    let groups = [
        general(raygen),
        general(miss),
        vk::RayTracingShaderGroupCreateInfoKHR::default()
            .ty(vk::RayTracingShaderGroupTypeKHR::PROCEDURAL_HIT_GROUP)
            .general_shader(vk::SHADER_UNUSED_KHR)
            .closest_hit_shader(closest_hit)
            .any_hit_shader(vk::SHADER_UNUSED_KHR)
            .intersection_shader(intersection),
    ];
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
