//! Bottom- and top-level acceleration structures: one BLAS of AABBs, one TLAS of instances.

use super::buffer::Buffer;
use super::commands::{memory_barrier, OneShot};
use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

pub struct AccelStruct {
    ctx: Arc<Context>,
    pub raw: vk::AccelerationStructureKHR,
    pub address: vk::DeviceAddress,
    _storage: Buffer,
}

impl Drop for AccelStruct {
    fn drop(&mut self) {
        // SAFETY: the GPU work using it has completed; the storage buffer is dropped after.
        unsafe { self.ctx.accel.destroy_acceleration_structure(self.raw, None) };
    }
}

/// A BLAS over axis-aligned boxes, one procedural primitive each, all opaque.
pub fn build_aabb_blas(ctx: &Arc<Context>, one_shot: &OneShot, aabbs: &[vk::AabbPositionsKHR]) -> Result<AccelStruct> {
    let bytes: Vec<u8> = aabbs.iter().flat_map(aabb_bytes).collect();
    let usage = vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
        | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
    let aabb_buffer = Buffer::with_data(ctx, "aabbs", &bytes, usage)?;
    let data = vk::AccelerationStructureGeometryAabbsDataKHR::default()
        .data(vk::DeviceOrHostAddressConstKHR { device_address: aabb_buffer.device_address() })
        .stride(size_of::<vk::AabbPositionsKHR>() as u64);
    let geometry = vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::AABBS)
        .geometry(vk::AccelerationStructureGeometryDataKHR { aabbs: data })
        .flags(vk::GeometryFlagsKHR::OPAQUE);
    build(ctx, one_shot, vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, geometry, aabbs.len() as u32, "blas")
}

/// A TLAS with one instance of `blas` under the identity transform.
pub fn build_single_instance_tlas(ctx: &Arc<Context>, one_shot: &OneShot, blas: &AccelStruct) -> Result<AccelStruct> {
    let instance = instance_bytes(blas.address);
    let usage = vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
        | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
    let instance_buffer = Buffer::with_data(ctx, "instances", &instance, usage)?;
    let data = vk::AccelerationStructureGeometryInstancesDataKHR::default()
        .array_of_pointers(false)
        .data(vk::DeviceOrHostAddressConstKHR { device_address: instance_buffer.device_address() });
    let geometry = vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::INSTANCES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { instances: data });
    build(ctx, one_shot, vk::AccelerationStructureTypeKHR::TOP_LEVEL, geometry, 1, "tlas")
}

fn build(
    ctx: &Arc<Context>,
    one_shot: &OneShot,
    ty: vk::AccelerationStructureTypeKHR,
    geometry: vk::AccelerationStructureGeometryKHR<'_>,
    primitive_count: u32,
    name: &str,
) -> Result<AccelStruct> {
    let geometries = [geometry];
    let mut info = vk::AccelerationStructureBuildGeometryInfoKHR::default()
        .ty(ty)
        .flags(vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_TRACE)
        .mode(vk::BuildAccelerationStructureModeKHR::BUILD)
        .geometries(&geometries);
    let mut sizes = vk::AccelerationStructureBuildSizesInfoKHR::default();
    // SAFETY: info describes geometry whose buffers are alive.
    unsafe {
        ctx.accel.get_acceleration_structure_build_sizes(
            vk::AccelerationStructureBuildTypeKHR::DEVICE,
            &info,
            &[primitive_count],
            &mut sizes,
        )
    };
    let storage = Buffer::new(
        ctx,
        name,
        sizes.acceleration_structure_size,
        vk::BufferUsageFlags::ACCELERATION_STRUCTURE_STORAGE_KHR | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS,
        MemoryLocation::GpuOnly,
    )?;
    let create = vk::AccelerationStructureCreateInfoKHR::default()
        .buffer(storage.raw)
        .size(sizes.acceleration_structure_size)
        .ty(ty);
    // SAFETY: the storage buffer is large enough and outlives the structure (held in AccelStruct).
    let raw =
        unsafe { ctx.accel.create_acceleration_structure(&create, None) }.call("vkCreateAccelerationStructureKHR")?;
    let address_info = vk::AccelerationStructureDeviceAddressInfoKHR::default().acceleration_structure(raw);
    // SAFETY: raw is live.
    let address = unsafe { ctx.accel.get_acceleration_structure_device_address(&address_info) };
    let accel = AccelStruct { ctx: ctx.clone(), raw, address, _storage: storage };
    // Scratch must be aligned to minAccelerationStructureScratchOffsetAlignment: over-allocate and round up.
    let align = u64::from(ctx.info.min_scratch_offset_alignment.max(1));
    let scratch = Buffer::new(
        ctx,
        "scratch",
        sizes.build_scratch_size + align,
        vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS,
        MemoryLocation::GpuOnly,
    )?;
    info = info
        .dst_acceleration_structure(raw)
        .scratch_data(vk::DeviceOrHostAddressKHR { device_address: scratch.device_address().next_multiple_of(align) });
    let range = [vk::AccelerationStructureBuildRangeInfoKHR::default().primitive_count(primitive_count)];
    one_shot.run(|device, cmd| {
        // SAFETY: every buffer referenced by `info` is alive until run() has waited.
        unsafe { ctx.accel.cmd_build_acceleration_structures(cmd, &[info], &[&range]) };
        // The build's writes must land before a later build or trace reads the structure.
        let build = (
            vk::PipelineStageFlags::ACCELERATION_STRUCTURE_BUILD_KHR,
            vk::AccessFlags::ACCELERATION_STRUCTURE_WRITE_KHR,
        );
        let read = (
            vk::PipelineStageFlags::ACCELERATION_STRUCTURE_BUILD_KHR | vk::PipelineStageFlags::RAY_TRACING_SHADER_KHR,
            vk::AccessFlags::ACCELERATION_STRUCTURE_READ_KHR,
        );
        memory_barrier(device, cmd, build, read);
        Ok(())
    })?;
    Ok(accel)
}

fn aabb_bytes(b: &vk::AabbPositionsKHR) -> Vec<u8> {
    [b.min_x, b.min_y, b.min_z, b.max_x, b.max_y, b.max_z].iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// VkAccelerationStructureInstanceKHR as bytes: identity 3x4 transform, custom index 0,
/// mask 0xff, SBT offset 0, culling off (procedural geometry has no facing), BLAS address.
fn instance_bytes(blas_address: vk::DeviceAddress) -> Vec<u8> {
    let transform: [f32; 12] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let mut bytes: Vec<u8> = transform.iter().flat_map(|v| v.to_le_bytes()).collect();
    let custom_index_and_mask: u32 = 0xff << 24;
    let flags = vk::GeometryInstanceFlagsKHR::TRIANGLE_FACING_CULL_DISABLE.as_raw();
    let sbt_offset_and_flags: u32 = flags << 24;
    bytes.extend_from_slice(&custom_index_and_mask.to_le_bytes());
    bytes.extend_from_slice(&sbt_offset_and_flags.to_le_bytes());
    bytes.extend_from_slice(&blas_address.to_le_bytes());
    bytes
}

#[cfg(test)]
mod tests {
    #[test]
    fn instance_record_has_vulkan_size() {
        assert_eq!(super::instance_bytes(0).len(), size_of::<ash::vk::AccelerationStructureInstanceKHR>());
    }
}
