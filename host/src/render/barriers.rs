//! Layouts of the output image through a render, and the barriers between them.

use crate::vk::commands::TRACING_STAGES;
use crate::vk::image::COLOR_RANGE;
use ash::vk;

/// The output image's layout before the first trace, and while traces write it.
pub(crate) const UNUSED_IMAGE: (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags) =
    (vk::ImageLayout::UNDEFINED, vk::PipelineStageFlags::TOP_OF_PIPE, vk::AccessFlags::empty());
pub(crate) const STORAGE_IMAGE: (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags) =
    (vk::ImageLayout::GENERAL, TRACING_STAGES, vk::AccessFlags::SHADER_WRITE);

/// The output image's layout while it is copied out.
pub(crate) const COPY_SOURCE: (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags) =
    (vk::ImageLayout::TRANSFER_SRC_OPTIMAL, vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_READ);

/// Layout transition of the output image, with the access and stage masks of both sides.
pub(crate) fn transition(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    image: vk::Image,
    (old_layout, src_stage, src_access): (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags),
    (new_layout, dst_stage, dst_access): (vk::ImageLayout, vk::PipelineStageFlags, vk::AccessFlags),
) {
    let barrier = [vk::ImageMemoryBarrier::default()
        .src_access_mask(src_access)
        .dst_access_mask(dst_access)
        .old_layout(old_layout)
        .new_layout(new_layout)
        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .image(image)
        .subresource_range(COLOR_RANGE)];
    // SAFETY: cmd is recording; the image is alive.
    unsafe { device.cmd_pipeline_barrier(cmd, src_stage, dst_stage, vk::DependencyFlags::empty(), &[], &[], &barrier) };
}
