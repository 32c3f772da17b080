//! The condition of a hit's t: how far t moves, relative to itself, when every input of the
//! problem is rounded to f32 where the problem lives, at the object. A forward error alone
//! cannot say whose fault a miss is; measured in units of this condition (error / (κ u)), it
//! can: near 1 or below, the answer is as good as rounding the problem's own inputs allows,
//! whatever the formula and wherever the GPU's coordinates are centred; far above, the formula,
//! the transform or the launch lost what the inputs held. docs/numerics.md explains the two ways
//! of writing a case's targets.
//!
//! For a ray o + t d meeting a surface with normal n, moving the surface (or the ray's origin)
//! by δ along n moves t by (n·δ) / (n·d). The problem, seen from the object it hits, is the ray's
//! start relative to the object's origin (o - T, T the instance's translation), the ray's
//! direction d, the instance's 3x3 part M and the hit's object-space point x (the surface point
//! is M x + T). Rounding each to f32 moves each component by up to u times its own magnitude,
//! u = 2^-24; summed to first order:
//!
//! κ = (Σ|n_i||o_i - T_i| + t Σ|n_i||d_i| + Σ_ij |n_i||M_ij||x_j|) / (|n·d| t).
//!
//! This is the componentwise relative condition number of t (Skeel's) with the world's origin
//! anywhere: written at scene coordinates with o and T rounded apart, the numerator's first term
//! would be Σ|n_i|(|o_i - c_i| + |T_i - c_i|) for an origin at c, and its least over every c
//! (any point between o and T) is the one above. So κ does not excuse what rounding at the
//! world's magnitude loses: an object 3e4 from the world origin seen from 5 units has the κ it
//! has at the origin, and a launch that rounds its rays at 3e4 shows a multiple in the
//! thousands. |o - T| is at most the ray's distance to the object's bounds plus the object's
//! extent about its origin, which the M x term counts too (a mesh whose vertices lie far from its
//! own origin is rounded at that distance in its own buffers: that is the problem's). The shape's
//! own parameters (radii, half extents) are left out: they move the surface by about as much as
//! M's entries do. `tests/condition.rs` checks κ against mpmath's derivatives, taken at 50 digits
//! by perturbing each input.

use super::scene::RefObject;
use glam::{DMat3, DVec3};

/// f32's unit roundoff, 2^-24: the largest relative change rounding to f32 makes (the
/// reference's own `F32_EPS`, by the name the condition multiple uses).
pub const F32_UNIT_ROUNDOFF: f64 = super::ray::F32_EPS;

/// κ of the hit at `t` of the world ray (`origin`, `direction`) on `object`, where the surface's
/// world-space normal is `normal` (any length, either side), at the object (see the module).
/// Infinite for a ray along the surface (n·d = 0), where any rounding may move t anywhere.
pub fn t_condition(object: &RefObject, origin: DVec3, direction: DVec3, t: f64, normal: DVec3) -> f64 {
    let to_world = object.object_to_world;
    let m = DMat3::from_mat4(to_world);
    let stretch = DMat3::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
    let x = object.world_to_object.transform_point3(origin + direction * t).abs();
    let start = origin - to_world.w_axis.truncate();
    let n = normal.abs();
    let moved = n.dot(start.abs()) + t * n.dot(direction.abs()) + n.dot(stretch * x);
    moved / (normal.dot(direction).abs() * t)
}

/// A hit's error in units of its condition: `relative_error` / (κ u).
pub fn condition_multiple(relative_error: f64, condition: f64) -> f64 {
    if relative_error == 0.0 {
        return 0.0;
    }
    relative_error / (condition * F32_UNIT_ROUNDOFF)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat4;

    fn object(to_world: DMat4) -> RefObject {
        RefObject {
            shapes: Vec::new(),
            world_to_object: to_world.inverse(),
            object_to_world: to_world,
            cutout: None,
            mask: 0,
            single_sided: false,
            corners: Vec::new(),
        }
    }

    /// A head-on ray at a tilted plane through the origin from 10 units: κ is 2 (the origin's
    /// and the direction's rounding, each of the size of t). The same plane met at 1 degree is
    /// worse by the cotangent of the angle; along an axis-aligned normal it would not be, as
    /// rounding moves each coordinate by its own size and the large ones then lie in the plane.
    #[test]
    fn a_grazing_ray_is_worse_conditioned_by_the_cotangent() {
        let plane = object(DMat4::IDENTITY);
        let n = DVec3::new(1.0, 1.0, 0.0).normalize();
        let head_on = t_condition(&plane, n * 10.0, -n, 10.0, n);
        assert!((head_on - 2.0).abs() < 1e-12, "{head_on}");
        let angle = 1f64.to_radians();
        let along = DVec3::new(1.0, -1.0, 0.0).normalize();
        let d = along * angle.cos() - n * angle.sin();
        let grazing = t_condition(&plane, -d * 10.0, d, 10.0, n);
        assert!((grazing / head_on - 1.0 / angle.tan()).abs() < 1e-9, "{grazing}");
        let flat = DVec3::new(angle.cos(), -angle.sin(), 0.0);
        let axis_aligned = t_condition(&plane, -flat * 10.0, flat, 10.0, DVec3::Y);
        assert!((axis_aligned - 2.0).abs() < 1e-9, "{axis_aligned}");
        assert_eq!(condition_multiple(0.0, grazing), 0.0);
        assert!((condition_multiple(head_on * F32_UNIT_ROUNDOFF, head_on) - 1.0).abs() < 1e-12);
    }

    /// Where the world's origin lies is not the problem's: an object 2.5e4 from it, seen from
    /// 10 units, is conditioned as it is at the origin, whichever way its surface faces; an
    /// error of rounding the ray at the world's magnitude is then thousands of times κ u.
    #[test]
    fn the_condition_is_the_same_wherever_the_world_origin_lies() {
        let turned =
            DMat4::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1) * DMat4::from_scale(DVec3::new(1.0, 3.0, 0.5));
        let near = object(turned);
        let shifted = DVec3::new(1e4, -2.5e4, 7e3);
        let far = object(DMat4::from_translation(shifted) * turned);
        let (o, d) = (DVec3::new(0.5, 10.0, -1.0), DVec3::new(0.05, -1.0, 0.1).normalize());
        for n in [DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(-0.3, 0.8, 0.5)] {
            let a = t_condition(&near, o, d, 9.0, n);
            let b = t_condition(&far, o + shifted, d, 9.0, n);
            assert!((a / b - 1.0).abs() < 1e-9, "{a} {b}");
            let rounded_at_the_world = F32_UNIT_ROUNDOFF * shifted.abs().max_element() / 9.0;
            assert!(
                condition_multiple(rounded_at_the_world, b) > 100.0,
                "{}",
                condition_multiple(rounded_at_the_world, b)
            );
        }
    }
}
