//! Compacting a bottom-level acceleration structure: after its build, the driver writes the
//! size it could be compacted to into a query; a structure of that size is made and the built
//! one copied into it (`COPY_MODE_COMPACT`), and the built one freed. The copy holds the same
//! hierarchy, so traces see the same structure in less memory.

use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

/// A query pool of compacted-size queries, one per structure of a batch.
pub struct CompactedSizes {
    ctx: Arc<Context>,
    pool: vk::QueryPool,
    count: u32,
}

impl CompactedSizes {
    pub fn new(ctx: &Arc<Context>, count: u32) -> Result<Self> {
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR)
            .query_count(count.max(1));
        // SAFETY: valid create info; destroyed in Drop.
        let pool = unsafe { ctx.device.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
        Ok(CompactedSizes { ctx: ctx.clone(), pool, count: count.max(1) })
    }

    /// Resets the queries, before the builds they measure (in the same command buffer).
    pub fn reset(&self, cmd: vk::CommandBuffer) {
        // SAFETY: cmd is recording; the pool is live.
        unsafe { self.ctx.device.cmd_reset_query_pool(cmd, self.pool, 0, self.count) };
    }

    /// Writes the compacted size of each of `accels` (at most the pool's count), built with
    /// ALLOW_COMPACTION, after a barrier that makes their builds visible.
    pub fn write(&self, cmd: vk::CommandBuffer, accels: &[vk::AccelerationStructureKHR]) {
        // SAFETY: cmd is recording; the structures are built before this in the same command
        // buffer, and no more of them than the pool has queries.
        unsafe {
            self.ctx.accel.cmd_write_acceleration_structures_properties(
                cmd,
                &accels[..accels.len().min(self.count as usize)],
                vk::QueryType::ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR,
                self.pool,
                0,
            )
        };
    }

    /// The first `n` sizes written, once the command buffer that wrote them has completed.
    pub fn read(&self, n: usize) -> Result<Vec<u64>> {
        let mut sizes = vec![0u64; n.min(self.count as usize)];
        if sizes.is_empty() {
            return Ok(sizes);
        }
        // SAFETY: the queries were written by completed work; one u64 result each.
        unsafe {
            self.ctx.device.get_query_pool_results(
                self.pool,
                0,
                &mut sizes,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .call("vkGetQueryPoolResults")?;
        Ok(sizes)
    }
}

impl Drop for CompactedSizes {
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
