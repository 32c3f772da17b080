//! Light sampling: for a shading point, where a light (sample) is, how much it delivers before
//! visibility, and how far a shadow ray must reach.

use crate::bindings::{LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_RECT};
use crate::layout::Light;
use crate::random::random;
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

/// The sample ray generation takes of light number `l` (`light`) for shadow sample `(i, j)` of
/// its `n` x `n`, for primary sample `sample` of pixel `pixel` with the frame's `seed`, at
/// `point`: rect lights jittered by the random numbers of dimensions `2 + 2 * (l * 64 + j * n +
/// i)` and the next (0 and 1 jitter the pixel), `stratified` (one per cell) or independent
/// (cell (0, 0) stretched over the whole light); other lights take no random numbers. This is
/// what `twinray explain` remakes a pixel's shadow rays with on the CPU. The stages' shading
/// loop (trace.rs, trace.glsl) writes the same arithmetic out: calling this from the Rust loop
/// changed its ray generation module's code (21320 to 21848 bytes), which the timing tables
/// measured, so it stays apart; explain's test checks that both add up to the image's pixels.
pub fn sample_of(
    light: &Light,
    (l, i, j, n): (u32, u32, u32, u32),
    stratified: bool,
    (seed, pixel, sample): (u32, u32, u32),
    point: Vec3,
    across: f32,
) -> LightSample {
    let dimension = 2 + 2 * (l * 64 + j * n + i);
    let (r1, r2) = if light.kind == LIGHT_RECT {
        (random(seed, pixel, sample, dimension), random(seed, pixel, sample, dimension + 1))
    } else {
        (0.0, 0.0)
    };
    let nf = n as f32;
    let (si, sj, r1, r2) = if stratified { (i, j, r1, r2) } else { (0, 0, r1 * nf, r2 * nf) };
    self::sample(light, point, (si, sj), (r1, r2), across)
}

/// Shadow samples per side of `light`: rect lights use their own count, the others one.
pub fn samples_per_side(light: &Light) -> u32 {
    if light.kind == LIGHT_DIRECTIONAL || light.kind == LIGHT_POINT {
        1
    } else {
        light.samples
    }
}
