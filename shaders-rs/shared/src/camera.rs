//! Primary rays: from the inverse view and projection through the centre of a pixel.

use crate::layout::CameraUniform;
use glam::{UVec2, Vec2, Vec3, Vec4Swizzles};

/// A ray with origin and (unit) direction.
#[derive(Clone, Copy)]
pub struct Ray {
    pub origin: Vec3,
    pub direction: Vec3,
}

/// The ray through the centre of `pixel` in an image of `size` pixels (y down, as in Vulkan).
pub fn primary_ray(camera: &CameraUniform, pixel: UVec2, size: UVec2) -> Ray {
    let uv = (pixel.as_vec2() + Vec2::splat(0.5)) / size.as_vec2();
    let ndc = uv * 2.0 - Vec2::ONE;
    let origin = (camera.view_inverse * glam::Vec4::new(0.0, 0.0, 0.0, 1.0)).xyz();
    let target = camera.proj_inverse * glam::Vec4::new(ndc.x, ndc.y, 1.0, 1.0);
    let direction = (camera.view_inverse * target.xyz().normalize().extend(0.0)).xyz();
    Ray { origin, direction }
}
