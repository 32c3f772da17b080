//! How far rays must reach, from the scene's extent: primary rays past the scene's farthest
//! point from the camera, a directional light's shadow rays across the whole scene. A fixed
//! reach (1000 units, once) rendered a scene seen from farther away as empty background and
//! let occluders beyond it cast no shadow. Also whether f32 can resolve each object where it
//! stands: a scene far from the origin can put an object within a few f32 steps.

use glam::{Mat4, Vec3, Vec4};
use twinray_shared::bindings::T_MIN;
use twinray_shared::shapes::spec::Aabb;

/// Slack on every reach: t of a hit is rounded in f32, and the shadow ray's origin is offset
/// from the surface; 1% is far more than either.
pub const SLACK: f64 = 1.01;

/// The smallest box holding `points`; `None` for none.
pub fn enclose(points: impl IntoIterator<Item = Vec3>) -> Option<Aabb> {
    points.into_iter().fold(None, |b: Option<Aabb>, p| match b {
        None => Some(Aabb { min: p, max: p }),
        Some(b) => Some(Aabb { min: b.min.min(p), max: b.max.max(p) }),
    })
}

/// The corners of `b`.
fn corners(b: &Aabb) -> [Vec3; 8] {
    std::array::from_fn(|k| {
        Vec3::new(
            if k & 1 == 0 { b.min.x } else { b.max.x },
            if k & 2 == 0 { b.min.y } else { b.max.y },
            if k & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

/// Each object's world-space bounds under `transforms` (object order).
pub fn world_boxes(object_bounds: &[Aabb], transforms: &[Mat4]) -> Vec<Aabb> {
    object_bounds
        .iter()
        .zip(transforms)
        .filter_map(|(b, m)| enclose(corners(b).map(|c| m.transform_point3(c))))
        .collect()
}

/// `FrameUniform::reach` for a camera at `eye` and objects in `boxes`: x, primary rays' t_max
/// (the farthest corner of the scene from the eye); y, directional shadow rays' (the scene's
/// diagonal). Computed in f64, with 1% slack; never below twice `T_MIN`.
pub fn reach(boxes: &[Aabb], eye: Vec3) -> Vec4 {
    let floor = 2.0 * f64::from(T_MIN);
    let Some(scene) = enclose(boxes.iter().flat_map(|b| [b.min, b.max])) else {
        return Vec4::new(floor as f32, floor as f32, 0.0, 0.0);
    };
    let eye = eye.as_dvec3();
    let farthest = corners(&scene).iter().map(|c| (c.as_dvec3() - eye).length()).fold(0.0, f64::max);
    let across = (scene.max.as_dvec3() - scene.min.as_dvec3()).length();
    let reach = |d: f64| (d * SLACK).max(floor) as f32;
    Vec4::new(reach(farthest), reach(across), 0.0, 0.0)
}

/// Fewer f32 steps than this across an object, where it stands: f32 cannot resolve it (its
/// surface collapses onto a handful of representable points). An error.
pub const UNRESOLVED_STEPS: f64 = 8.0;
/// Fewer than this: f32 resolves it coarsely (its silhouette and t are quantised to worse than
/// a thousandth of its size). A warning.
pub const COARSE_STEPS: f64 = 1024.0;

/// How many f32 steps span object `i`'s largest side, at the largest coordinate a ray to it
/// involves (its corners, and the eye the primary rays leave from): (object, steps) of the
/// object spanned by the fewest.
pub fn coarsest(boxes: &[Aabb], eye: Vec3) -> Option<(usize, f64)> {
    boxes
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let size = (b.max - b.min).as_dvec3().max_element();
            let magnitude = corners(b).iter().map(|c| c.abs().max_element()).fold(eye.abs().max_element(), f32::max);
            (i, size / step(magnitude))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// The spacing of f32 values at magnitude `m` (at least the smallest normal's).
pub fn step(m: f32) -> f64 {
    let m = m.abs().max(f32::MIN_POSITIVE);
    f64::from(f32::from_bits(m.to_bits() + 1) - m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(center: Vec3, half: f32) -> Aabb {
        Aabb { min: center - Vec3::splat(half), max: center + Vec3::splat(half) }
    }

    #[test]
    fn reaches_past_the_farthest_corner_and_across_the_scene() {
        let boxes = [cube(Vec3::ZERO, 100.0)];
        let r = reach(&boxes, Vec3::new(0.0, 0.0, 5000.0));
        let far = (5100.0f64 * 5100.0 + 2.0 * 100.0 * 100.0).sqrt();
        assert!(f64::from(r.x) >= far && f64::from(r.x) <= far * 1.02, "{r}");
        let across = (3.0f64 * 200.0 * 200.0).sqrt();
        assert!(f64::from(r.y) >= across && f64::from(r.y) <= across * 1.02, "{r}");
        assert_eq!(reach(&[], Vec3::ZERO).x, 2.0 * T_MIN, "an empty scene still has a valid ray interval");
    }

    #[test]
    fn counts_the_f32_steps_across_an_object_where_it_stands() {
        let eye = Vec3::new(0.0, 0.0, 10.0);
        let near = cube(Vec3::ZERO, 1.0);
        let far = cube(Vec3::new(1.0e6, 0.0, 0.0), 1.0);
        let (i, steps) = coarsest(&[near, far], eye).unwrap();
        assert_eq!(i, 1);
        assert_eq!(steps, 2.0 / 0.0625, "f32 steps by 1/16 at 1e6");
        assert!(step(1.0) == f64::from(f32::EPSILON));
    }

    #[test]
    fn world_boxes_follow_the_transform() {
        let m = Mat4::from_translation(Vec3::new(10.0, 0.0, 0.0)) * Mat4::from_scale(Vec3::splat(2.0));
        let b = world_boxes(&[cube(Vec3::ZERO, 1.0)], &[m]);
        assert_eq!(b[0].min, Vec3::new(8.0, -2.0, -2.0));
        assert_eq!(b[0].max, Vec3::new(12.0, 2.0, 2.0));
    }
}
