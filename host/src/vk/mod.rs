//! Thin, self-releasing wrappers over the Vulkan objects twinray uses.

pub mod accel;
pub mod blas;
pub mod buffer;
pub mod commands;
pub mod compact;
pub mod context;
pub mod deferred;
pub mod descriptors;
pub mod device;
pub mod device_select;
pub mod image;
pub mod kept;
pub mod pipeline;
pub mod pipeline_cache;
pub mod refit;
pub mod sbt;
pub mod texture;
pub mod timing;
pub mod validation;
