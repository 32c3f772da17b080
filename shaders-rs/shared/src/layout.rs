//! Every struct that crosses the CPU/GPU line, defined once. `#[repr(C)]`, built from scalars,
//! `Vec4` and `Mat4` only, so std140/std430 and Rust agree; sizes are asserted at compile time.

use glam::{Mat4, Vec4};

/// Uniform buffer at [`crate::bindings::BINDING_CAMERA`].
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct CameraUniform {
    /// Camera-to-world transform.
    pub view_inverse: Mat4,
    /// Clip-to-camera transform.
    pub proj_inverse: Mat4,
}
const _: () = assert!(core::mem::size_of::<CameraUniform>() == 128);

/// One element of the storage buffer at [`crate::bindings::BINDING_SPHERES`].
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Sphere {
    /// xyz: centre, w: radius.
    pub center_radius: Vec4,
    /// rgb: albedo, w: unused (1).
    pub color: Vec4,
}
const _: () = assert!(core::mem::size_of::<Sphere>() == 32);

/// The payload of primary rays, written by the closest-hit and miss stages.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct RayPayload {
    /// rgb: shaded colour, w: 1.
    pub color: Vec4,
    /// Primitive id that was hit, or [`crate::bindings::NO_HIT`].
    pub primitive: u32,
}
