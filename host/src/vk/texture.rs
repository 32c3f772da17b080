//! Sampled textures: an RGBA8 image with its mip levels uploaded through a staging buffer,
//! its view, and the sampler it is read through (the pair a combined image sampler binds).

use super::buffer::Buffer;
use super::commands::OneShot;
use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use gpu_allocator::vulkan::Allocation;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// A texture in shader-read layout, with its view and sampler.
pub struct Texture {
    ctx: Arc<Context>,
    image: vk::Image,
    pub view: vk::ImageView,
    pub sampler: vk::Sampler,
    allocation: Option<Allocation>,
}

impl Texture {
    /// A texture of `format` (8-bit RGBA, sRGB or not) whose levels, level 0 first, are
    /// `levels` (width, height, tightly packed texels), read through a sampler of `sampler`.
    pub fn new(
        ctx: &Arc<Context>,
        one_shot: &OneShot,
        name: &str,
        format: vk::Format,
        levels: &[(u32, u32, &[u8])],
        sampler: &vk::SamplerCreateInfo,
    ) -> Result<Texture> {
        let (width, height, _) = levels[0];
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(format)
            .extent(vk::Extent3D { width, height, depth: 1 })
            .mip_levels(levels.len() as u32)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: valid create info; destroyed in Drop.
        let image = unsafe { ctx.device.create_image(&info, None) }.call("vkCreateImage")?;
        let mut texture = Texture {
            ctx: ctx.clone(),
            image,
            view: vk::ImageView::null(),
            sampler: vk::Sampler::null(),
            allocation: None,
        };
        // SAFETY: a live image of this device.
        let requirements = unsafe { ctx.device.get_image_memory_requirements(image) };
        let allocation = ctx.allocate(&format!("texture {name}"), requirements, MemoryLocation::GpuOnly, false)?;
        // SAFETY: the allocation was made for this image's requirements.
        unsafe { ctx.device.bind_image_memory(image, allocation.memory(), allocation.offset()) }
            .call("vkBindImageMemory")?;
        texture.allocation = Some(allocation);
        let range = vk::ImageSubresourceRange {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            base_mip_level: 0,
            level_count: levels.len() as u32,
            base_array_layer: 0,
            layer_count: 1,
        };
        texture.upload(one_shot, levels, range)?;
        let view_info = vk::ImageViewCreateInfo::default()
            .image(image)
            .view_type(vk::ImageViewType::TYPE_2D)
            .format(format)
            .subresource_range(range);
        // SAFETY: the image is bound to memory.
        texture.view = unsafe { ctx.device.create_image_view(&view_info, None) }.call("vkCreateImageView")?;
        // SAFETY: valid create info.
        texture.sampler = unsafe { ctx.device.create_sampler(sampler, None) }.call("vkCreateSampler")?;
        Ok(texture)
    }

    /// Copies every level from one staging buffer, leaving the image ready for shaders to read.
    fn upload(&self, one_shot: &OneShot, levels: &[(u32, u32, &[u8])], range: vk::ImageSubresourceRange) -> Result<()> {
        let bytes: Vec<u8> = levels.iter().flat_map(|(_, _, t)| t.iter().copied()).collect();
        let staging = Buffer::with_data(&self.ctx, "texture staging", &bytes, vk::BufferUsageFlags::TRANSFER_SRC)?;
        let mut offset = 0u64;
        let regions: Vec<vk::BufferImageCopy> = levels
            .iter()
            .enumerate()
            .map(|(level, &(width, height, texels))| {
                let region = vk::BufferImageCopy::default()
                    .buffer_offset(offset)
                    .image_subresource(vk::ImageSubresourceLayers {
                        aspect_mask: vk::ImageAspectFlags::COLOR,
                        mip_level: level as u32,
                        base_array_layer: 0,
                        layer_count: 1,
                    })
                    .image_extent(vk::Extent3D { width, height, depth: 1 });
                offset += texels.len() as u64;
                region
            })
            .collect();
        let barrier = |from, to, src_access, dst_access| {
            vk::ImageMemoryBarrier::default()
                .old_layout(from)
                .new_layout(to)
                .src_access_mask(src_access)
                .dst_access_mask(dst_access)
                .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                .image(self.image)
                .subresource_range(range)
        };
        one_shot.run(|device, cmd| {
            let to_copy = barrier(
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                vk::AccessFlags::empty(),
                vk::AccessFlags::TRANSFER_WRITE,
            );
            let to_read = barrier(
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                vk::AccessFlags::TRANSFER_WRITE,
                vk::AccessFlags::SHADER_READ,
            );
            // SAFETY: cmd is recording; the image and staging buffer live until the wait ends.
            unsafe {
                device.cmd_pipeline_barrier(
                    cmd,
                    vk::PipelineStageFlags::TOP_OF_PIPE,
                    vk::PipelineStageFlags::TRANSFER,
                    vk::DependencyFlags::empty(),
                    &[],
                    &[],
                    &[to_copy],
                );
                device.cmd_copy_buffer_to_image(
                    cmd,
                    staging.raw,
                    self.image,
                    vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                    &regions,
                );
                device.cmd_pipeline_barrier(
                    cmd,
                    vk::PipelineStageFlags::TRANSFER,
                    vk::PipelineStageFlags::ALL_COMMANDS,
                    vk::DependencyFlags::empty(),
                    &[],
                    &[],
                    &[to_read],
                );
            }
            Ok(())
        })
    }
}

impl Drop for Texture {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return; // the GPU may still use it: see Context::abandon
        }
        // SAFETY: the GPU work reading this texture has completed; null handles are ignored.
        unsafe {
            self.ctx.device.destroy_sampler(self.sampler, None);
            self.ctx.device.destroy_image_view(self.view, None);
            self.ctx.device.destroy_image(self.image, None);
        }
        if let Some(allocation) = self.allocation.take() {
            self.ctx.free(allocation);
        }
    }
}
