//! Bottom- and top-level acceleration structures: BLASes of AABBs, and a TLAS of instances.

use super::buffer::Buffer;
use super::commands::{memory_barrier, OneShot};
use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use glam::Mat4;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// An acceleration structure with its storage buffer and device address.
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

/// One TLAS instance: a BLAS placed by an affine transform.
#[derive(Clone, Copy, Debug)]
pub struct InstanceRecord {
    pub object_to_world: Mat4,
    /// The instance custom index (24 bits).
    pub custom_index: u32,
    pub mask: u32,
    /// The instance's SBT record offset (24 bits).
    pub sbt_offset: u32,
    pub blas_address: vk::DeviceAddress,
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

/// A BLAS over one mesh: `vertex_count` vertices of `vertex_stride` bytes (an f32 position at
/// offset 0) from `vertices`, `index_count` u32 indices from `indices` (device addresses), all opaque.
pub fn build_triangle_blas(
    ctx: &Arc<Context>,
    one_shot: &OneShot,
    vertices: vk::DeviceAddress,
    vertex_stride: u64,
    vertex_count: u32,
    indices: vk::DeviceAddress,
    index_count: u32,
) -> Result<AccelStruct> {
    let data = vk::AccelerationStructureGeometryTrianglesDataKHR::default()
        .vertex_format(vk::Format::R32G32B32_SFLOAT)
        .vertex_data(vk::DeviceOrHostAddressConstKHR { device_address: vertices })
        .vertex_stride(vertex_stride)
        .max_vertex(vertex_count.saturating_sub(1))
        .index_type(vk::IndexType::UINT32)
        .index_data(vk::DeviceOrHostAddressConstKHR { device_address: indices });
    let geometry = vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::TRIANGLES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { triangles: data })
        .flags(vk::GeometryFlagsKHR::OPAQUE);
    build(ctx, one_shot, vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, geometry, index_count / 3, "mesh blas")
}

/// A TLAS over `instances`.
pub fn build_tlas(ctx: &Arc<Context>, one_shot: &OneShot, instances: &[InstanceRecord]) -> Result<AccelStruct> {
    let instance: Vec<u8> = instances.iter().flat_map(instance_bytes).collect();
    let usage = vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
        | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
    let instance_buffer = Buffer::with_data(ctx, "instances", &instance, usage)?;
    let data = vk::AccelerationStructureGeometryInstancesDataKHR::default()
        .array_of_pointers(false)
        .data(vk::DeviceOrHostAddressConstKHR { device_address: instance_buffer.device_address() });
    let geometry = vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::INSTANCES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { instances: data });
    build(ctx, one_shot, vk::AccelerationStructureTypeKHR::TOP_LEVEL, geometry, instances.len() as u32, "tlas")
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

/// VkAabbPositionsKHR as bytes.
fn aabb_bytes(b: &vk::AabbPositionsKHR) -> Vec<u8> {
    [b.min_x, b.min_y, b.min_z, b.max_x, b.max_y, b.max_z].iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// VkAccelerationStructureInstanceKHR as bytes: the 3x4 row-major transform, custom index and
/// mask, SBT offset and flags (culling off: procedural geometry has no facing), BLAS address.
fn instance_bytes(r: &InstanceRecord) -> Vec<u8> {
    let m = r.object_to_world;
    let rows = [m.row(0), m.row(1), m.row(2)];
    let mut bytes: Vec<u8> = rows.iter().flat_map(|row| row.to_array()).flat_map(f32::to_le_bytes).collect();
    let custom_index_and_mask = (r.custom_index & 0x00ff_ffff) | ((r.mask & 0xff) << 24);
    let flags = vk::GeometryInstanceFlagsKHR::TRIANGLE_FACING_CULL_DISABLE.as_raw();
    let sbt_offset_and_flags = (r.sbt_offset & 0x00ff_ffff) | (flags << 24);
    bytes.extend_from_slice(&custom_index_and_mask.to_le_bytes());
    bytes.extend_from_slice(&sbt_offset_and_flags.to_le_bytes());
    bytes.extend_from_slice(&r.blas_address.to_le_bytes());
    bytes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instance_record_has_vulkan_layout() {
        let record = InstanceRecord {
            object_to_world: Mat4::from_translation(glam::Vec3::new(1.0, 2.0, 3.0)),
            custom_index: 5,
            mask: 2,
            sbt_offset: 7,
            blas_address: 0x1234,
        };
        let bytes = instance_bytes(&record);
        assert_eq!(bytes.len(), size_of::<vk::AccelerationStructureInstanceKHR>());
        let word = |i: usize| u32::from_le_bytes([bytes[4 * i], bytes[4 * i + 1], bytes[4 * i + 2], bytes[4 * i + 3]]);
        // Row 0 is (1, 0, 0, tx): the translation sits in the fourth column.
        assert_eq!(f32::from_bits(word(3)), 1.0);
        assert_eq!(f32::from_bits(word(11)), 3.0);
        assert_eq!(word(12), 5 | (2 << 24));
        assert_eq!(word(13) & 0x00ff_ffff, 7);
    }
}
