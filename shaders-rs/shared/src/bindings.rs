//! Descriptor bindings, shader-group order and ray constants shared by both shader sets.
//!
//! The Rust shaders must spell bindings as literals in `#[spirv(...)]` attributes; a test reads
//! the decorations back from every compiled module and checks them against these constants.

/// The only descriptor set.
pub const DESCRIPTOR_SET: u32 = 0;
/// Top-level acceleration structure.
pub const BINDING_TLAS: u32 = 0;
/// Output colour, a storage image of format rgba8.
pub const BINDING_IMAGE: u32 = 1;
/// [`crate::layout::CameraUniform`], a uniform buffer.
pub const BINDING_CAMERA: u32 = 2;
/// `[Sphere]`, a storage buffer indexed by primitive id.
pub const BINDING_SPHERES: u32 = 3;
/// `[u32]` per pixel: primitive id hit by the primary ray, or [`NO_HIT`].
pub const BINDING_HIT_IDS: u32 = 4;

/// Shader groups in pipeline order; the shader binding table follows it.
pub const GROUP_RAYGEN: u32 = 0;
pub const GROUP_MISS: u32 = 1;
pub const GROUP_SPHERE_HIT: u32 = 2;

/// Written to the hit-id buffer (and the payload) when a ray hits nothing.
pub const NO_HIT: u32 = 0xffff_ffff;
/// Primary ray interval.
pub const T_MIN: f32 = 0.1;
pub const T_MAX: f32 = 1000.0;
