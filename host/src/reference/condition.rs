//! The condition of a hit's t: how far t moves, relative to itself, when every input the GPU is
//! handed is rounded to f32. A forward error alone cannot say whose fault a miss is; measured in
//! units of this condition (error / (κ u)), it can: near 1 or below, the answer is as good as
//! rounding the problem's own inputs allows, whatever the formula; far above, the formula (or
//! the transform) lost what the inputs held. docs/numerics.md explains the two ways of writing
//! a case's targets.
//!
//! For a ray o + t d meeting a surface with normal n, moving the surface (or the ray's origin)
//! by δ along n moves t by (n·δ) / (n·d). The inputs are the world ray (o, d) and the
//! instance's object-to-world transform (the 3x3 part M and the translation T: the surface
//! point is M x + T); rounding each to f32 moves each component by up to u times its own
//! magnitude, u = 2^-24. Summed to first order:
//!
//! κ = (Σ|n_i||o_i| + t Σ|n_i||d_i| + Σ|n_i||T_i| + Σ_ij |n_i||M_ij||x_j|) / (|n·d| t),
//!
//! with x the hit's object-space point. This is the componentwise relative condition number of
//! t (Skeel's), in the scene's own coordinates: where twinray centres the GPU's copy is its own
//! choice, not the problem's. The shape's own parameters (radii, half extents) are left out: they
//! move the surface by about as much as M's entries do. `tests/condition.rs` checks κ against
//! mpmath's derivatives, taken at 50 digits by perturbing each input.

use super::scene::RefObject;
use glam::{DMat3, DVec3};

/// f32's unit roundoff, 2^-24: the largest relative change rounding to f32 makes (the
/// reference's own `F32_EPS`, by the name the condition multiple uses).
pub const F32_UNIT_ROUNDOFF: f64 = super::ray::F32_EPS;

/// κ of the hit at `t` of the world ray (`origin`, `direction`) on `object`, where the surface's
/// world-space normal is `normal` (any length, either side). Infinite for a ray along the
/// surface (n·d = 0), where any rounding may move t anywhere.
pub fn t_condition(object: &RefObject, origin: DVec3, direction: DVec3, t: f64, normal: DVec3) -> f64 {
    let to_world = object.object_to_world;
    let m = DMat3::from_mat4(to_world);
    let stretch = DMat3::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
    let x = object.world_to_object.transform_point3(origin + direction * t).abs();
    let n = normal.abs();
    let moved =
        n.dot(origin.abs()) + t * n.dot(direction.abs()) + n.dot(to_world.w_axis.truncate().abs()) + n.dot(stretch * x);
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

    /// Far from the world origin the translation's own rounding dominates: κ grows with it.
    #[test]
    fn a_far_instance_is_worse_conditioned_by_its_distance() {
        let near = object(DMat4::from_translation(DVec3::ZERO));
        let far = object(DMat4::from_translation(DVec3::new(1e4, 0.0, 0.0)));
        let (o, d) = (DVec3::new(0.0, 10.0, 0.0), -DVec3::Y);
        let shifted = DVec3::new(1e4, 0.0, 0.0);
        let a = t_condition(&near, o, d, 10.0, DVec3::Y);
        let b = t_condition(&far, o + shifted, d, 10.0, DVec3::Y);
        // The normal is along y: x coordinates do not move t, whatever their size.
        assert!((a - b).abs() < 1e-12, "{a} {b}");
        let tilted = DVec3::new(1.0, 1.0, 0.0);
        assert!(t_condition(&far, o + shifted, d, 10.0, tilted) > 500.0 * t_condition(&near, o, d, 10.0, tilted));
    }
}
