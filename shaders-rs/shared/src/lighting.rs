//! Light sampling: for a shading point, where a light (sample) is, how much it delivers before
//! visibility, and how far a shadow ray must reach.

use crate::bindings::{LIGHT_DIRECTIONAL, LIGHT_POINT};
use crate::layout::Light;
use glam::{Vec3, Vec4Swizzles};
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

/// One sample of a light as seen from a point.
#[derive(Clone, Copy)]
pub struct LightSample {
    /// Unit direction from the point towards the sample.
    pub direction: Vec3,
    /// How far a shadow ray may go before it passes the light.
    pub distance: f32,
    /// Irradiance arriving along `direction` on a surface facing it (before the cosine at the
    /// receiver and before visibility).
    pub irradiance: Vec3,
}

/// Sample `(i, j)` of a light at `point`, with `(r1, r2)` in [0, 1) jittering the sample
/// inside its stratum (rect lights only; one sample for the others). A directional light's
/// shadow ray reaches `across` (`FrameUniform::reach.y`: across the whole scene).
pub fn sample(light: &Light, point: Vec3, (i, j): (u32, u32), (r1, r2): (f32, f32), across: f32) -> LightSample {
    let radiance = light.radiance.xyz();
    if light.kind == LIGHT_DIRECTIONAL {
        return LightSample { direction: light.position.xyz(), distance: across, irradiance: radiance };
    }
    let target = if light.kind == LIGHT_POINT {
        light.position.xyz()
    } else {
        let n = light.samples as f32;
        let s = (i as f32 + r1) / n - 0.5;
        let t = (j as f32 + r2) / n - 0.5;
        light.position.xyz() + light.u.xyz() * s + light.v.xyz() * t
    };
    let to_light = target - point;
    let distance_sq = to_light.dot(to_light);
    let distance = distance_sq.sqrt();
    let direction = to_light / distance;
    let irradiance = if light.kind == LIGHT_POINT {
        radiance / distance_sq
    } else {
        // Area light, two-sided: radiance x cosine at the light x solid angle of one stratum.
        let area_normal = light.u.xyz().cross(light.v.xyz());
        let cos_light = area_normal.dot(direction).abs() / area_normal.length();
        let n = light.samples as f32;
        radiance * (cos_light * area_normal.length() / (n * n * distance_sq))
    };
    LightSample { direction, distance, irradiance }
}

/// Shadow samples per side of `light`: rect lights use their own count, the others one.
pub fn samples_per_side(light: &Light) -> u32 {
    if light.kind == LIGHT_DIRECTIONAL || light.kind == LIGHT_POINT {
        1
    } else {
        light.samples
    }
}
