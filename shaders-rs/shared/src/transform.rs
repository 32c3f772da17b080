//! The object-space ray of an instance, computed by the stages from the world ray and the
//! instance's transform rather than read from `ObjectRayOriginKHR`: the driver's transform
//! applies the whole world-to-object matrix in f32, `M⁻¹ o + t'` with `t' = -M⁻¹ T`, and for an
//! instance far from the world origin both terms are large and cancel, so the object-space
//! origin carries an error of the order of the world coordinates' ulp (2.5e-4 relative t error
//! on lavapipe for a shape 1e4 away seen from 10 units, docs/numerics.md). Taking the
//! instance's translation off the world origin first, `M⁻¹ (o - T)`, rounds `o - T` at the
//! magnitude of the ray's distance from the instance, not of the world coordinates: the bound
//! of pbrt's transformed-point error analysis (Pharr, Jakob and Humphreys, *Physically Based
//! Rendering*, 3rd ed., §3.9.4), γ₃ |M⁻¹| |o - T|, with |o - T| in place of |o| + |T|.
//! The GLSL twin is `object_ray` in shaders-glsl/transform.glsl.

use crate::features::{Features, FAR_INSTANCES};
use glam::{Mat3, Vec3};

/// The object-space origin and direction of the world ray (`origin`, `direction`) for an
/// instance whose object-to-world translation is `translation` and whose world-to-object
/// transform has the 3x3 part `inverse`. The direction has no translation to lose: it is the
/// driver's own product. The ray parameter t is the same in both spaces.
#[inline(always)]
pub fn object_ray(origin: Vec3, direction: Vec3, translation: Vec3, inverse: Mat3) -> (Vec3, Vec3) {
    (inverse * (origin - translation), inverse * direction)
}

/// The object-space ray an intersection stage uses: its own (`object_ray` of the world ray)
/// where the scene has far instances (`features::FAR_INSTANCES`, a specialisation constant,
/// so the other branch is compiled out), else the `driver`'s, which costs nothing and is as
/// good near the origin.
#[inline(always)]
pub fn stage_ray(
    features: Features,
    driver: (Vec3, Vec3),
    (origin, direction): (Vec3, Vec3),
    translation: Vec3,
    inverse: Mat3,
) -> (Vec3, Vec3) {
    if features.has::<FAR_INSTANCES>() {
        object_ray(origin, direction, translation, inverse)
    } else {
        driver
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    type M = [[f64; 3]; 3];

    /// Rows of the rotation by `angle` about the unit `axis` (Rodrigues).
    fn turn(axis: [f64; 3], angle: f64) -> M {
        let (s, c) = angle.sin_cos();
        let [x, y, z] = axis;
        let k = 1.0 - c;
        [
            [c + x * x * k, x * y * k - z * s, x * z * k + y * s],
            [y * x * k + z * s, c + y * y * k, y * z * k - x * s],
            [z * x * k - y * s, z * y * k + x * s, c + z * z * k],
        ]
    }

    fn apply(m: &M, v: [f64; 3]) -> [f64; 3] {
        m.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
    }

    fn transpose(m: &M) -> M {
        [0, 1, 2].map(|i| [m[0][i], m[1][i], m[2][i]])
    }

    fn f32s(v: [f64; 3]) -> Vec3 {
        Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
    }

    fn distance(a: Vec3, b: [f64; 3]) -> f64 {
        let d = [f64::from(a.x) - b[0], f64::from(a.y) - b[1], f64::from(a.z) - b[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    }

    /// A unit shape's instance turned about an oblique axis and moved 3e4 from the origin; rays
    /// from 5 units away. The stages' form keeps the object-space origin within a few ulp of
    /// its size; applying the whole matrix at once (the driver's form) loses about the world
    /// coordinates' ulp.
    #[test]
    fn the_translation_taken_off_first_keeps_the_origin_at_its_own_scale() {
        let n = (1.0f64 + 4.0 + 9.0).sqrt();
        let rot = turn([1.0 / n, 2.0 / n, 3.0 / n], 0.7);
        let inv = transpose(&rot);
        let t = [30000.0, -20000.5, 12345.25];
        let inverse = Mat3::from_cols(f32s(inv.map(|r| r[0])), f32s(inv.map(|r| r[1])), f32s(inv.map(|r| r[2])));
        let t_inv = apply(&inv, t).map(|x| -x);
        let (mut stages, mut whole) = (0.0f64, 0.0f64);
        for k in 0..64 {
            let local = [(k as f64 * 0.37).sin(), (k as f64 * 0.11).cos(), -5.0];
            let moved = apply(&rot, local);
            let world = f32s([moved[0] + t[0], moved[1] + t[1], moved[2] + t[2]]);
            // The truth: the f32 world origin, exactly transformed.
            let w = [f64::from(world.x), f64::from(world.y), f64::from(world.z)];
            let truth = apply(&inv, [w[0] - t[0], w[1] - t[1], w[2] - t[2]]);
            let (o, _) = object_ray(world, Vec3::Z, f32s(t), inverse);
            stages = stages.max(distance(o, truth));
            let driver = inverse * world + f32s(t_inv);
            whole = whole.max(distance(driver, truth));
        }
        assert!(stages < 4e-6, "the stages' form is {stages:e} off");
        assert!(whole > 1e-4, "the whole matrix at once was {whole:e} off: the case is not hard");
    }
}
