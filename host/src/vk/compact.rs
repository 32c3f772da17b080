//! Compacting a bottom-level acceleration structure: after its build, the driver writes the
//! size it could be compacted to into a query; a structure of that size is made and the built
//! one copied into it (`COPY_MODE_COMPACT`), and the built one freed. The copy holds the same
//! hierarchy, so traces see the same structure in less memory.

use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

/// A query pool of one compacted-size query.
pub struct CompactedSize {
    ctx: Arc<Context>,
    pool: vk::QueryPool,
}

impl CompactedSize {
    pub fn new(ctx: &Arc<Context>) -> Result<Self> {
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR)
            .query_count(1);
        // SAFETY: valid create info; destroyed in Drop.
        let pool = unsafe { ctx.device.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
        Ok(CompactedSize { ctx: ctx.clone(), pool })
    }

    /// Resets the query, before the build it measures (in the same command buffer).
    pub fn reset(&self, cmd: vk::CommandBuffer) {
        // SAFETY: cmd is recording; the pool is live.
        unsafe { self.ctx.device.cmd_reset_query_pool(cmd, self.pool, 0, 1) };
    }

    /// Writes the compacted size of `accel`, built with ALLOW_COMPACTION, after a barrier that
    /// makes its build visible.
    pub fn write(&self, cmd: vk::CommandBuffer, accel: vk::AccelerationStructureKHR) {
        // SAFETY: cmd is recording; accel is built before this in the same command buffer.
        unsafe {
            self.ctx.accel.cmd_write_acceleration_structures_properties(
                cmd,
                &[accel],
                vk::QueryType::ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR,
                self.pool,
                0,
            )
        };
    }

    /// The size written, once the command buffer that wrote it has completed.
    pub fn read(&self) -> Result<u64> {
        let mut size = [0u64];
        // SAFETY: the query was written by completed work; one u64 result.
        unsafe {
            self.ctx.device.get_query_pool_results(
                self.pool,
                0,
                &mut size,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .call("vkGetQueryPoolResults")?;
        Ok(size[0])
    }
}

impl Drop for CompactedSize {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return;
        }
        // SAFETY: no submitted work uses the pool any more.
        unsafe { self.ctx.device.destroy_query_pool(self.pool, None) };
    }
}

/// Records the compacting copy of `from` into `to`, which has the compacted size.
pub fn record_copy(
    ctx: &Context,
    cmd: vk::CommandBuffer,
    from: vk::AccelerationStructureKHR,
    to: vk::AccelerationStructureKHR,
) {
    let info = vk::CopyAccelerationStructureInfoKHR::default()
        .src(from)
        .dst(to)
        .mode(vk::CopyAccelerationStructureModeKHR::COMPACT);
    // SAFETY: cmd is recording; both structures live until the submission completes.
    unsafe { ctx.accel.cmd_copy_acceleration_structure(cmd, &info) };
}
