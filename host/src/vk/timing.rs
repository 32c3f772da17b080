//! GPU timing with timestamp queries: a pair of timestamps around each timed trace.

use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

/// A pool of timestamp queries: a begin and an end per timed trace.
pub struct Timestamps {
    ctx: Arc<Context>,
    pool: vk::QueryPool,
    pairs: u32,
}

impl Timestamps {
    /// Room for `pairs` (begin, end) timestamps; `None` if the queue cannot time.
    pub fn new(ctx: &Arc<Context>, pairs: u32) -> Result<Option<Self>> {
        if ctx.info.timestamp_valid_bits == 0 || pairs == 0 {
            return Ok(None);
        }
        let info = vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::TIMESTAMP).query_count(2 * pairs);
        // SAFETY: valid create info; destroyed in Drop.
        let pool = unsafe { ctx.device.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
        Ok(Some(Timestamps { ctx: ctx.clone(), pool, pairs }))
    }

    /// Records a reset of every query; must precede the first `begin`.
    pub fn reset(&self, cmd: vk::CommandBuffer) {
        // SAFETY: cmd is recording, outside a render pass.
        unsafe { self.ctx.device.cmd_reset_query_pool(cmd, self.pool, 0, 2 * self.pairs) };
    }

    /// Timestamp after all earlier work has finished, before pair `i`'s work starts.
    pub fn begin(&self, cmd: vk::CommandBuffer, i: u32) {
        // SAFETY: cmd is recording; the query was reset.
        unsafe { self.ctx.device.cmd_write_timestamp(cmd, vk::PipelineStageFlags::TOP_OF_PIPE, self.pool, 2 * i) };
    }

    /// Timestamp once pair `i`'s work has completed.
    pub fn end(&self, cmd: vk::CommandBuffer, i: u32) {
        // SAFETY: cmd is recording; the query was reset.
        unsafe {
            self.ctx.device.cmd_write_timestamp(cmd, vk::PipelineStageFlags::BOTTOM_OF_PIPE, self.pool, 2 * i + 1)
        };
    }

    /// Milliseconds of each pair, once the command buffer has completed.
    pub fn read_ms(&self) -> Result<Vec<f64>> {
        let mut ticks = vec![0u64; 2 * self.pairs as usize];
        // SAFETY: all queries were written by a completed submission.
        unsafe {
            self.ctx.device.get_query_pool_results(
                self.pool,
                0,
                &mut ticks,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .call("vkGetQueryPoolResults")?;
        let bits = self.ctx.info.timestamp_valid_bits;
        let mask = if bits >= 64 { u64::MAX } else { (1u64 << bits) - 1 };
        let period_ms = f64::from(self.ctx.info.timestamp_period_ns) * 1e-6;
        Ok(ticks.chunks_exact(2).map(|p| ((p[1] & mask).wrapping_sub(p[0] & mask) & mask) as f64 * period_ms).collect())
    }
}

impl Drop for Timestamps {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return; // the GPU may still use it: see Context::abandon
        }
        // SAFETY: results were read after the work completed.
        unsafe { self.ctx.device.destroy_query_pool(self.pool, None) };
    }
}
