//! twinray's shared GPU contract: buffer layouts, binding numbers and the math both the Rust
//! shaders and the host (tests, CPU reference) use. `no_std` on SPIR-V, `std` on the CPU.
#![cfg_attr(target_arch = "spirv", no_std)]
#![warn(missing_docs)]

pub mod bindings;
pub mod camera;
pub mod contract;
#[cfg(not(target_arch = "spirv"))]
pub mod custom;
pub mod exact;
pub mod features;
pub mod layout;
pub mod lighting;
pub mod offset;
pub mod random;
pub mod shading;
pub mod shapes;
pub mod surface;
pub mod texture;
pub mod transform;

#[cfg(not(target_arch = "spirv"))]
pub mod catalog;
#[cfg(not(target_arch = "spirv"))]
pub mod glsl;
#[cfg(not(target_arch = "spirv"))]
pub mod interface;
#[cfg(not(target_arch = "spirv"))]
pub mod module_check;
#[cfg(not(target_arch = "spirv"))]
pub mod spirv_info;

pub use glam;
