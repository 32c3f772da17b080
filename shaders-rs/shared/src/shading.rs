//! Shading of the sphere scene: Lambert under one directional light, grey background.

use glam::Vec3;

/// Direction towards the light before normalisation; both sets normalise it the same way.
pub const LIGHT_DIRECTION: Vec3 = Vec3::ONE;
/// Grey returned by the miss stage.
pub const MISS_GREY: f32 = 0.3;

/// Lambert shading of `albedo` at a point with unit normal `normal`.
pub fn lambert(albedo: Vec3, normal: Vec3) -> Vec3 {
    albedo * normal.dot(LIGHT_DIRECTION.normalize()).max(0.0)
}
