//! The storage image the ray generation stage writes (rgba32f: the mean radiance of each pixel,
//! in f32, so that references and error measures are not quantised), with its memory and view.

use super::context::Context;
use crate::error::{Error, Result, VkContext};
use ash::vk;
use gpu_allocator::vulkan::Allocation;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Format of the output image: linear RGBA f32, as ray generation writes it.
pub const FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;
/// Bytes per pixel of [`FORMAT`].
pub const PIXEL_BYTES: u64 = 16;

/// A 2D storage image with its view and memory.
pub struct StorageImage {
    ctx: Arc<Context>,
    pub raw: vk::Image,
    pub view: vk::ImageView,
    pub extent: vk::Extent2D,
    allocation: Option<Allocation>,
}

impl StorageImage {
    /// A device-local rgba32f image usable as a storage image, a copy source and a copy
    /// target (the host fills it with a sentinel before each set writes it).
    pub fn new(ctx: &Arc<Context>, width: u32, height: u32) -> Result<Self> {
        // SAFETY: plain query on a live physical device.
        let format_props = unsafe { ctx.instance.get_physical_device_format_properties(ctx.physical, FORMAT) };
        if !format_props.optimal_tiling_features.contains(vk::FormatFeatureFlags::STORAGE_IMAGE) {
            return Err(Error::Unsupported("the device cannot use R32G32B32A32_SFLOAT as a storage image".into()));
        }
        let extent = vk::Extent2D { width, height };
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(FORMAT)
            .extent(extent.into())
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: valid create info; destroyed in Drop.
        let raw = unsafe { ctx.device.create_image(&info, None) }.call("vkCreateImage")?;
        let mut image = StorageImage { ctx: ctx.clone(), raw, view: vk::ImageView::null(), extent, allocation: None };
        // SAFETY: raw is a live image of this device.
        let requirements = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let what = format!("output image {width}x{height}");
        let allocation = ctx.allocate(&what, requirements, MemoryLocation::GpuOnly, false)?;
        // SAFETY: the allocation was made for this image's requirements.
        unsafe { ctx.device.bind_image_memory(raw, allocation.memory(), allocation.offset()) }
            .call("vkBindImageMemory")?;
        image.allocation = Some(allocation);
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(vk::ImageViewType::TYPE_2D)
            .format(FORMAT)
            .subresource_range(COLOR_RANGE);
        // SAFETY: the image is bound to memory.
        image.view = unsafe { ctx.device.create_image_view(&view_info, None) }.call("vkCreateImageView")?;
        Ok(image)
    }
}

impl StorageImage {
    /// A copy between the whole image and a tightly packed buffer.
    pub fn whole_copy(&self) -> vk::BufferImageCopy {
        vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: vk::ImageAspectFlags::COLOR,
                mip_level: 0,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(self.extent.into())
    }
}

/// The one colour mip level and layer of an image.
pub const COLOR_RANGE: vk::ImageSubresourceRange = vk::ImageSubresourceRange {
    aspect_mask: vk::ImageAspectFlags::COLOR,
    base_mip_level: 0,
    level_count: 1,
    base_array_layer: 0,
    layer_count: 1,
};

impl Drop for StorageImage {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return; // the GPU may still use it: see Context::abandon
        }
        // SAFETY: the GPU work using this image has completed; a null view is ignored.
        unsafe {
            self.ctx.device.destroy_image_view(self.view, None);
            self.ctx.device.destroy_image(self.raw, None);
        }
        if let Some(allocation) = self.allocation.take() {
            self.ctx.free(allocation);
        }
    }
}
