//! A Vulkan buffer and its memory, released together on drop.

use super::context::Context;
use crate::error::{Error, Result, VkContext};
use ash::vk;
use gpu_allocator::vulkan::Allocation;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// A buffer with its memory, freed when dropped.
pub struct Buffer {
    ctx: Arc<Context>,
    pub raw: vk::Buffer,
    pub size: u64,
    allocation: Option<Allocation>,
}

impl Buffer {
    /// An uninitialised buffer of `size` bytes (at least 1) at `location`.
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Self> {
        let size = size.max(1);
        let info = vk::BufferCreateInfo::default().size(size).usage(usage).sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: valid create info; the buffer is destroyed in Drop.
        let raw = unsafe { ctx.device.create_buffer(&info, None) }.call("vkCreateBuffer")?;
        let mut buffer = Buffer { ctx: ctx.clone(), raw, size, allocation: None };
        // SAFETY: raw is a live buffer of this device.
        let requirements = unsafe { ctx.device.get_buffer_memory_requirements(raw) };
        let allocation = ctx.allocate(&format!("buffer {name} ({size} bytes)"), requirements, location, true)?;
        // SAFETY: the allocation was made for this buffer's requirements.
        unsafe { ctx.device.bind_buffer_memory(raw, allocation.memory(), allocation.offset()) }
            .call("vkBindBufferMemory")?;
        buffer.allocation = Some(allocation);
        Ok(buffer)
    }

    /// A host-visible buffer holding `data`.
    pub fn with_data(ctx: &Arc<Context>, name: &str, data: &[u8], usage: vk::BufferUsageFlags) -> Result<Self> {
        let mut buffer = Self::new(ctx, name, data.len() as u64, usage, MemoryLocation::CpuToGpu)?;
        buffer.write(data)?;
        Ok(buffer)
    }

    /// Copies `data` to the start of a host-visible buffer large enough for it.
    pub fn write(&mut self, data: &[u8]) -> Result<()> {
        self.write_parts(std::iter::once(data))
    }

    /// Copies `data` into a host-visible buffer at byte `offset`; the GPU must not be using
    /// that range.
    pub fn write_at(&mut self, offset: usize, data: &[u8]) -> Result<()> {
        let mapped = self.mapped_mut()?;
        let capacity = mapped.len();
        let target = mapped.get_mut(offset..offset + data.len()).ok_or_else(|| {
            Error::Unsupported(format!("writing {} bytes at {offset} into a buffer of {capacity}", data.len()))
        })?;
        target.copy_from_slice(data);
        Ok(())
    }

    /// Copies `parts` end to end from the start of a host-visible buffer large enough for
    /// them all.
    pub fn write_parts<'a>(&mut self, parts: impl Iterator<Item = &'a [u8]>) -> Result<()> {
        let mapped = self.mapped_mut()?;
        let capacity = mapped.len();
        let mut at = 0;
        for data in parts {
            let target = mapped.get_mut(at..at + data.len()).ok_or_else(|| {
                Error::Unsupported(format!("writing {} bytes at {at} into a buffer of {capacity}", data.len()))
            })?;
            target.copy_from_slice(data);
            at += data.len();
        }
        Ok(())
    }

    /// The mapped bytes of a host-visible buffer.
    pub fn mapped(&self) -> Result<&[u8]> {
        self.allocation
            .as_ref()
            .and_then(|a| a.mapped_slice())
            .ok_or_else(|| Error::Unsupported("buffer memory is not host-visible".into()))
    }

    fn mapped_mut(&mut self) -> Result<&mut [u8]> {
        self.allocation
            .as_mut()
            .and_then(|a| a.mapped_slice_mut())
            .ok_or_else(|| Error::Unsupported("buffer memory is not host-visible".into()))
    }

    /// The buffer's device address; it must have been made with SHADER_DEVICE_ADDRESS.
    pub fn device_address(&self) -> vk::DeviceAddress {
        let info = vk::BufferDeviceAddressInfo::default().buffer(self.raw);
        // SAFETY: the buffer is live and was created with SHADER_DEVICE_ADDRESS usage.
        unsafe { self.ctx.device.get_buffer_device_address(&info) }
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        if self.ctx.abandoned() {
            return; // the GPU may still use it: see Context::abandon
        }
        // SAFETY: the GPU work using this buffer has completed (every submit waits on a fence).
        unsafe { self.ctx.device.destroy_buffer(self.raw, None) };
        if let Some(allocation) = self.allocation.take() {
            self.ctx.free(allocation);
        }
    }
}
