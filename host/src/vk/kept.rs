//! Pipelines a context keeps until its device goes, found by a key their maker chose: the
//! pipeline libraries and compute pipelines of a CPU device (see `Context::keeps_libraries`). They are kept as bare
//! handles, destroyed by the context itself, because a pipeline that held the context (as every
//! other Vulkan object here does) would keep it alive from inside it.

use crate::error::Result;
use ash::vk;
use std::collections::HashMap;
use std::sync::Mutex;

/// The handles of one kept pipeline.
#[derive(Clone, Copy)]
pub struct KeptPipeline {
    pub set_layout: vk::DescriptorSetLayout,
    pub layout: vk::PipelineLayout,
    pub raw: vk::Pipeline,
}

/// Every pipeline a context keeps, by key.
#[derive(Default)]
pub struct KeptPipelines(Mutex<HashMap<u64, KeptPipeline>>);

impl KeptPipelines {
    /// The pipeline kept under `key`, made by `make` and kept unless one is (made once however
    /// many threads ask: they wait while it is made); whether `make` made it.
    pub fn get_or_make(&self, key: u64, make: impl FnOnce() -> Result<KeptPipeline>) -> Result<(KeptPipeline, bool)> {
        let mut kept = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(k) = kept.get(&key) {
            return Ok((*k, false));
        }
        let made = make()?;
        kept.insert(key, made);
        Ok((made, true))
    }

    /// How many are kept.
    pub fn len(&self) -> usize {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).len()
    }

    /// Whether none is.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Destroys every kept pipeline.
    ///
    /// # Safety
    /// `device` made them, and no pending GPU work uses them.
    pub unsafe fn destroy(&self, device: &ash::Device) {
        for (_, k) in self.0.lock().unwrap_or_else(|e| e.into_inner()).drain() {
            // SAFETY: as the caller promises; null handles are ignored.
            unsafe {
                device.destroy_pipeline(k.raw, None);
                device.destroy_pipeline_layout(k.layout, None);
                device.destroy_descriptor_set_layout(k.set_layout, None);
            }
        }
    }
}
