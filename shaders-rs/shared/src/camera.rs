//! Primary rays: from the inverse view and projection through a point of a pixel.

use crate::layout::FrameUniform;
use glam::{UVec2, Vec2, Vec3, Vec4, Vec4Swizzles};

/// A ray with origin and (unit) direction.
#[derive(Clone, Copy)]
pub struct Ray {
    /// Where the ray starts, in world space.
    pub origin: Vec3,
    /// Where it goes: unit length for camera rays.
    pub direction: Vec3,
}

/// The ray through `pixel + offset` in an image of `size` pixels (y down, as in Vulkan);
/// `offset` in [0, 1)^2, (0.5, 0.5) being the pixel centre. A perspective camera's rays leave
/// the eye; an orthographic camera's (`frame.cone.y` 1) leave the point of the camera's plane
/// that `proj_inverse` maps the pixel to, all down the camera's -z.
pub fn primary_ray(frame: &FrameUniform, pixel: UVec2, size: UVec2, offset: Vec2) -> Ray {
    let uv = (pixel.as_vec2() + offset) / size.as_vec2();
    let ndc = uv * 2.0 - Vec2::ONE;
    if frame.cone.y != 0.0 {
        let on_plane = frame.proj_inverse * Vec4::new(ndc.x, ndc.y, 0.0, 1.0);
        let origin = (frame.view_inverse * Vec4::new(on_plane.x, on_plane.y, 0.0, 1.0)).xyz();
        let direction = (frame.view_inverse * Vec4::new(0.0, 0.0, -1.0, 0.0)).xyz();
        return Ray { origin, direction };
    }
    let origin = (frame.view_inverse * Vec4::new(0.0, 0.0, 0.0, 1.0)).xyz();
    let target = frame.proj_inverse * Vec4::new(ndc.x, ndc.y, 1.0, 1.0);
    let direction = (frame.view_inverse * target.xyz().normalize().extend(0.0)).xyz();
    Ray { origin, direction }
}

/// Offset of sample `(sx, sy)` of `m` x `m` stratified, jittered samples in a pixel: the
/// centre of the pixel when `m` is 1, else `(r1, r2)` places it inside its stratum.
pub fn sample_offset(sx: u32, sy: u32, m: u32, r1: f32, r2: f32) -> Vec2 {
    if m == 1 {
        return Vec2::splat(0.5);
    }
    Vec2::new((sx as f32 + r1) / m as f32, (sy as f32 + r2) / m as f32)
}
