//! The logical device: which features and extensions twinray turns on (ray tracing, and
//! where the device has them pipeline libraries, ray queries and robust access), and what
//! the device is and can do, as `twinray info` reports it.

use super::device_select::{Candidate, REQUIRED_EXTENSIONS};
use crate::error::{Result, VkContext};
use ash::vk;
use std::ffi::CStr;

/// What a device is and can do, as reported by `twinray info` and used to lay out the SBT.
#[derive(Clone, Debug, serde::Serialize)]
pub struct DeviceInfo {
    pub name: String,
    pub device_type: String,
    pub api_version: String,
    /// The Vulkan version twinray can use on the device: the device's, at most the instance's
    /// (which says what SPIR-V its modules may be, `twinray_shared::catalog::SPIRV_VERSIONS`).
    pub vulkan: (u32, u32),
    pub driver_name: String,
    pub driver_info: String,
    pub shader_group_handle_size: u32,
    pub shader_group_handle_alignment: u32,
    pub shader_group_base_alignment: u32,
    pub max_ray_recursion_depth: u32,
    pub max_ray_dispatch_invocation_count: u32,
    pub max_image_dimension_2d: u32,
    pub min_scratch_offset_alignment: u32,
    /// Most triangles or boxes in one bottom-level structure (`maxPrimitiveCount`).
    pub max_primitive_count: u64,
    /// Most geometries in one bottom-level structure (`maxGeometryCount`).
    pub max_geometry_count: u64,
    /// Most instances in one top-level structure (`maxInstanceCount`).
    pub max_instance_count: u64,
    /// Nanoseconds per timestamp tick.
    pub timestamp_period_ns: f32,
    /// Valid bits of timestamps on the queue used; 0 means no GPU timing.
    pub timestamp_valid_bits: u32,
    /// Threads of a CPU device (lavapipe): LP_NUM_THREADS if set, else the CPU count, which
    /// is what lavapipe uses; `None` for GPUs.
    pub cpu_threads: Option<u32>,
    /// Whether the device has (and twinray enabled) VK_KHR_pipeline_library.
    pub pipeline_library: bool,
    /// Whether the device has (and twinray enabled) VK_KHR_ray_query with its `rayQuery`
    /// feature.
    pub ray_query: bool,
    /// Robust access twinray turned on (see [`Robustness`]).
    pub robustness: Robustness,
    /// Whether the device can build acceleration structures on the host
    /// (`accelerationStructureHostCommands`); twinray builds them on the device either way.
    pub host_acceleration_structure_commands: bool,
}

/// Robust access (VK_EXT_robustness2) as twinray turned it on: with `buffer`, a read outside
/// a bound buffer gives zero and a write there is dropped; with `image`, the same for images.
/// So a stage reading past its data behaves the same on every driver, and both sets of a
/// comparison see the same zeros, instead of whatever memory lies there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Robustness {
    pub buffer_access2: bool,
    pub image_access2: bool,
}

/// The robust access `physical` offers, when it has VK_EXT_robustness2 among `optional`.
pub(super) fn robustness(instance: &ash::Instance, physical: vk::PhysicalDevice, optional: &[&CStr]) -> Robustness {
    if !optional.contains(&ash::ext::robustness2::NAME) {
        return Robustness::default();
    }
    let mut robust2 = vk::PhysicalDeviceRobustness2FeaturesEXT::default();
    let mut features = vk::PhysicalDeviceFeatures2::default().push_next(&mut robust2);
    // SAFETY: the chained struct lives until the call returns; the extension is present.
    unsafe { instance.get_physical_device_features2(physical, &mut features) };
    // robustBufferAccess2 needs the core robustBufferAccess.
    let core = features.features.robust_buffer_access == vk::TRUE;
    Robustness {
        buffer_access2: core && robust2.robust_buffer_access2 == vk::TRUE,
        image_access2: robust2.robust_image_access2 == vk::TRUE,
    }
}

/// The logical device with twinray's features, the `optional` extensions the device has,
/// and robust access as `robust` says (a subset of what [`robustness`] found).
pub(super) fn create_device(
    instance: &ash::Instance,
    candidate: &Candidate,
    optional: &[&CStr],
    robust: Robustness,
) -> Result<ash::Device> {
    let priorities = [1.0];
    let queues =
        [vk::DeviceQueueCreateInfo::default().queue_family_index(candidate.queue_family).queue_priorities(&priorities)];
    let extensions: Vec<_> = REQUIRED_EXTENSIONS.iter().chain(optional).map(|e| e.as_ptr()).collect();
    // The texture array: a runtime array of combined image samplers indexed per hit.
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default()
        .buffer_device_address(true)
        .vulkan_memory_model(true)
        .runtime_descriptor_array(true)
        .shader_sampled_image_array_non_uniform_indexing(true);
    let mut accel = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default().acceleration_structure(true);
    let mut rt = vk::PhysicalDeviceRayTracingPipelineFeaturesKHR::default().ray_tracing_pipeline(true);
    let mut query = vk::PhysicalDeviceRayQueryFeaturesKHR::default().ray_query(true);
    let core = vk::PhysicalDeviceFeatures::default().robust_buffer_access(robust.buffer_access2);
    let mut robust2 = vk::PhysicalDeviceRobustness2FeaturesEXT::default()
        .robust_buffer_access2(robust.buffer_access2)
        .robust_image_access2(robust.image_access2);
    let mut info = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queues)
        .enabled_extension_names(&extensions)
        .enabled_features(&core)
        .push_next(&mut f12)
        .push_next(&mut accel)
        .push_next(&mut rt);
    if optional.contains(&ash::khr::ray_query::NAME) {
        info = info.push_next(&mut query);
    }
    if robust != Robustness::default() {
        info = info.push_next(&mut robust2);
    }
    // SAFETY: the candidate supports every extension and feature enabled here.
    unsafe { instance.create_device(candidate.physical, &info, None) }.call("vkCreateDevice")
}

pub(super) fn device_info(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    queue_family: u32,
    name: String,
) -> DeviceInfo {
    let mut rt = vk::PhysicalDeviceRayTracingPipelinePropertiesKHR::default();
    let mut accel = vk::PhysicalDeviceAccelerationStructurePropertiesKHR::default();
    let mut driver = vk::PhysicalDeviceDriverProperties::default();
    let mut props2 =
        vk::PhysicalDeviceProperties2::default().push_next(&mut rt).push_next(&mut accel).push_next(&mut driver);
    // SAFETY: the chained structs live until the call returns.
    unsafe { instance.get_physical_device_properties2(physical, &mut props2) };
    let props = props2.properties;
    let mut accel_features = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default();
    let mut features = vk::PhysicalDeviceFeatures2::default().push_next(&mut accel_features);
    // SAFETY: the chained struct lives until the call returns; the device was chosen for having
    // VK_KHR_acceleration_structure.
    unsafe { instance.get_physical_device_features2(physical, &mut features) };
    // SAFETY: physical comes from this instance.
    let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
    let text = |c: Result<&std::ffi::CStr, _>| c.map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    DeviceInfo {
        name,
        device_type: format!("{:?}", props.device_type),
        cpu_threads: (props.device_type == vk::PhysicalDeviceType::CPU).then(cpu_threads),
        pipeline_library: false,
        ray_query: false,
        robustness: Robustness::default(),
        host_acceleration_structure_commands: accel_features.acceleration_structure_host_commands == vk::TRUE,
        api_version: format!(
            "{}.{}.{}",
            vk::api_version_major(props.api_version),
            vk::api_version_minor(props.api_version),
            vk::api_version_patch(props.api_version)
        ),
        vulkan: (vk::api_version_major(props.api_version), vk::api_version_minor(props.api_version)),
        driver_name: text(driver.driver_name_as_c_str()),
        driver_info: text(driver.driver_info_as_c_str()),
        shader_group_handle_size: rt.shader_group_handle_size,
        shader_group_handle_alignment: rt.shader_group_handle_alignment,
        shader_group_base_alignment: rt.shader_group_base_alignment,
        max_ray_recursion_depth: rt.max_ray_recursion_depth,
        max_ray_dispatch_invocation_count: rt.max_ray_dispatch_invocation_count,
        max_image_dimension_2d: props.limits.max_image_dimension2_d,
        min_scratch_offset_alignment: accel.min_acceleration_structure_scratch_offset_alignment,
        max_primitive_count: accel.max_primitive_count,
        max_geometry_count: accel.max_geometry_count,
        max_instance_count: accel.max_instance_count,
        timestamp_period_ns: props.limits.timestamp_period,
        timestamp_valid_bits: families.get(queue_family as usize).map_or(0, |f| f.timestamp_valid_bits),
    }
}

/// Rasterizer threads lavapipe runs with: LP_NUM_THREADS, or the CPUs available.
fn cpu_threads() -> u32 {
    let from_env = std::env::var("LP_NUM_THREADS").ok().and_then(|v| v.trim().parse().ok());
    from_env.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get() as u32))
}
