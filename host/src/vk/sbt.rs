//! The shader binding table, laid out from the device's own handle size and alignments
//! (lavapipe: 32/16/32, NVIDIA Hopper: 32/32/64 — never hard-coded).

use super::buffer::Buffer;
use super::context::Context;
use crate::error::{Result, VkContext};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Where each region (ray generation, miss, hit, callable) lies, in bytes from an aligned base.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SbtLayout {
    pub handle_size: u64,
    /// Distance between records: the handle size rounded up to the handle alignment.
    pub stride: u64,
    /// Offset of each region's first record; each is a multiple of the base alignment.
    pub offsets: [u64; 4],
    pub counts: [u64; 4],
    pub base_alignment: u64,
    pub total_size: u64,
}

impl SbtLayout {
    /// `counts` are the number of records in the raygen, miss, hit and callable regions.
    pub fn new(handle_size: u32, handle_alignment: u32, base_alignment: u32, counts: [u32; 4]) -> Self {
        let handle_size = u64::from(handle_size);
        let stride = handle_size.next_multiple_of(u64::from(handle_alignment.max(1)));
        let base = u64::from(base_alignment.max(1));
        let counts = counts.map(u64::from);
        let mut offsets = [0; 4];
        let mut end = 0u64;
        for (offset, count) in offsets.iter_mut().zip(counts) {
            *offset = end.next_multiple_of(base);
            end = *offset + count * stride;
        }
        SbtLayout { handle_size, stride, offsets, counts, base_alignment: base, total_size: end }
    }

    /// The region of `index` (0 raygen, 1 miss, 2 hit, 3 callable) at `base` (already aligned);
    /// an empty region is all zeros, as Vulkan asks of an unused one.
    pub fn region(&self, base: vk::DeviceAddress, index: usize) -> vk::StridedDeviceAddressRegionKHR {
        if self.counts[index] == 0 {
            return vk::StridedDeviceAddressRegionKHR::default();
        }
        // The ray generation region must have size equal to its stride (one record).
        let size = if index == 0 { self.stride } else { self.counts[index] * self.stride };
        vk::StridedDeviceAddressRegionKHR::default()
            .device_address(base + self.offsets[index])
            .stride(self.stride)
            .size(size)
    }
}

/// The SBT buffer and the four regions to pass to vkCmdTraceRaysKHR.
pub struct ShaderBindingTable {
    _buffer: Buffer,
    pub raygen: vk::StridedDeviceAddressRegionKHR,
    pub miss: vk::StridedDeviceAddressRegionKHR,
    pub hit: vk::StridedDeviceAddressRegionKHR,
    pub callable: vk::StridedDeviceAddressRegionKHR,
}

impl ShaderBindingTable {
    /// Copies the handles of `pipeline`'s `group_count` groups into the records of each region
    /// (raygen, miss, hit, callable): `records[r]` lists the group of each record of region r
    /// (a group may have several records).
    pub fn new(ctx: &Arc<Context>, pipeline: vk::Pipeline, group_count: u32, records: &[Vec<u32>; 4]) -> Result<Self> {
        let info = &ctx.info;
        let layout = SbtLayout::new(
            info.shader_group_handle_size,
            info.shader_group_handle_alignment,
            info.shader_group_base_alignment,
            records.each_ref().map(|r| r.len() as u32),
        );
        if let Some(bad) = records.iter().flatten().find(|&&g| g >= group_count) {
            return Err(crate::error::Error::Unsupported(format!("SBT record for group {bad} of {group_count}")));
        }
        let handle_size = layout.handle_size as usize;
        // SAFETY: the pipeline is live and has `group_count` groups.
        let handles = unsafe {
            ctx.rt.get_ray_tracing_shader_group_handles(pipeline, 0, group_count, group_count as usize * handle_size)
        }
        .call("vkGetRayTracingShaderGroupHandlesKHR")?;
        let mut bytes = vec![0u8; (layout.total_size + layout.base_alignment) as usize];
        let usage = vk::BufferUsageFlags::SHADER_BINDING_TABLE_KHR | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
        // Allocate first to learn the address, then place the regions from the first aligned byte.
        let mut buffer = Buffer::new(ctx, "sbt", bytes.len() as u64, usage, MemoryLocation::CpuToGpu)?;
        let address = buffer.device_address();
        let base = address.next_multiple_of(layout.base_alignment);
        let pad = (base - address) as usize;
        for (region, groups) in records.iter().enumerate() {
            for (i, &group) in groups.iter().enumerate() {
                let at = pad + layout.offsets[region] as usize + i * layout.stride as usize;
                let group = group as usize;
                let src = &handles[group * handle_size..(group + 1) * handle_size];
                bytes[at..at + handle_size].copy_from_slice(src);
            }
        }
        buffer.write(&bytes)?;
        Ok(ShaderBindingTable {
            raygen: layout.region(base, 0),
            miss: layout.region(base, 1),
            hit: layout.region(base, 2),
            callable: layout.region(base, 3),
            _buffer: buffer,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::SbtLayout;

    #[test]
    fn lavapipe_layout() {
        let l = SbtLayout::new(32, 16, 32, [1, 1, 1, 0]);
        assert_eq!((l.stride, l.offsets, l.total_size), (32, [0, 32, 64, 96], 96));
        let empty = l.region(1 << 20, 3);
        assert_eq!((empty.device_address, empty.stride, empty.size), (0, 0, 0), "no callables: all zeros");
    }

    #[test]
    fn nvidia_hopper_layout() {
        let l = SbtLayout::new(32, 32, 64, [1, 1, 1, 4]);
        assert_eq!((l.stride, l.offsets, l.total_size), (32, [0, 64, 128, 192], 320));
        assert_eq!(l.region(1 << 20, 3).size, 4 * 32);
    }

    #[test]
    fn handle_smaller_than_alignment_pads_records() {
        let l = SbtLayout::new(32, 64, 64, [1, 2, 3, 0]);
        assert_eq!((l.stride, l.offsets, l.total_size), (64, [0, 64, 192, 384], 384));
    }
}
