//! The descriptor pool and the one descriptor set of a render.

use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use std::sync::Arc;

/// What each binding points at.
pub struct DescriptorTargets {
    pub tlas: vk::AccelerationStructureKHR,
    pub image_view: vk::ImageView,
    /// (binding, buffer, type) of each buffer binding.
    pub buffers: Vec<(u32, vk::Buffer, vk::DescriptorType)>,
    pub tlas_binding: u32,
    pub image_binding: u32,
    /// The binding of an array of combined image samplers, and the (view, sampler) of each of
    /// its elements (in shader-read layout).
    pub textures: (u32, Vec<(vk::ImageView, vk::Sampler)>),
}

/// A descriptor set of its own pool.
pub struct DescriptorSet {
    ctx: Arc<Context>,
    pool: vk::DescriptorPool,
    pub raw: vk::DescriptorSet,
}

impl DescriptorSet {
    /// A set of `layout` writing `targets` (pool sized by `pool_sizes`).
    pub fn new(
        ctx: &Arc<Context>,
        layout: vk::DescriptorSetLayout,
        pool_sizes: &[vk::DescriptorPoolSize],
        targets: &DescriptorTargets,
    ) -> Result<Self> {
        let info = vk::DescriptorPoolCreateInfo::default().max_sets(1).pool_sizes(pool_sizes);
        // SAFETY: valid create info; destroyed (with its set) in Drop.
        let pool = unsafe { ctx.device.create_descriptor_pool(&info, None) }.call("vkCreateDescriptorPool")?;
        let mut set = DescriptorSet { ctx: ctx.clone(), pool, raw: vk::DescriptorSet::null() };
        let layouts = [layout];
        let alloc = vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&layouts);
        // SAFETY: the pool has room for one set of this layout.
        set.raw = unsafe { ctx.device.allocate_descriptor_sets(&alloc) }.call("vkAllocateDescriptorSets")?[0];
        set.write(targets);
        Ok(set)
    }

    fn write(&self, t: &DescriptorTargets) {
        let structures = [t.tlas];
        let mut tlas_info =
            vk::WriteDescriptorSetAccelerationStructureKHR::default().acceleration_structures(&structures);
        let image_info =
            [vk::DescriptorImageInfo::default().image_view(t.image_view).image_layout(vk::ImageLayout::GENERAL)];
        let buffer_infos: Vec<_> = t
            .buffers
            .iter()
            .map(|&(_, buffer, _)| [vk::DescriptorBufferInfo::default().buffer(buffer).range(vk::WHOLE_SIZE)])
            .collect();
        let mut writes = vec![
            vk::WriteDescriptorSet::default()
                .dst_set(self.raw)
                .dst_binding(t.tlas_binding)
                .descriptor_type(vk::DescriptorType::ACCELERATION_STRUCTURE_KHR)
                .descriptor_count(1)
                .push_next(&mut tlas_info),
            vk::WriteDescriptorSet::default()
                .dst_set(self.raw)
                .dst_binding(t.image_binding)
                .descriptor_type(vk::DescriptorType::STORAGE_IMAGE)
                .image_info(&image_info),
        ];
        let (texture_binding, textures) = &t.textures;
        let texture_info: Vec<_> = textures
            .iter()
            .map(|&(view, sampler)| {
                vk::DescriptorImageInfo::default()
                    .image_view(view)
                    .sampler(sampler)
                    .image_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
            })
            .collect();
        if !texture_info.is_empty() {
            writes.push(
                vk::WriteDescriptorSet::default()
                    .dst_set(self.raw)
                    .dst_binding(*texture_binding)
                    .descriptor_type(vk::DescriptorType::COMBINED_IMAGE_SAMPLER)
                    .image_info(&texture_info),
            );
        }
        for (&(binding, _, ty), info) in t.buffers.iter().zip(&buffer_infos) {
            writes.push(
                vk::WriteDescriptorSet::default()
                    .dst_set(self.raw)
                    .dst_binding(binding)
                    .descriptor_type(ty)
                    .buffer_info(info),
            );
        }
        // SAFETY: every handle written is alive; the set is not in use yet.
        unsafe { self.ctx.device.update_descriptor_sets(&writes, &[]) };
    }
}

impl Drop for DescriptorSet {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return; // the GPU may still use it: see Context::abandon
        }
        // SAFETY: no pending work uses the set; destroying the pool frees it.
        unsafe { self.ctx.device.destroy_descriptor_pool(self.pool, None) };
    }
}
