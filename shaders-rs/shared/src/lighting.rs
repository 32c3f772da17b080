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
/// shadow ray reaches `across` (`FrameUniform::reach.y`: across the whole scene). A point
/// light's range and cone dim it only with `cones` (the feature `LIGHT_CONES`: a scene without
/// them pays nothing for the falloff, which is 1 there).
pub fn sample(
    light: &Light,
    point: Vec3,
    (i, j): (u32, u32),
    (r1, r2): (f32, f32),
    across: f32,
    cones: bool,
) -> LightSample {
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
        // Times the falloff first: a plain point light (falloff 1) gives radiance / d^2 exactly.
        let dimmed = if cones { radiance * falloff(light, direction, distance) } else { radiance };
        dimmed / distance_sq
    } else {
        // Area light, two-sided: radiance x cosine at the light x solid angle of one stratum.
        let area_normal = light.u.xyz().cross(light.v.xyz());
        let cos_light = area_normal.dot(direction).abs() / area_normal.length();
        let n = light.samples as f32;
        radiance * (cos_light * area_normal.length() / (n * n * distance_sq))
    };
    LightSample { direction, distance, irradiance }
}

/// What a point light's range and cone leave of its inverse-square light at `distance` along
/// `direction` (from the point to the light), as glTF's KHR_lights_punctual and its sample
/// viewer have it: the window `clamp(1 - (distance / range)^4, 0, 1)` (`position.w` holds
/// 1 / range, 0 for none) times the cone's `clamp(cos * v.x + v.y, 0, 1)^2`, `cos` the cosine
/// between the light's axis `u` and the way to the point (`v.x` = 1 / (cos inner - cos outer),
/// `v.y` = -cos outer * `v.x`; 0 and 1 for a light without a cone). 1 for a plain point light.
// `max` then `min`, not `clamp`: f32::clamp asserts its bounds, a panic path on the GPU.
#[allow(clippy::manual_clamp)]
pub fn falloff(light: &Light, direction: Vec3, distance: f32) -> f32 {
    let x = distance * light.position.w;
    let x2 = x * x;
    let window = (1.0 - x2 * x2).max(0.0).min(1.0);
    let cone = (light.u.xyz().dot(-direction) * light.v.x + light.v.y).max(0.0).min(1.0);
    window * (cone * cone)
}

/// The sample ray generation takes of light number `l` (`light`) for shadow sample `(i, j)` of
/// its `n` x `n`, for primary sample `sample` of pixel `pixel` with the frame's `seed`, at
/// `point` (its range and cone always applied: 1 where a scene has none, as the stages' sample
/// without the feature): rect lights jittered by the random numbers of dimensions `2 + 2 * (l * 64 + j * n +
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
    self::sample(light, point, (si, sj), (r1, r2), across, true)
}

/// Shadow samples per side of `light`: rect lights use their own count, the others one.
pub fn samples_per_side(light: &Light) -> u32 {
    if light.kind == LIGHT_DIRECTIONAL || light.kind == LIGHT_POINT {
        1
    } else {
        light.samples
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bindings::LIGHT_POINT;
    use glam::Vec4;

    fn point(reach: f32, axis: Vec3, cone: (f32, f32)) -> Light {
        Light {
            kind: LIGHT_POINT,
            samples: 1,
            shadows: 1,
            _pad0: 0,
            position: Vec4::new(0.0, 0.0, 0.0, reach),
            radiance: Vec4::ONE,
            u: axis.extend(0.0),
            v: Vec4::new(cone.0, cone.1, 0.0, 0.0),
        }
    }

    /// glTF-Sample-Viewer's range and spot attenuation, in f64, as it writes them.
    fn viewer(distance: f64, range: Option<f64>, cos: f64, cones: Option<(f64, f64)>) -> f64 {
        let window = range.map_or(1.0, |r| (1.0 - (distance / r).powi(4)).clamp(0.0, 1.0));
        let cone = match cones {
            None => 1.0,
            Some((inner, outer)) if cos > outer && cos < inner => ((cos - outer) / (inner - outer)).powi(2),
            Some((_, outer)) if cos > outer => 1.0,
            Some(_) => 0.0,
        };
        window * cone
    }

    #[test]
    fn falloff_is_the_sample_viewers_range_and_cone() {
        assert_eq!(falloff(&point(0.0, Vec3::ZERO, (0.0, 1.0)), Vec3::X, 123.0), 1.0, "a plain point light");
        let (inner, outer) = (20f64.to_radians().cos(), 30f64.to_radians().cos());
        let scale = 1.0 / (inner - outer);
        let light = point(1.0 / 3.0, Vec3::NEG_Y, (scale as f32, (-outer * scale) as f32));
        for degrees in [0.0f64, 10.0, 19.9, 20.1, 25.0, 29.9, 30.1, 60.0, 170.0] {
            for distance in [0.5f64, 1.5, 2.9, 3.0, 4.0] {
                // The way from a point below the light up to it, `degrees` off its axis.
                let a = degrees.to_radians();
                let up = Vec3::new(-(a.sin() as f32), a.cos() as f32, 0.0);
                let got = falloff(&light, up, distance as f32);
                let want = viewer(distance, Some(3.0), a.cos(), Some((inner, outer)));
                assert!((f64::from(got) - want).abs() < 1e-5, "{degrees} degrees at {distance}: {got} against {want}");
            }
        }
    }
}
