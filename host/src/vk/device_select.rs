//! Choosing a physical device that can run twinray, and saying what the others lack.

use crate::error::{Error, Result, VkContext};
use ash::vk;
use std::ffi::CStr;

/// Device extensions twinray needs.
pub const REQUIRED_EXTENSIONS: [&CStr; 3] = [
    ash::khr::acceleration_structure::NAME,
    ash::khr::ray_tracing_pipeline::NAME,
    ash::khr::deferred_host_operations::NAME,
];

/// A device that passed [`missing_requirements`], and the queue family to use on it.
pub struct Candidate {
    pub physical: vk::PhysicalDevice,
    pub name: String,
    pub queue_family: u32,
}

/// Picks the first suitable device whose name contains `filter` (any, if `None`), preferring
/// discrete, then integrated, then other GPUs, then CPU implementations.
pub fn pick(instance: &ash::Instance, filter: Option<&str>) -> Result<Candidate> {
    // SAFETY: the instance is valid for the duration of the call.
    let devices = unsafe { instance.enumerate_physical_devices() }.call("vkEnumeratePhysicalDevices")?;
    let mut rejected = Vec::new();
    let mut best: Option<(u32, Candidate)> = None;
    for physical in devices {
        // SAFETY: physical comes from this instance.
        let props = unsafe { instance.get_physical_device_properties(physical) };
        let name = props.device_name_as_c_str().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if filter.is_some_and(|f| !name.to_lowercase().contains(&f.to_lowercase())) {
            rejected.push(format!("{name}: does not match --device {:?}", filter.unwrap_or_default()));
            continue;
        }
        let missing = missing_requirements(instance, physical, props.api_version)?;
        let queue_family = compute_queue_family(instance, physical);
        match (missing.is_empty(), queue_family) {
            (true, Some(queue_family)) => {
                let rank = match props.device_type {
                    vk::PhysicalDeviceType::DISCRETE_GPU => 0,
                    vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
                    vk::PhysicalDeviceType::CPU => 3,
                    _ => 2,
                };
                if best.as_ref().is_none_or(|(r, _)| rank < *r) {
                    best = Some((rank, Candidate { physical, name, queue_family }));
                }
            }
            (true, None) => rejected.push(format!("{name}: no compute queue")),
            (false, _) => rejected.push(format!("{name}: lacks {}", missing.join(", "))),
        }
    }
    match best {
        Some((_, candidate)) => Ok(candidate),
        None if rejected.is_empty() => Err(Error::NoDevice(
            "the Vulkan loader found no device; install a driver (cargo xtask setup installs Mesa lavapipe)".into(),
        )),
        None => Err(Error::NoDevice(rejected.join("; "))),
    }
}

/// Extensions twinray enables where the device has them: pipeline libraries (`--pipeline
/// libraries`), ray queries (tracing inline, without the pipeline's shader table; every
/// device with the extension has its `rayQuery` feature) and robust access (`device`).
pub const OPTIONAL_EXTENSIONS: [&CStr; 3] =
    [ash::khr::pipeline_library::NAME, ash::khr::ray_query::NAME, ash::ext::robustness2::NAME];

/// The optional extensions `physical` has.
pub fn optional_extensions(instance: &ash::Instance, physical: vk::PhysicalDevice) -> Result<Vec<&'static CStr>> {
    // SAFETY: physical comes from this instance.
    let available = unsafe { instance.enumerate_device_extension_properties(physical) }
        .call("vkEnumerateDeviceExtensionProperties")?;
    Ok(OPTIONAL_EXTENSIONS
        .into_iter()
        .filter(|wanted| available.iter().any(|e| e.extension_name_as_c_str() == Ok(*wanted)))
        .collect())
}

/// What `physical` lacks of twinray's needs, by name; empty when it has everything.
pub fn missing_requirements(instance: &ash::Instance, physical: vk::PhysicalDevice, api: u32) -> Result<Vec<String>> {
    let mut missing = Vec::new();
    if api < vk::API_VERSION_1_2 {
        missing.push(format!("Vulkan 1.2 (device has {}.{})", vk::api_version_major(api), vk::api_version_minor(api)));
        return Ok(missing);
    }
    // SAFETY: physical comes from this instance.
    let available = unsafe { instance.enumerate_device_extension_properties(physical) }
        .call("vkEnumerateDeviceExtensionProperties")?;
    for required in REQUIRED_EXTENSIONS {
        if !available.iter().any(|e| e.extension_name_as_c_str() == Ok(required)) {
            missing.push(required.to_string_lossy().into_owned());
        }
    }
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut accel = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default();
    let mut rt = vk::PhysicalDeviceRayTracingPipelineFeaturesKHR::default();
    let mut features = vk::PhysicalDeviceFeatures2::default();
    if missing.is_empty() {
        features = features.push_next(&mut f12).push_next(&mut accel).push_next(&mut rt);
    } else {
        features = features.push_next(&mut f12);
    }
    // SAFETY: the chained structs live until the call returns.
    unsafe { instance.get_physical_device_features2(physical, &mut features) };
    let checks = [(f12.buffer_device_address, "bufferDeviceAddress"), (f12.vulkan_memory_model, "vulkanMemoryModel")];
    for (have, name) in checks {
        if have == vk::FALSE {
            missing.push(name.into());
        }
    }
    if missing.is_empty() {
        if accel.acceleration_structure == vk::FALSE {
            missing.push("accelerationStructure".into());
        }
        if rt.ray_tracing_pipeline == vk::FALSE {
            missing.push("rayTracingPipeline".into());
        }
    }
    Ok(missing)
}

fn compute_queue_family(instance: &ash::Instance, physical: vk::PhysicalDevice) -> Option<u32> {
    // SAFETY: physical comes from this instance.
    let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
    families.iter().position(|f| f.queue_flags.contains(vk::QueueFlags::COMPUTE)).and_then(|i| u32::try_from(i).ok())
}
