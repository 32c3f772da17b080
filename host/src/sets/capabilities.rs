//! What a module asks of the device: every `OpCapability` and `OpExtension` it declares, checked
//! against what twinray enabled on the device before any pipeline is made. A driver handed a
//! module that needs what it was not asked to turn on may fail with no word of why ("an unknown
//! error has occurred") or compile it wrongly; here the module, the capability and the device
//! are named, always, not only under `--validate`.

use crate::vk::device::DeviceInfo;

/// What turns a capability or extension on, on a device twinray made (Vulkan 1.2 with the ray
/// tracing pipeline, acceleration structures, `bufferDeviceAddress`, `vulkanMemoryModel`,
/// `runtimeDescriptorArray` and `shaderSampledImageArrayNonUniformIndexing`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Enabled {
    /// Core Vulkan 1.2 with no feature, or a feature twinray always turns on.
    Always,
    /// VK_KHR_ray_query with its `rayQuery` feature, where the device has them.
    RayQuery,
    /// Something twinray does not turn on: the feature or extension, named.
    Not(&'static str),
}
use Enabled::{Always, Not, RayQuery};

/// (number, name, what enables it) of the capabilities a Vulkan ray tracing module may
/// declare. The SPIR-V validator (Vulkan 1.1 / SPIR-V 1.4) has already refused the ones
/// Vulkan does not allow at all.
const CAPABILITIES: &[(u32, &str, Enabled)] = &[
    (0, "Matrix", Always),
    (1, "Shader", Always),
    (9, "Float16", Not("the shaderFloat16 feature")),
    (10, "Float64", Not("the shaderFloat64 feature")),
    (11, "Int64", Not("the shaderInt64 feature")),
    (12, "Int64Atomics", Not("the shaderBufferInt64Atomics feature")),
    (22, "Int16", Not("the shaderInt16 feature")),
    (39, "Int8", Not("the shaderInt8 feature")),
    (40, "InputAttachment", Always),
    (43, "Sampled1D", Always),
    (44, "Image1D", Always),
    (46, "SampledBuffer", Always),
    (47, "ImageBuffer", Always),
    (49, "StorageImageExtendedFormats", Always),
    (50, "ImageQuery", Always),
    (51, "DerivativeControl", Always),
    (55, "StorageImageReadWithoutFormat", Not("the shaderStorageImageReadWithoutFormat feature")),
    (56, "StorageImageWriteWithoutFormat", Not("the shaderStorageImageWriteWithoutFormat feature")),
    (61, "GroupNonUniform", Always),
    (62, "GroupNonUniformVote", Always),
    (63, "GroupNonUniformArithmetic", Always),
    (64, "GroupNonUniformBallot", Always),
    (65, "GroupNonUniformShuffle", Always),
    (66, "GroupNonUniformShuffleRelative", Always),
    (67, "GroupNonUniformClustered", Always),
    (68, "GroupNonUniformQuad", Always),
    (4427, "DrawParameters", Not("the shaderDrawParameters feature")),
    (4433, "StorageBuffer16BitAccess", Not("the storageBuffer16BitAccess feature")),
    (4434, "UniformAndStorageBuffer16BitAccess", Not("the uniformAndStorageBuffer16BitAccess feature")),
    (4437, "DeviceGroup", Always),
    (4445, "VariablePointersStorageBuffer", Not("the variablePointersStorageBuffer feature")),
    (4446, "VariablePointers", Not("the variablePointers feature")),
    (4448, "StorageBuffer8BitAccess", Not("the storageBuffer8BitAccess feature")),
    (4449, "UniformAndStorageBuffer8BitAccess", Not("the uniformAndStorageBuffer8BitAccess feature")),
    (4464, "DenormPreserve", Not("the shaderDenormPreserve property")),
    (4465, "DenormFlushToZero", Not("the shaderDenormFlushToZero property")),
    (4466, "SignedZeroInfNanPreserve", Not("the shaderSignedZeroInfNanPreserve property")),
    (4467, "RoundingModeRTE", Not("the shaderRoundingModeRTE property")),
    (4468, "RoundingModeRTZ", Not("the shaderRoundingModeRTZ property")),
    (4472, "RayQueryKHR", RayQuery),
    (4478, "RayTraversalPrimitiveCullingKHR", Not("the rayTraversalPrimitiveCulling feature")),
    (4479, "RayTracingKHR", Always),
    (5301, "ShaderNonUniform", Always),
    (5302, "RuntimeDescriptorArray", Always),
    (5307, "SampledImageArrayNonUniformIndexing", Always),
    (5308, "StorageBufferArrayNonUniformIndexing", Not("the shaderStorageBufferArrayNonUniformIndexing feature")),
    (5309, "StorageImageArrayNonUniformIndexing", Not("the shaderStorageImageArrayNonUniformIndexing feature")),
    (5336, "RayTracingPositionFetchKHR", Not("VK_KHR_ray_tracing_position_fetch")),
    (5340, "RayTracingNV", Not("VK_NV_ray_tracing")),
    (5341, "RayTracingMotionBlurNV", Not("VK_NV_ray_tracing_motion_blur")),
    (5345, "VulkanMemoryModel", Always),
    (5346, "VulkanMemoryModelDeviceScope", Not("the vulkanMemoryModelDeviceScope feature")),
    (5347, "PhysicalStorageBufferAddresses", Always),
    (5383, "ShaderInvocationReorderNV", Not("VK_NV_ray_tracing_invocation_reorder")),
    (5391, "RayQueryPositionFetchKHR", Not("VK_KHR_ray_tracing_position_fetch")),
];

/// SPIR-V extensions and what enables them: core in Vulkan 1.2, or the device extension.
const EXTENSIONS: &[(&str, Enabled)] = &[
    ("SPV_KHR_ray_tracing", Always),
    ("SPV_KHR_ray_query", RayQuery),
    ("SPV_KHR_vulkan_memory_model", Always),
    ("SPV_KHR_physical_storage_buffer", Always),
    ("SPV_EXT_descriptor_indexing", Always),
    ("SPV_KHR_storage_buffer_storage_class", Always),
    ("SPV_KHR_variable_pointers", Always),
    ("SPV_KHR_shader_draw_parameters", Always),
    ("SPV_KHR_16bit_storage", Always),
    ("SPV_KHR_8bit_storage", Always),
    ("SPV_KHR_float_controls", Always),
    ("SPV_KHR_multiview", Always),
    ("SPV_KHR_device_group", Always),
    ("SPV_KHR_no_integer_wrap_decoration", Always),
    ("SPV_GOOGLE_decorate_string", Always),
    ("SPV_GOOGLE_hlsl_functionality1", Always),
    ("SPV_GOOGLE_user_type", Always),
    ("SPV_KHR_non_semantic_info", Not("VK_KHR_shader_non_semantic_info")),
    ("SPV_KHR_ray_tracing_position_fetch", Not("VK_KHR_ray_tracing_position_fetch")),
    ("SPV_NV_ray_tracing", Not("VK_NV_ray_tracing")),
    ("SPV_NV_ray_tracing_motion_blur", Not("VK_NV_ray_tracing_motion_blur")),
    ("SPV_NV_shader_invocation_reorder", Not("VK_NV_ray_tracing_invocation_reorder")),
];

/// What of `enabled` `device` lacks, in words; none when it has it.
fn lacking(enabled: Enabled, device: &DeviceInfo) -> Option<String> {
    match enabled {
        Always => None,
        RayQuery if device.ray_query => None,
        RayQuery => Some("VK_KHR_ray_query, which the device lacks".into()),
        Not(what) => Some(format!("{what}, which twinray does not enable")),
    }
}

/// The first capability or extension `module` (the module named `name`, from `origin`)
/// declares that `device` does not have enabled, in words naming the module, what it declares,
/// what that needs and the device; none when the device has everything the module asks for.
pub fn missing(
    name: &str,
    origin: &str,
    info: &twinray_shared::spirv_info::ModuleInfo,
    device: &DeviceInfo,
) -> Option<String> {
    let refuse = |what: String, needs: String| {
        format!("the {name} module ({origin}) declares {what}, which needs {needs}, on {}", device.name)
    };
    if let Some(v) = twinray_shared::catalog::spirv_version(info.version).filter(|v| v.vulkan > device.vulkan) {
        let (have, need) = (device.vulkan, v.vulkan);
        return Some(format!(
            "the {name} module ({origin}) is SPIR-V {}.{}, which needs Vulkan {}.{}; {} runs Vulkan {}.{}",
            v.spirv.0, v.spirv.1, need.0, need.1, device.name, have.0, have.1
        ));
    }
    for &cap in &info.capabilities {
        match CAPABILITIES.iter().find(|c| c.0 == cap) {
            Some(&(_, cap_name, enabled)) => {
                if let Some(needs) = lacking(enabled, device) {
                    return Some(refuse(format!("capability {cap_name}"), needs));
                }
            }
            None => {
                return Some(refuse(format!("capability {cap}"), "a feature twinray does not know of or enable".into()))
            }
        }
    }
    for ext in &info.extensions {
        match EXTENSIONS.iter().find(|e| e.0 == ext) {
            Some(&(_, enabled)) => {
                if let Some(needs) = lacking(enabled, device) {
                    return Some(refuse(format!("extension {ext}"), needs));
                }
            }
            None => {
                return Some(refuse(
                    format!("extension {ext}"),
                    "a device extension twinray does not know of or enable".into(),
                ))
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use twinray_shared::spirv_info::ModuleInfo;

    fn device(ray_query: bool) -> DeviceInfo {
        DeviceInfo {
            name: "test gpu".into(),
            device_type: String::new(),
            api_version: String::new(),
            vulkan: (1, 2),
            driver_name: String::new(),
            driver_info: String::new(),
            shader_group_handle_size: 32,
            shader_group_handle_alignment: 32,
            shader_group_base_alignment: 64,
            max_ray_recursion_depth: 1,
            max_ray_dispatch_invocation_count: 1 << 30,
            max_image_dimension_2d: 16384,
            min_scratch_offset_alignment: 128,
            max_primitive_count: 1 << 29,
            max_geometry_count: 1 << 24,
            max_instance_count: 1 << 24,
            timestamp_period_ns: 1.0,
            timestamp_valid_bits: 64,
            cpu_threads: None,
            pipeline_library: true,
            ray_query,
            robustness: Default::default(),
            host_acceleration_structure_commands: false,
        }
    }

    #[test]
    fn a_module_newer_than_the_device_runs_is_refused_naming_both_versions() {
        let mut info = ModuleInfo { version: (1, 6), ..ModuleInfo::default() };
        let e = missing("raygen", "mine.spv", &info, &device(false)).expect("SPIR-V 1.6 on Vulkan 1.2");
        assert_eq!(e, "the raygen module (mine.spv) is SPIR-V 1.6, which needs Vulkan 1.3; test gpu runs Vulkan 1.2");
        info.version = (1, 5);
        assert_eq!(missing("raygen", "mine.spv", &info, &device(false)), None);
    }

    #[test]
    fn names_the_module_the_capability_and_the_device() {
        let motion = ModuleInfo { capabilities: vec![1, 4479, 5341], ..Default::default() };
        let e = missing("raygen", "blur.spv", &motion, &device(true)).unwrap();
        assert_eq!(
            e,
            "the raygen module (blur.spv) declares capability RayTracingMotionBlurNV, which needs \
             VK_NV_ray_tracing_motion_blur, which twinray does not enable, on test gpu"
        );
        let query = ModuleInfo { capabilities: vec![1, 4472], ..Default::default() };
        assert!(missing("raygen_query", "rust", &query, &device(true)).is_none());
        assert!(missing("raygen_query", "rust", &query, &device(false))
            .unwrap()
            .contains("VK_KHR_ray_query, which the device lacks"));
        let unknown = ModuleInfo { capabilities: vec![1, 99999], ..Default::default() };
        assert!(missing("miss", "m.spv", &unknown, &device(true)).unwrap().contains("capability 99999"));
        let info = ModuleInfo {
            capabilities: vec![1],
            extensions: vec!["SPV_KHR_non_semantic_info".into()],
            ..Default::default()
        };
        assert!(missing("miss", "m.spv", &info, &device(true)).unwrap().contains("VK_KHR_shader_non_semantic_info"));
    }

    #[test]
    fn every_committed_module_is_allowed_where_the_device_has_ray_queries() {
        for spec in twinray_shared::catalog::MODULES {
            for language in twinray_shared::catalog::Language::ALL {
                let Some(bytes) = crate::sets::builtin::spirv(language, spec.name) else { continue };
                let info = twinray_shared::spirv_info::parse(bytes).unwrap();
                assert_eq!(missing(spec.name, language.name(), &info, &device(true)), None);
            }
        }
    }
}
