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
    /// A scene that cannot be read, parsed or checked.
    #[error("scene {path}: {message}")]
    Scene { path: String, message: String },
    /// A probe case that cannot be read, parsed or checked (its inline scene's faults too).
    #[error("probe case {path}: {message}")]
    Case { path: String, message: String },
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
    /// A module declares a capability or extension the device does not have enabled (the text
    /// names the module, what it declares and the device): refused before any pipeline is
    /// made. The CLI exits with code 2; suites skip the case or scene and say why.
    #[error("{0}")]
    DeviceLacks(String),
    /// A file operation failed.
    #[error("{what} {}: {source}", path.display())]
    Io {
        what: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A set's stages left outputs unwritten, or wrote them non-finite, where a measurement
    /// needs them (a reference, a bench row): the text names the set and the counts.
    #[error("{0}")]
    Output(String),
    /// GPU work did not finish within the deadline (`--gpu-timeout`): a stage may never
    /// return. The device is abandoned: nothing made from it is destroyed, since the GPU (or
    /// a lavapipe thread) is still running the work; end the process, with `libc::_exit` on
    /// lavapipe, whose exit handlers would wait for that thread.
    #[error(
        "{doing} did not finish in {seconds} s: a stage may never return (if it is only slow, raise --gpu-timeout)"
    )]
    GpuTimeout { doing: String, seconds: String },
    /// The device was lost while doing GPU work (a fault in a stage, or the driver's watchdog).
    #[error(
        "{doing}: the device was lost (VK_ERROR_DEVICE_LOST): a stage faulted or ran past the driver's own time limit"
    )]
    DeviceLost { doing: String },
    /// An error while doing something named in words ("creating the pipeline of SET (its
    /// modules)").
    /// (Its cause is in its text, and not a `source`, so that a chain printed with `{:#}`
    /// says it once.)
    #[error("{doing}: {cause}")]
    While { doing: String, cause: Box<Error> },
    /// An image (OpenEXR) could not be encoded.
    #[error("writing {}: {source}", path.display())]
    Image {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
}

impl Error {
    /// True when the error comes from what the user asked for, not from the machine.
    pub fn is_input(&self) -> bool {
        match self {
            Error::While { cause, .. } => cause.is_input(),
            other => {
                matches!(other, Error::Input(_) | Error::Scene { .. } | Error::Case { .. } | Error::DeviceLacks(_))
            }
        }
    }

    /// True when GPU work did not finish: past the deadline, or the device was lost. The
    /// process should end now (see [`Error::GpuTimeout`]).
    pub fn is_stalled(&self) -> bool {
        match self {
            Error::While { cause, .. } => cause.is_stalled(),
            other => matches!(other, Error::GpuTimeout { .. } | Error::DeviceLost { .. }),
        }
    }

    /// True when a module needs what the device lacks ([`Error::DeviceLacks`]): a suite skips
    /// the case or scene rather than stopping.
    pub fn device_lacks(&self) -> bool {
        match self {
            Error::While { cause, .. } => cause.device_lacks(),
            other => matches!(other, Error::DeviceLacks(_)),
        }
    }

    /// This error, said to have happened while doing `doing`.
    pub fn during(self, doing: impl Into<String>) -> Error {
        Error::While { doing: doing.into(), cause: Box::new(self) }
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
