//! The ray flags every stage traces primary rays with, shared by `trace_ray` (trace.rs,
//! probe.rs) and ray queries (query.rs), so the two paths cannot drift apart.

use spirv_std::ray_tracing::RayFlags;

/// `bindings::PRIMARY_RAY_FLAGS` as ray flags (GLSL reads the same constant from its layout).
pub const PRIMARY_RAY_FLAGS: RayFlags = RayFlags::from_bits_truncate(twinray_shared::bindings::PRIMARY_RAY_FLAGS);
