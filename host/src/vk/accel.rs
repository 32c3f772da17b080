//! Bottom- and top-level acceleration structures: BLASes of AABBs or triangles, built once,
//! and a TLAS of instances that can be rebuilt or updated in place frame after frame.

use super::buffer::Buffer;
use super::commands::{memory_barrier, OneShot, TRACING_STAGES};
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
    /// Bytes of its storage.
    pub bytes: u64,
    /// Bytes of its storage as first built: more than `bytes` once compacted.
    pub built_bytes: u64,
    _storage: Buffer,
}

impl Drop for AccelStruct {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return; // the GPU may still use it: see Context::abandon
        }
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
    /// Forced opaque (no any-hit stage runs), or forced not opaque (its hit group's any-hit
    /// stage runs for every candidate hit), whatever its BLAS's geometry says.
    pub opaque: bool,
    /// Triangles seen from behind are culled for rays that ask for it (primary rays): a glTF
    /// material that is not `doubleSided`. The front is counterclockwise in object space, as
    /// glTF has it (a mirroring node fronts its clockwise faces in world space); see
    /// [`facing_flags`].
    pub single_sided: bool,
    pub blas_address: vk::DeviceAddress,
}

/// The geometry of one opaque mesh: `vertex_count` vertices of `vertex_stride` bytes (an f32
/// position at offset 0) from `vertices`, u32 indices from `indices` (device addresses).
pub(super) fn triangles(
    vertices: vk::DeviceAddress,
    vertex_stride: u64,
    vertex_count: u32,
    indices: vk::DeviceAddress,
) -> vk::AccelerationStructureGeometryKHR<'static> {
    let data = vk::AccelerationStructureGeometryTrianglesDataKHR::default()
        .vertex_format(vk::Format::R32G32B32_SFLOAT)
        .vertex_data(vk::DeviceOrHostAddressConstKHR { device_address: vertices })
        .vertex_stride(vertex_stride)
        .max_vertex(vertex_count.saturating_sub(1))
        .index_type(vk::IndexType::UINT32)
        .index_data(vk::DeviceOrHostAddressConstKHR { device_address: indices });
    vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::TRIANGLES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { triangles: data })
        .flags(vk::GeometryFlagsKHR::OPAQUE)
}

/// How a TLAS is built: the `VkBuildAccelerationStructureFlagsKHR` it is built with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TlasFlags {
    /// `PREFER_FAST_TRACE`: rebuilt when it changes.
    FastTrace,
    /// `PREFER_FAST_BUILD`: rebuilt when it changes, quickly, possibly tracing slower.
    FastBuild,
    /// `ALLOW_UPDATE | PREFER_FAST_TRACE`: refitted in place (`MODE_UPDATE`) when it changes.
    Updatable,
}

impl TlasFlags {
    pub(super) fn raw(self) -> vk::BuildAccelerationStructureFlagsKHR {
        type F = vk::BuildAccelerationStructureFlagsKHR;
        match self {
            TlasFlags::FastTrace => F::PREFER_FAST_TRACE,
            TlasFlags::FastBuild => F::PREFER_FAST_BUILD,
            TlasFlags::Updatable => F::ALLOW_UPDATE | F::PREFER_FAST_TRACE,
        }
    }
}

/// A TLAS with its host-visible instance buffer and its scratch: rewritten and rebuilt (or
/// updated) in place, so descriptors that name it stay valid across frames.
pub struct Tlas {
    pub accel: AccelStruct,
    instances: Buffer,
    _scratch: Buffer,
    scratch_address: vk::DeviceAddress,
    flags: TlasFlags,
    count: u32,
}

impl Tlas {
    /// Storage and scratch for a TLAS over `instances`, which it holds; nothing is built yet.
    pub fn new(ctx: &Arc<Context>, instances: &[InstanceRecord], flags: TlasFlags) -> Result<Tlas> {
        let bytes: Vec<u8> = instances.iter().flat_map(instance_bytes).collect();
        let usage = vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
            | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
        let instance_buffer = Buffer::with_data(ctx, "instances", &bytes, usage)?;
        let count = instances.len() as u32;
        let geometry = instances_geometry(&instance_buffer);
        let info = build_info(vk::AccelerationStructureTypeKHR::TOP_LEVEL, flags.raw(), &geometry);
        let (accel, sizes) = allocate(ctx, &info, count, "tlas")?;
        let scratch_size = if flags == TlasFlags::Updatable {
            sizes.build_scratch_size.max(sizes.update_scratch_size)
        } else {
            sizes.build_scratch_size
        };
        let (scratch, scratch_address) = scratch(ctx, scratch_size)?;
        Ok(Tlas { accel, instances: instance_buffer, _scratch: scratch, scratch_address, flags, count })
    }

    /// The flags it was made with.
    pub fn flags(&self) -> TlasFlags {
        self.flags
    }

    /// Rewrites the instances (as many as it was made with) for the next build or update;
    /// the GPU must not be using the buffer.
    pub fn write(&mut self, instances: &[InstanceRecord]) -> Result<()> {
        if instances.len() as u32 != self.count {
            return Err(crate::error::Error::Unsupported(format!(
                "a TLAS of {} instances rewritten with {}",
                self.count,
                instances.len()
            )));
        }
        let bytes: Vec<u8> = instances.iter().flat_map(instance_bytes).collect();
        self.instances.write(&bytes)
    }

    /// Records a full build (`update` false) or an in-place update of an `Updatable` TLAS that
    /// was built before, between barriers: after every earlier trace and build, before every
    /// later one.
    pub fn record(&self, ctx: &Context, cmd: vk::CommandBuffer, update: bool) {
        let geometry = instances_geometry(&self.instances);
        let mode = if update && self.flags == TlasFlags::Updatable {
            vk::BuildAccelerationStructureModeKHR::UPDATE
        } else {
            vk::BuildAccelerationStructureModeKHR::BUILD
        };
        let mut info = build_info(vk::AccelerationStructureTypeKHR::TOP_LEVEL, self.flags.raw(), &geometry)
            .mode(mode)
            .dst_acceleration_structure(self.accel.raw)
            .scratch_data(vk::DeviceOrHostAddressKHR { device_address: self.scratch_address });
        if mode == vk::BuildAccelerationStructureModeKHR::UPDATE {
            info = info.src_acceleration_structure(self.accel.raw);
        }
        // SAFETY: the instance, storage and scratch buffers live as long as self.
        unsafe { record_between_barriers(ctx, cmd, info, self.count) };
    }
}

/// Records the build or update `info` of `count` primitives between barriers: after every
/// earlier trace and build, before every later one.
///
/// # Safety
/// Every buffer `info` names must live until the command buffer has completed.
pub(super) unsafe fn record_between_barriers(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    info: vk::AccelerationStructureBuildGeometryInfoKHR<'_>,
    count: u32,
) {
    // Earlier traces read the structure and earlier builds wrote it and the scratch.
    let earlier = (
        TRACING_STAGES | vk::PipelineStageFlags::ACCELERATION_STRUCTURE_BUILD_KHR,
        vk::AccessFlags::ACCELERATION_STRUCTURE_READ_KHR | vk::AccessFlags::ACCELERATION_STRUCTURE_WRITE_KHR,
    );
    let build = (
        vk::PipelineStageFlags::ACCELERATION_STRUCTURE_BUILD_KHR,
        vk::AccessFlags::ACCELERATION_STRUCTURE_READ_KHR | vk::AccessFlags::ACCELERATION_STRUCTURE_WRITE_KHR,
    );
    memory_barrier(&ctx.device, cmd, earlier, build);
    let range = [vk::AccelerationStructureBuildRangeInfoKHR::default().primitive_count(count)];
    // SAFETY: the caller keeps every buffer alive.
    unsafe { ctx.accel.cmd_build_acceleration_structures(cmd, &[info], &[&range]) };
    memory_barrier(&ctx.device, cmd, build, built_for_reading());
}

/// A TLAS over `instances`, built once.
pub fn build_tlas(ctx: &Arc<Context>, one_shot: &OneShot, instances: &[InstanceRecord]) -> Result<Tlas> {
    let tlas = Tlas::new(ctx, instances, TlasFlags::FastTrace)?;
    one_shot.run(|_, cmd| {
        tlas.record(ctx, cmd, false);
        Ok(())
    })?;
    Ok(tlas)
}

fn instances_geometry(instances: &Buffer) -> [vk::AccelerationStructureGeometryKHR<'static>; 1] {
    let data = vk::AccelerationStructureGeometryInstancesDataKHR::default()
        .array_of_pointers(false)
        .data(vk::DeviceOrHostAddressConstKHR { device_address: instances.device_address() });
    [vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::INSTANCES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { instances: data })]
}

pub(super) fn build_info<'a>(
    ty: vk::AccelerationStructureTypeKHR,
    flags: vk::BuildAccelerationStructureFlagsKHR,
    geometries: &'a [vk::AccelerationStructureGeometryKHR<'a>],
) -> vk::AccelerationStructureBuildGeometryInfoKHR<'a> {
    vk::AccelerationStructureBuildGeometryInfoKHR::default()
        .ty(ty)
        .flags(flags)
        .mode(vk::BuildAccelerationStructureModeKHR::BUILD)
        .geometries(geometries)
}

/// What reads a built structure: later builds (a TLAS over a BLAS) and traces.
pub(super) fn built_for_reading() -> (vk::PipelineStageFlags, vk::AccessFlags) {
    (
        vk::PipelineStageFlags::ACCELERATION_STRUCTURE_BUILD_KHR | TRACING_STAGES,
        vk::AccessFlags::ACCELERATION_STRUCTURE_READ_KHR,
    )
}

/// An acceleration structure of the size `info` over `primitive_count` needs, and the sizes.
pub(super) fn allocate(
    ctx: &Arc<Context>,
    info: &vk::AccelerationStructureBuildGeometryInfoKHR<'_>,
    primitive_count: u32,
    name: &str,
) -> Result<(AccelStruct, vk::AccelerationStructureBuildSizesInfoKHR<'static>)> {
    let mut sizes = vk::AccelerationStructureBuildSizesInfoKHR::default();
    // SAFETY: info describes geometry whose buffers are alive.
    unsafe {
        ctx.accel.get_acceleration_structure_build_sizes(
            vk::AccelerationStructureBuildTypeKHR::DEVICE,
            info,
            &[primitive_count],
            &mut sizes,
        )
    };
    Ok((allocate_sized(ctx, info.ty, sizes.acceleration_structure_size, name)?, sizes))
}

/// An acceleration structure of type `ty` in `bytes` of new storage, not built yet.
pub(super) fn allocate_sized(
    ctx: &Arc<Context>,
    ty: vk::AccelerationStructureTypeKHR,
    bytes: u64,
    name: &str,
) -> Result<AccelStruct> {
    let storage = Buffer::new(
        ctx,
        name,
        bytes,
        vk::BufferUsageFlags::ACCELERATION_STRUCTURE_STORAGE_KHR | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS,
        MemoryLocation::GpuOnly,
    )?;
    let create = vk::AccelerationStructureCreateInfoKHR::default().buffer(storage.raw).size(bytes).ty(ty);
    // SAFETY: the storage buffer is large enough and outlives the structure (held in AccelStruct).
    let raw =
        unsafe { ctx.accel.create_acceleration_structure(&create, None) }.call("vkCreateAccelerationStructureKHR")?;
    let address_info = vk::AccelerationStructureDeviceAddressInfoKHR::default().acceleration_structure(raw);
    // SAFETY: raw is live.
    let address = unsafe { ctx.accel.get_acceleration_structure_device_address(&address_info) };
    Ok(AccelStruct { ctx: ctx.clone(), raw, address, bytes, built_bytes: bytes, _storage: storage })
}

/// A scratch buffer of `size` bytes and its address, aligned to
/// minAccelerationStructureScratchOffsetAlignment (over-allocated, then rounded up).
pub(super) fn scratch(ctx: &Arc<Context>, size: u64) -> Result<(Buffer, vk::DeviceAddress)> {
    let align = u64::from(ctx.info.min_scratch_offset_alignment.max(1));
    let buffer = Buffer::new(
        ctx,
        "scratch",
        size + align,
        vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS,
        MemoryLocation::GpuOnly,
    )?;
    let address = buffer.device_address().next_multiple_of(align);
    Ok((buffer, address))
}

/// The facing flags of an instance: culling off where it is double-sided, else none. Vulkan
/// decides facing in object space, whatever the instance transform, and its front is the side
/// from which a triangle's corners run counterclockwise in a right-handed frame (the spec says
/// clockwise, in DXR's left-handed one): glTF's front. glTF states its rule in world space (a
/// node whose determinant is negative fronts its clockwise faces), and a mirroring transform
/// turns counterclockwise corners clockwise there: the same faces, so a mirrored instance
/// needs no flip. `tests/single_sided.rs` checks both sides and mirrored nodes.
pub fn facing_flags(single_sided: bool) -> vk::GeometryInstanceFlagsKHR {
    if single_sided {
        vk::GeometryInstanceFlagsKHR::empty()
    } else {
        vk::GeometryInstanceFlagsKHR::TRIANGLE_FACING_CULL_DISABLE
    }
}

/// VkAccelerationStructureInstanceKHR as bytes: the 3x4 row-major transform, custom index and
/// mask, SBT offset and flags (facing, [`facing_flags`]: procedural geometry has none; forced
/// opaque or not), BLAS address.
fn instance_bytes(r: &InstanceRecord) -> Vec<u8> {
    let m = r.object_to_world;
    let rows = [m.row(0), m.row(1), m.row(2)];
    let mut bytes: Vec<u8> = rows.iter().flat_map(|row| row.to_array()).flat_map(f32::to_le_bytes).collect();
    let custom_index_and_mask = (r.custom_index & 0x00ff_ffff) | ((r.mask & 0xff) << 24);
    let opacity = if r.opaque {
        vk::GeometryInstanceFlagsKHR::FORCE_OPAQUE
    } else {
        vk::GeometryInstanceFlagsKHR::FORCE_NO_OPAQUE
    };
    let flags = (facing_flags(r.single_sided) | opacity).as_raw();
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
            opaque: false,
            single_sided: false,
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
        let flags = vk::GeometryInstanceFlagsKHR::from_raw(word(13) >> 24);
        assert!(flags.contains(vk::GeometryInstanceFlagsKHR::FORCE_NO_OPAQUE));
        let opaque = instance_bytes(&InstanceRecord { opaque: true, ..record });
        let flags = u32::from_le_bytes([opaque[52], opaque[53], opaque[54], opaque[55]]) >> 24;
        assert!(vk::GeometryInstanceFlagsKHR::from_raw(flags).contains(vk::GeometryInstanceFlagsKHR::FORCE_OPAQUE));
    }
}
