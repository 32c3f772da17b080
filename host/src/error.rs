//! The one error type of the twinray library: each variant names the Vulkan call or the input
//! that failed.

use ash::vk;
use std::path::PathBuf;

/// The library's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, naming the Vulkan call or the input.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input from the user: a scene, a shader-set spec, a size. The CLI exits with code 2.
    #[error("{0}")]
    Input(String),
    /// A scene or probe case that cannot be read, parsed or checked.
    #[error("scene {path}: {message}")]
    Scene { path: String, message: String },
    /// The Vulkan loader library is missing.
    #[error("could not load the Vulkan loader (libvulkan.so.1): {0}")]
    Loader(#[from] ash::LoadingError),
    /// A Vulkan call returned an error.
    #[error("{call} failed: {result}")]
    Vulkan { call: &'static str, result: vk::Result },
    /// The memory allocator could not serve a request.
    #[error("memory allocation for {what} failed: {source}")]
    Allocation {
        what: String,
        #[source]
        source: gpu_allocator::AllocationError,
    },
    /// No device offers what twinray needs (the text says what was missing).
    #[error("no suitable Vulkan device: {0}")]
    NoDevice(String),
    /// The validation layer reported errors during the work.
    #[error("the validation layer reported {count} error(s); first: {first}")]
    Validation { count: usize, first: String },
    /// Something the device or this build cannot do.
    #[error("{0}")]
    Unsupported(String),
    /// A file operation failed.
    #[error("{what} {}: {source}", path.display())]
    Io {
        what: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A PNG could not be written.
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
    /// The result, with the call's name on its error.
    fn call(self, call: &'static str) -> Result<T>;
}

impl<T> VkContext<T> for std::result::Result<T, vk::Result> {
    fn call(self, call: &'static str) -> Result<T> {
        self.map_err(|result| Error::Vulkan { call, result })
    }
}
