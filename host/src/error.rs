//! The one error type of the twinray library: each variant names the Vulkan call or the input
//! that failed.

use ash::vk;
use std::path::PathBuf;

pub type Result<T, E = Error> = std::result::Result<T, E>;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input from the user: a scene, a shader-set spec, a size. The CLI exits with code 2.
    #[error("{0}")]
    Input(String),
    #[error("scene {path}: {message}")]
    Scene { path: String, message: String },
    #[error("could not load the Vulkan loader (libvulkan.so.1): {0}")]
    Loader(#[from] ash::LoadingError),
    #[error("{call} failed: {result}")]
    Vulkan { call: &'static str, result: vk::Result },
    #[error("memory allocation for {what} failed: {source}")]
    Allocation {
        what: String,
        #[source]
        source: gpu_allocator::AllocationError,
    },
    #[error("no suitable Vulkan device: {0}")]
    NoDevice(String),
    #[error("the validation layer reported {count} error(s); first: {first}")]
    Validation { count: usize, first: String },
    #[error("{0}")]
    Unsupported(String),
    #[error("{what} {}: {source}", path.display())]
    Io {
        what: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("writing PNG {}: {source}", path.display())]
    Png {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
}

impl Error {
    /// True when the error comes from what the user asked for, not from the machine.
    pub fn is_input(&self) -> bool {
        matches!(self, Error::Input(_) | Error::Scene { .. })
    }
}

/// Attaches the name of the Vulkan call to a `vk::Result` error.
pub trait VkContext<T> {
    fn call(self, call: &'static str) -> Result<T>;
}

impl<T> VkContext<T> for std::result::Result<T, vk::Result> {
    fn call(self, call: &'static str) -> Result<T> {
        self.map_err(|result| Error::Vulkan { call, result })
    }
}
