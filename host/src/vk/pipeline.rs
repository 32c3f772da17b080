//! A ray tracing pipeline from plain Vulkan-shaped inputs: the descriptor bindings of its one
//! set, its shader stages (SPIR-V, entry point, specialisation) and its shader groups, in
//! shader binding table order; or a compute pipeline of one stage over the same set (the ray
//! query renderer). What goes in it is decided above this layer (`render::pipeline`).

use super::context::Context;
use super::kept::KeptPipeline;
use crate::error::{Error, Result, VkContext};
use crate::util::watchdog;
use ash::vk;
use std::ffi::CStr;
use std::sync::Arc;

/// A descriptor binding: its number, type, how many descriptors (an array's length) and the
/// stages that see it.
pub type Binding = (u32, vk::DescriptorType, u32, vk::ShaderStageFlags);

/// One shader stage of a pipeline.
#[derive(Clone, Copy)]
pub struct StageDesc<'a> {
    /// Names the module in errors.
    pub name: &'a str,
    pub stage: vk::ShaderStageFlags,
    /// SPIR-V bytes (little-endian words).
    pub spirv: &'a [u8],
    pub entry: &'a CStr,
    pub specialization: Option<&'a vk::SpecializationInfo<'a>>,
}

/// One shader group, by indices into the stages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroupDesc {
    /// Ray generation, miss or callable.
    General(u32),
    /// Built-in triangle test with a closest-hit stage and an any-hit stage
    /// (`vk::SHADER_UNUSED_KHR` for none).
    Triangles { closest_hit: u32, any_hit: u32 },
    /// An intersection stage for AABBs with a closest-hit stage and an any-hit stage.
    Procedural { intersection: u32, closest_hit: u32, any_hit: u32 },
}

/// Everything a pipeline is made of.
pub struct PipelineDesc<'a> {
    /// (binding, type, stages that see it) of every descriptor of set 0.
    pub bindings: &'a [Binding],
    pub stages: &'a [StageDesc<'a>],
    /// In shader binding table order.
    pub groups: &'a [GroupDesc],
    pub max_recursion_depth: u32,
}

/// What every library of a linked pipeline, and the pipeline itself, agree on
/// (`VkRayTracingPipelineInterfaceCreateInfoKHR`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Interface {
    pub max_payload_bytes: u32,
    pub max_hit_attribute_bytes: u32,
    pub max_recursion_depth: u32,
}

/// How a pipeline is made (`VK_KHR_pipeline_library`).
#[derive(Clone, Copy)]
enum Making<'a> {
    /// Whole, from its own stages.
    Whole,
    /// A library of its own stages and groups, for linking.
    Library(Interface),
    /// Linked from libraries, with no stages of its own: its groups are theirs, in order.
    Linked(Interface, &'a [vk::Pipeline]),
}

/// A ray tracing pipeline (or a compute one) with its set and pipeline layouts.
pub struct RtPipeline {
    ctx: Arc<Context>,
    pub set_layout: vk::DescriptorSetLayout,
    pub layout: vk::PipelineLayout,
    pub raw: vk::Pipeline,
    /// `RAY_TRACING_KHR`, or `COMPUTE` for [`RtPipeline::compute`].
    pub bind_point: vk::PipelineBindPoint,
    /// The context keeps the handles (`Context::kept`) and destroys them, not this.
    kept: bool,
}

impl RtPipeline {
    /// Creates the pipeline `desc` describes.
    pub fn new(ctx: &Arc<Context>, desc: &PipelineDesc) -> Result<Self> {
        Self::make(ctx, desc, Making::Whole)
    }

    /// A pipeline library of `desc`'s stages and groups (`VK_KHR_pipeline_library`), to be
    /// linked into pipelines with the same bindings and `interface`.
    pub fn library(ctx: &Arc<Context>, desc: &PipelineDesc, interface: Interface) -> Result<Self> {
        Self::make(ctx, desc, Making::Library(interface))
    }

    /// A pipeline linked from `libraries`, its groups theirs in order: each library made by
    /// [`RtPipeline::library`] with `bindings` and `interface`, alive (or kept) until this is.
    pub fn link(
        ctx: &Arc<Context>,
        bindings: &[Binding],
        libraries: &[vk::Pipeline],
        interface: Interface,
    ) -> Result<Self> {
        let desc =
            PipelineDesc { bindings, stages: &[], groups: &[], max_recursion_depth: interface.max_recursion_depth };
        Self::make(ctx, &desc, Making::Linked(interface, libraries))
    }

    /// This pipeline's handles, for its context to keep until the device goes
    /// (`Context::kept`), which then destroys them instead of this.
    pub fn into_kept(mut self) -> KeptPipeline {
        KeptPipeline {
            set_layout: std::mem::take(&mut self.set_layout),
            layout: std::mem::take(&mut self.layout),
            raw: std::mem::take(&mut self.raw),
        }
    }

    /// A pipeline the context keeps (`Context::kept`), lent to its user: dropping it destroys
    /// nothing.
    pub fn lent(ctx: &Arc<Context>, kept: KeptPipeline, bind_point: vk::PipelineBindPoint) -> Self {
        let KeptPipeline { set_layout, layout, raw } = kept;
        RtPipeline { ctx: ctx.clone(), set_layout, layout, raw, bind_point, kept: true }
    }

    /// A compute pipeline of `stage` over a set with `bindings`.
    pub fn compute(ctx: &Arc<Context>, bindings: &[Binding], stage: &StageDesc) -> Result<Self> {
        let mut pipeline = Self::layouts(ctx, bindings, vk::PipelineBindPoint::COMPUTE)?;
        // A driver's compiler may never return on a damaged module: see util::watchdog.
        let _deadline = watchdog::arm(ctx.gpu_timeout());
        let mut made = Modules { ctx, raw: Vec::new() };
        let info =
            [vk::ComputePipelineCreateInfo::default().stage(stage_info(&mut made, stage)?).layout(pipeline.layout)];
        // SAFETY: valid create info; the module lives until the call returns.
        let raw = unsafe { ctx.device.create_compute_pipelines(ctx.pipeline_cache(), &info, None) }
            .map_err(|(_, e)| e)
            .call("vkCreateComputePipelines")?;
        pipeline.raw = raw[0];
        Ok(pipeline)
    }

    fn make(ctx: &Arc<Context>, desc: &PipelineDesc, making: Making) -> Result<Self> {
        let mut pipeline = Self::layouts(ctx, desc.bindings, vk::PipelineBindPoint::RAY_TRACING_KHR)?;
        pipeline.raw = create_pipeline(ctx, pipeline.layout, desc, making)?;
        Ok(pipeline)
    }

    /// The set and pipeline layouts over `bindings`, and no pipeline yet.
    fn layouts(ctx: &Arc<Context>, bindings: &[Binding], bind_point: vk::PipelineBindPoint) -> Result<Self> {
        let bindings: Vec<_> = bindings
            .iter()
            .map(|&(binding, ty, count, stages)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(binding)
                    .descriptor_type(ty)
                    .descriptor_count(count)
                    .stage_flags(stages)
            })
            .collect();
        let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
        // SAFETY: valid create info; destroyed in Drop.
        let set_layout =
            unsafe { ctx.device.create_descriptor_set_layout(&info, None) }.call("vkCreateDescriptorSetLayout")?;
        let mut pipeline = RtPipeline {
            ctx: ctx.clone(),
            set_layout,
            layout: vk::PipelineLayout::null(),
            raw: vk::Pipeline::null(),
            bind_point,
            kept: false,
        };
        let layouts = [set_layout];
        let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&layouts);
        // SAFETY: valid create info; destroyed in Drop.
        pipeline.layout = unsafe { ctx.device.create_pipeline_layout(&info, None) }.call("vkCreatePipelineLayout")?;
        Ok(pipeline)
    }

    /// Bytes of stack the ray generation stage in group `group` needs: the state it keeps
    /// across each trace call (the driver's figure; lavapipe reports a constant); 0 for a
    /// compute pipeline, which keeps none.
    pub fn raygen_stack_bytes_of(&self, group: u32) -> u64 {
        if self.bind_point != vk::PipelineBindPoint::RAY_TRACING_KHR {
            return 0;
        }
        self.group_stack_bytes(group, vk::ShaderGroupShaderKHR::GENERAL)
    }

    /// Bytes of stack the `shader` stage of group `group` needs (the driver's figure). The
    /// caller names a group of this ray tracing pipeline that has such a stage.
    pub fn group_stack_bytes(&self, group: u32, shader: vk::ShaderGroupShaderKHR) -> u64 {
        self.stack_bytes_in(self.raw, group, shader)
    }

    /// As [`Self::group_stack_bytes`], of the ray generation library `library` this was linked
    /// from (its one group).
    pub fn library_raygen_stack_bytes(&self, library: vk::Pipeline) -> u64 {
        self.stack_bytes_in(library, 0, vk::ShaderGroupShaderKHR::GENERAL)
    }

    fn stack_bytes_in(&self, pipeline: vk::Pipeline, group: u32, shader: vk::ShaderGroupShaderKHR) -> u64 {
        // SAFETY: a live ray tracing pipeline of this device; the group and its stage are the
        // caller's promise, which the validation layer checks.
        unsafe { self.ctx.rt.get_ray_tracing_shader_group_stack_size(pipeline, group, shader) }
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

/// The create info of stage `s`, its module made and kept in `made`.
fn stage_info<'a>(made: &mut Modules, s: &StageDesc<'a>) -> Result<vk::PipelineShaderStageCreateInfo<'a>> {
    let code = ash::util::read_spv(&mut std::io::Cursor::new(s.spirv))
        .map_err(|e| Error::Unsupported(format!("module {} is not SPIR-V: {e}", s.name)))?;
    let info = vk::ShaderModuleCreateInfo::default().code(&code);
    // SAFETY: the code was checked before (SPIR-V header, entry points, bindings).
    let module = unsafe { made.ctx.device.create_shader_module(&info, None) }.call("vkCreateShaderModule")?;
    made.raw.push(module);
    let mut stage = vk::PipelineShaderStageCreateInfo::default().stage(s.stage).module(module).name(s.entry);
    if let Some(spec) = s.specialization {
        stage = stage.specialization_info(spec);
    }
    Ok(stage)
}

fn create_pipeline(
    ctx: &Context,
    layout: vk::PipelineLayout,
    desc: &PipelineDesc,
    making: Making,
) -> Result<vk::Pipeline> {
    // A driver's compiler may never return on a damaged module: see util::watchdog.
    let _deadline = watchdog::arm(ctx.gpu_timeout());
    let mut made = Modules { ctx, raw: Vec::new() };
    let stages = desc.stages.iter().map(|s| stage_info(&mut made, s)).collect::<Result<Vec<_>>>()?;
    let unused = vk::SHADER_UNUSED_KHR;
    let groups: Vec<_> = desc
        .groups
        .iter()
        .map(|g| {
            type Ty = vk::RayTracingShaderGroupTypeKHR;
            let (ty, general, intersection, closest_hit, any_hit) = match *g {
                GroupDesc::General(i) => (Ty::GENERAL, i, unused, unused, unused),
                GroupDesc::Triangles { closest_hit, any_hit } => {
                    (Ty::TRIANGLES_HIT_GROUP, unused, unused, closest_hit, any_hit)
                }
                GroupDesc::Procedural { intersection, closest_hit, any_hit } => {
                    (Ty::PROCEDURAL_HIT_GROUP, unused, intersection, closest_hit, any_hit)
                }
            };
            vk::RayTracingShaderGroupCreateInfoKHR::default()
                .ty(ty)
                .general_shader(general)
                .closest_hit_shader(closest_hit)
                .any_hit_shader(any_hit)
                .intersection_shader(intersection)
        })
        .collect();
    let mut interface_info = vk::RayTracingPipelineInterfaceCreateInfoKHR::default();
    let mut library_info = vk::PipelineLibraryCreateInfoKHR::default();
    let mut info = vk::RayTracingPipelineCreateInfoKHR::default()
        .stages(&stages)
        .groups(&groups)
        .max_pipeline_ray_recursion_depth(desc.max_recursion_depth)
        .layout(layout);
    match making {
        Making::Whole => {}
        Making::Library(interface) | Making::Linked(interface, _) => {
            interface_info = interface_info
                .max_pipeline_ray_payload_size(interface.max_payload_bytes)
                .max_pipeline_ray_hit_attribute_size(interface.max_hit_attribute_bytes);
            info = info.library_interface(&interface_info);
        }
    }
    match making {
        Making::Library(_) => info = info.flags(vk::PipelineCreateFlags::LIBRARY_KHR),
        Making::Linked(_, libraries) => {
            library_info = library_info.libraries(libraries);
            info = info.library_info(&library_info);
        }
        Making::Whole => {}
    }
    // Libraries and links are created directly: on the H100 (driver 580.159.04) creating them
    // as deferred operations crashed the process (a segfault, no message) with 1 and with 16
    // joining threads, while whole pipelines were fine; lavapipe took both.
    let threads = if matches!(making, Making::Whole) { ctx.pipeline_threads() } else { 0 };
    super::deferred::create_pipeline(ctx, &info, threads)
}

/// Descriptor pool sizes for one set with these bindings.
pub fn pool_sizes(bindings: &[Binding]) -> Vec<vk::DescriptorPoolSize> {
    bindings.iter().map(|&(_, ty, descriptor_count, _)| vk::DescriptorPoolSize { ty, descriptor_count }).collect()
}

impl Drop for RtPipeline {
    fn drop(&mut self) {
        if self.kept || self.ctx.abandoned() {
            return; // the context's, or the GPU may still use it: see Context::abandon
        }
        // SAFETY: no command buffer using these is pending; null handles are ignored.
        unsafe {
            self.ctx.device.destroy_pipeline(self.raw, None);
            self.ctx.device.destroy_pipeline_layout(self.layout, None);
            self.ctx.device.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}
