//! Bottom-level structures of meshes whose vertices move (skins, morph targets): built with the
//! flags a moving scene's TLAS has, never compacted, and rebuilt or refitted in place
//! (`MODE_UPDATE`) over the same storage after the vertices are rewritten, so the TLAS
//! instances that point at them stay valid.

use super::accel::{allocate, build_info, record_between_barriers, scratch, triangles, AccelStruct, TlasFlags};
use super::buffer::Buffer;
use super::commands::OneShot;
use super::context::Context;
use crate::error::Result;
use ash::vk;
use std::sync::Arc;

/// A mesh's BLAS that follows its vertices from frame to frame.
pub struct MovingBlas {
    pub accel: AccelStruct,
    _scratch: Buffer,
    scratch_address: vk::DeviceAddress,
    flags: TlasFlags,
    /// Vertex address, stride and count, index address, index count.
    mesh: (vk::DeviceAddress, u64, u32, vk::DeviceAddress, u32),
}

impl MovingBlas {
    /// The BLAS of a mesh (`vertices`: address, stride, count; `indices`: address, count), built.
    pub fn new(
        ctx: &Arc<Context>,
        one_shot: &OneShot,
        (vertices, stride, vertex_count): (vk::DeviceAddress, u64, u32),
        (indices, index_count): (vk::DeviceAddress, u32),
        flags: TlasFlags,
    ) -> Result<MovingBlas> {
        let geometry = [triangles(vertices, stride, vertex_count, indices)];
        let info = build_info(vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, flags.raw(), &geometry);
        let (accel, sizes) = allocate(ctx, &info, index_count / 3, "moving mesh blas")?;
        let size = match flags {
            TlasFlags::Updatable => sizes.build_scratch_size.max(sizes.update_scratch_size),
            _ => sizes.build_scratch_size,
        };
        let (scratch, scratch_address) = scratch(ctx, size)?;
        let mesh = (vertices, stride, vertex_count, indices, index_count);
        let blas = MovingBlas { accel, _scratch: scratch, scratch_address, flags, mesh };
        one_shot.run(|_, cmd| {
            blas.record(ctx, cmd, false);
            Ok(())
        })?;
        Ok(blas)
    }

    /// Its mesh's triangles.
    pub fn triangles(&self) -> u32 {
        self.mesh.4 / 3
    }

    /// Records a full build (`update` false) or, where it was made updatable, a refit of the
    /// built structure to its vertices as they are now.
    pub fn record(&self, ctx: &Context, cmd: vk::CommandBuffer, update: bool) {
        let (vertices, stride, count, indices, index_count) = self.mesh;
        let geometry = [triangles(vertices, stride, count, indices)];
        let update = update && self.flags == TlasFlags::Updatable;
        let mode = match update {
            true => vk::BuildAccelerationStructureModeKHR::UPDATE,
            false => vk::BuildAccelerationStructureModeKHR::BUILD,
        };
        let mut info = build_info(vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, self.flags.raw(), &geometry)
            .mode(mode)
            .dst_acceleration_structure(self.accel.raw)
            .scratch_data(vk::DeviceOrHostAddressKHR { device_address: self.scratch_address });
        if update {
            info = info.src_acceleration_structure(self.accel.raw);
        }
        // SAFETY: the storage and scratch live as long as self, the mesh's buffers as long as
        // the scene that holds both.
        unsafe { record_between_barriers(ctx, cmd, info, index_count / 3) };
    }
}
