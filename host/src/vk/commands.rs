//! Recording a command buffer, submitting it and waiting for it: the only way twinray submits.

use super::context::Context;
use crate::error::{Error, Result, VkContext};
use crate::util::{activity, watchdog};
use ash::vk;
use std::sync::Arc;

/// A command pool with one primary command buffer and a fence.
pub struct OneShot {
    ctx: Arc<Context>,
    pool: vk::CommandPool,
    pub cmd: vk::CommandBuffer,
    fence: vk::Fence,
}

impl OneShot {
    /// A command pool and a fence on the context's queue.
    pub fn new(ctx: &Arc<Context>) -> Result<Self> {
        // The one command buffer is re-recorded for each run(): it must be individually resettable.
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        // SAFETY: valid create info; destroyed in Drop (with its command buffer).
        let pool = unsafe { ctx.device.create_command_pool(&pool_info, None) }.call("vkCreateCommandPool")?;
        let mut one = OneShot { ctx: ctx.clone(), pool, cmd: vk::CommandBuffer::null(), fence: vk::Fence::null() };
        let alloc = vk::CommandBufferAllocateInfo::default().command_pool(pool).command_buffer_count(1);
        // SAFETY: the pool is live.
        one.cmd = unsafe { ctx.device.allocate_command_buffers(&alloc) }.call("vkAllocateCommandBuffers")?[0];
        // SAFETY: valid create info; destroyed in Drop.
        one.fence = unsafe { ctx.device.create_fence(&vk::FenceCreateInfo::default(), None) }.call("vkCreateFence")?;
        Ok(one)
    }

    /// Records with `record`, submits, waits (one unit of work: see [`OneShot::run_units`]),
    /// and fails on any validation error it caused.
    pub fn run(&self, record: impl FnOnce(&ash::Device, vk::CommandBuffer) -> Result<()>) -> Result<()> {
        self.run_units(1, record)
    }

    /// As [`OneShot::run`], for a submission of `units` units of work (traces, builds), each
    /// of which may take the context's GPU timeout: past `units` times it, the work is given up
    /// with [`Error::GpuTimeout`] naming what this thread is doing (`util::activity`), and the
    /// context is abandoned. A lost device ends the same way with [`Error::DeviceLost`].
    pub fn run_units(
        &self,
        units: u32,
        record: impl FnOnce(&ash::Device, vk::CommandBuffer) -> Result<()>,
    ) -> Result<()> {
        let device = &self.ctx.device;
        let begin = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
        // SAFETY: the command buffer is not in use (every run waits for its fence).
        unsafe { device.begin_command_buffer(self.cmd, &begin) }.call("vkBeginCommandBuffer")?;
        record(device, self.cmd)?;
        // SAFETY: recording started above.
        unsafe { device.end_command_buffer(self.cmd) }.call("vkEndCommandBuffer")?;
        let cmds = [self.cmd];
        let submit = [vk::SubmitInfo::default().command_buffers(&cmds)];
        let limit = self.ctx.gpu_timeout().saturating_mul(units.max(1));
        let nanos = u64::try_from(limit.as_nanos()).unwrap_or(u64::MAX);
        // SAFETY: the buffer is recorded; the fence is unsignalled; waiting keeps resources
        // alive, and a wait that gives up abandons the context, so that nothing is destroyed.
        let waited = unsafe {
            device.reset_fences(&[self.fence]).call("vkResetFences")?;
            device
                .queue_submit(self.ctx.queue, &submit, self.fence)
                .and_then(|()| device.wait_for_fences(&[self.fence], true, nanos))
        };
        let outcome = ended(waited, limit);
        if outcome.as_ref().is_err_and(Error::is_stalled) {
            self.ctx.abandon();
        }
        outcome?;
        self.ctx.check_validation()
    }
}

/// What a submission whose wait ended with `waited` (under a deadline of `limit`) comes to:
/// a timeout or a lost device names what this thread was doing.
fn ended(waited: std::result::Result<(), vk::Result>, limit: std::time::Duration) -> Result<()> {
    match waited {
        Ok(()) => Ok(()),
        Err(vk::Result::TIMEOUT) => {
            Err(Error::GpuTimeout { doing: activity::describe(), seconds: watchdog::seconds(limit) })
        }
        Err(vk::Result::ERROR_DEVICE_LOST) => Err(Error::DeviceLost { doing: activity::describe() }),
        Err(result) => Err(Error::Vulkan { call: "vkQueueSubmit/vkWaitForFences", result }),
    }
}

impl Drop for OneShot {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return; // the GPU may still use it: see Context::abandon
        }
        // SAFETY: run() waits for completion, so the command buffer is idle.
        unsafe {
            self.ctx.device.destroy_fence(self.fence, None);
            self.ctx.device.destroy_command_pool(self.pool, None);
        }
    }
}

/// The stages that trace rays: the ray tracing shaders, and the compute renderer's shader, which
/// traces with ray queries. Barriers around traces and builds name both.
pub const TRACING_STAGES: vk::PipelineStageFlags = vk::PipelineStageFlags::from_raw(
    vk::PipelineStageFlags::RAY_TRACING_SHADER_KHR.as_raw() | vk::PipelineStageFlags::COMPUTE_SHADER.as_raw(),
);

/// A global memory barrier between two pipeline stages.
pub fn memory_barrier(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    (src_stage, src_access): (vk::PipelineStageFlags, vk::AccessFlags),
    (dst_stage, dst_access): (vk::PipelineStageFlags, vk::AccessFlags),
) {
    let barrier = [vk::MemoryBarrier::default().src_access_mask(src_access).dst_access_mask(dst_access)];
    // SAFETY: cmd is recording.
    unsafe { device.cmd_pipeline_barrier(cmd, src_stage, dst_stage, vk::DependencyFlags::empty(), &barrier, &[], &[]) };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A device lost (NVIDIA's answer to some faults) and a timeout both end the work with what
    /// was being done; neither is an anonymous Vulkan error.
    #[test]
    fn a_lost_device_and_a_timeout_name_the_work() {
        let _doing = activity::doing("the trace of rust");
        let limit = std::time::Duration::from_secs(3);
        let lost = ended(Err(vk::Result::ERROR_DEVICE_LOST), limit).unwrap_err();
        assert!(lost.is_stalled() && lost.to_string().starts_with("the trace of rust: the device was lost"), "{lost}");
        let late = ended(Err(vk::Result::TIMEOUT), limit).unwrap_err();
        assert!(late.is_stalled() && late.to_string().contains("the trace of rust did not finish in 3 s"), "{late}");
        let other = ended(Err(vk::Result::ERROR_OUT_OF_DEVICE_MEMORY), limit).unwrap_err();
        assert!(!other.is_stalled());
        assert!(ended(Ok(()), limit).is_ok());
    }
}
