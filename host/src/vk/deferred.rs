//! Pipeline creation as a deferred host operation (`VK_KHR_deferred_host_operations`): the
//! driver's long host work (compiling a ray tracing pipeline or library, linking) is handed to
//! the application's threads, which join the operation until it is done.

use super::context::Context;
use crate::error::{Error, Result, VkContext};
use ash::vk;

/// Creates the ray tracing pipeline `info` describes as a deferred operation joined by up to
/// `threads` threads (at most what the driver says it can use); with 0 threads, directly.
pub fn create_pipeline(
    ctx: &Context,
    info: &vk::RayTracingPipelineCreateInfoKHR,
    threads: usize,
) -> Result<vk::Pipeline> {
    if threads == 0 {
        let infos = std::slice::from_ref(info);
        // SAFETY: everything `info` points to is alive for the call.
        let made = unsafe {
            ctx.rt.create_ray_tracing_pipelines(vk::DeferredOperationKHR::null(), ctx.pipeline_cache(), infos, None)
        };
        let made = made.map_err(|(_, result)| Error::Vulkan { call: "vkCreateRayTracingPipelinesKHR", result })?;
        return made
            .first()
            .copied()
            .ok_or(Error::Vulkan { call: "vkCreateRayTracingPipelinesKHR", result: vk::Result::ERROR_UNKNOWN });
    }
    let deferred = &ctx.deferred;
    // SAFETY: valid call; destroyed below once complete.
    let op = unsafe { deferred.create_deferred_operation(None) }.call("vkCreateDeferredOperationKHR")?;
    let mut pipeline = vk::Pipeline::null();
    // SAFETY: `info` and everything it points to, and `pipeline`, live until the operation
    // completes: it is joined to completion before this function returns.
    let started = unsafe {
        (ctx.rt.fp().create_ray_tracing_pipelines_khr)(
            ctx.rt.device(),
            op,
            ctx.pipeline_cache(),
            1,
            info,
            std::ptr::null(),
            &mut pipeline,
        )
    };
    let result = match started {
        vk::Result::OPERATION_DEFERRED_KHR => join(ctx, op, threads),
        // Done on this thread already, with this result.
        vk::Result::OPERATION_NOT_DEFERRED_KHR => vk::Result::SUCCESS,
        other => other,
    };
    // SAFETY: the operation is complete (or never started).
    unsafe { deferred.destroy_deferred_operation(op, None) };
    match result {
        vk::Result::SUCCESS => Ok(pipeline),
        result => Err(Error::Vulkan { call: "vkCreateRayTracingPipelinesKHR (deferred)", result }),
    }
}

/// Joins `op` from `threads` threads until it completes; its result.
fn join(ctx: &Context, op: vk::DeferredOperationKHR, threads: usize) -> vk::Result {
    let deferred = &ctx.deferred;
    // SAFETY: op is a live deferred operation.
    let useful = unsafe { deferred.get_deferred_operation_max_concurrency(op) } as usize;
    let threads = threads.clamp(1, useful.max(1));
    std::thread::scope(|scope| {
        for _ in 0..threads {
            // Until the operation is done, or done as far as this thread goes, or failed (the
            // result says); on THREAD_IDLE others are still working and this one may help later.
            // SAFETY: op stays live until every joiner has returned (scope end).
            scope.spawn(|| {
                while unsafe { deferred.deferred_operation_join(op) } == Err(vk::Result::THREAD_IDLE_KHR) {
                    std::thread::yield_now();
                }
            });
        }
    });
    // SAFETY: every join returned, so the operation is complete.
    match unsafe { deferred.get_deferred_operation_result(op) } {
        Ok(()) => vk::Result::SUCCESS,
        Err(e) => e,
    }
}
