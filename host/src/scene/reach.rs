//! How far rays must reach, from the scene's extent: primary rays past the scene's farthest
//! point from the camera, a directional light's shadow rays across the whole scene, and
//! primary rays' near reach a fixed fraction of their far one. Nothing is a constant in scene
//! units: a fixed far reach (1000 units, once) rendered a scene seen from farther away as
//! empty background, and a fixed near reach (0.1 units, once) rendered the same scene modelled
//! 1/100 as large as background. Also whether f32 can resolve each object where it stands: a
//! scene far from the origin can put an object within a few f32 steps.

use glam::{Mat4, Vec3, Vec4};
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

/// How many times its own size (half its world box's diagonal) an object's translation may
/// reach before the driver's f32 world-to-object transform, which works at the magnitude of the
/// translation, costs more than about 1e-6 of the object's size: past it the scene has far
/// instances (`features::FAR_INSTANCES`), and the intersection stages compute their own
/// object-space ray (docs/numerics.md).
pub const FAR_FACTOR: f32 = 16.0;

/// Whether any object lies far from the world origin for its size (see [`FAR_FACTOR`]), its
/// own bounds being `object_bounds` and its transform `transforms`.
pub fn far_instances(object_bounds: &[Aabb], transforms: &[Mat4]) -> bool {
    let boxes = world_boxes(object_bounds, transforms);
    boxes.iter().zip(transforms).any(|(b, t)| {
        let size = 0.5 * (b.max - b.min).length();
        t.w_axis.truncate().abs().max_element() > FAR_FACTOR * size
    })
}

/// How many times its own size (as [`FAR_FACTOR`] measures it) a probe's ray may start from an
/// object before the scene has far instances: the stages bring a ray that starts farther than
/// this many of its primitive's bounds near it (`twinray_shared::transform::FAR_BOUNDS`), and
/// would not bring it anywhere without the feature.
pub const START_FACTOR: f32 = twinray_shared::transform::FAR_BOUNDS;

/// Whether any object lies far for its size (see [`START_FACTOR`]) from where rays start, a box
/// around every ray origin (`starts`, in the coordinates of `transforms`): a ray from there is
/// transformed at the magnitude of its distance, however near the world origin the object
/// stands, and the stages bring it near first only where the scene has far instances. The
/// distance is to the box's farthest corner, so that no start in it is farther.
pub fn far_from(object_bounds: &[Aabb], transforms: &[Mat4], starts: &Aabb) -> bool {
    world_boxes(object_bounds, transforms).iter().any(|b| {
        let (centre, size) = (0.5 * (b.min + b.max), 0.5 * (b.max - b.min).length());
        let farthest = (starts.min - centre).abs().max((starts.max - centre).abs()).length();
        farthest > START_FACTOR * size
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

/// Primary rays' t_min as a fraction of their t_max. A camera ray needs no gap to leave a
/// surface (it starts at the eye); the near reach only keeps t_min above 0, where an eye lying
/// on a surface would hit it at t = 0 in one set and not the other. 2^-20 of the far reach is
/// a few f32 steps of t there, and nearer than any object f32 resolves from the eye.
pub const NEAR_FRACTION: f64 = 1.0 / (1u64 << 20) as f64;

/// `FrameUniform::reach` for a camera at `eye` and objects in `boxes`: x, primary rays' t_max
/// (the farthest corner of the scene from the eye); y, directional shadow rays' (the scene's
/// diagonal); z, primary rays' t_min ([`NEAR_FRACTION`] of x). Computed in f64, with 1% slack.
/// A scene with no extent (no objects, or all at the eye) reaches 1 unit: any reach is right.
pub fn reach(boxes: &[Aabb], eye: Vec3) -> Vec4 {
    let Some(scene) = enclose(boxes.iter().flat_map(|b| [b.min, b.max])) else {
        return from_far(1.0, 1.0);
    };
    let eye = eye.as_dvec3();
    let farthest = corners(&scene).iter().map(|c| (c.as_dvec3() - eye).length()).fold(0.0, f64::max);
    let across = (scene.max.as_dvec3() - scene.min.as_dvec3()).length();
    let positive = |d: f64| if d > 0.0 && d.is_finite() { d * SLACK } else { 1.0 };
    from_far(positive(farthest), positive(across))
}

/// The reach of a scene whose primary rays reach `far` and directional shadow rays `across`.
fn from_far(far: f64, across: f64) -> Vec4 {
    Vec4::new(far as f32, across as f32, (far * NEAR_FRACTION) as f32, 0.0)
}

/// The first object whose box comes nearer the eye than primary rays' near reach `near`, with
/// its distance: the part of it that near is not seen. None for a scene seen from outside, and
/// boxes holding the eye are not judged (the eye inside a box need not be inside the object).
pub fn within_near(boxes: &[Aabb], eye: Vec3, near: f32) -> Option<(usize, f64)> {
    let eye = eye.as_dvec3();
    boxes.iter().enumerate().find_map(|(i, b)| {
        let nearest = eye.clamp(b.min.as_dvec3(), b.max.as_dvec3());
        let d = (nearest - eye).length();
        (d > 0.0 && d < f64::from(near)).then_some((i, d))
    })
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
        assert!(r.z > 0.0 && f64::from(r.z) == (f64::from(r.x) * NEAR_FRACTION) as f32 as f64, "{r}");
        let empty = reach(&[], Vec3::ZERO);
        assert!(empty.z > 0.0 && empty.z < empty.x, "an empty scene still has a valid ray interval: {empty}");
    }

    #[test]
    fn every_reach_scales_with_the_scene() {
        let eye = Vec3::new(0.3, 4.5, 11.0);
        let boxes = [cube(Vec3::new(0.5, 0.0, -1.0), 2.0), cube(Vec3::ZERO, 20.0)];
        let at = |s: f32| {
            let scaled: Vec<Aabb> = boxes.iter().map(|b| Aabb { min: b.min * s, max: b.max * s }).collect();
            reach(&scaled, eye * s)
        };
        for k in -4..=4 {
            let s = 10f32.powi(k);
            let (r, one) = (at(s), at(1.0));
            for (a, b) in [(r.x, one.x), (r.y, one.y), (r.z, one.z)] {
                assert!((a / s / b - 1.0).abs() < 1e-5, "10^{k}: {r} against {one}");
            }
        }
    }

    #[test]
    fn names_an_object_nearer_the_eye_than_the_near_reach() {
        let boxes = [cube(Vec3::new(0.0, 0.0, -50.0), 1.0), cube(Vec3::new(0.0, 0.0, 1e-7), 1e-8)];
        let near = reach(&boxes, Vec3::ZERO).z;
        assert_eq!(within_near(&boxes, Vec3::ZERO, near).map(|(i, _)| i), Some(1));
        assert_eq!(within_near(&boxes[..1], Vec3::ZERO, near), None, "a scene seen from outside");
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
    fn an_object_is_far_from_rays_that_start_three_times_its_size_away() {
        let unit = [cube(Vec3::ZERO, 1.0)];
        let still = [Mat4::IDENTITY];
        let size = 3.0f32.sqrt();
        let at = |x: f32| Aabb { min: Vec3::new(x, 0.0, 0.0), max: Vec3::new(x, 0.0, 0.0) };
        assert!(!far_from(&unit, &still, &at(START_FACTOR * size * 0.99)));
        assert!(far_from(&unit, &still, &at(-START_FACTOR * size * 1.01)), "whichever side");
        // A box of starts is judged by its farthest corner: one near start does not hide a far one.
        let spread = Aabb { min: Vec3::new(-1.0, 0.0, 0.0), max: Vec3::new(1.0e3, 0.0, 0.0) };
        assert!(far_from(&unit, &still, &spread));
        // Scaled up, the same start is near again; and the translation counts.
        assert!(!far_from(&unit, &[Mat4::from_scale(Vec3::splat(2.0))], &at(START_FACTOR * size * 1.01)));
        let moved = [Mat4::from_translation(Vec3::new(1.0e3, 0.0, 0.0))];
        assert!(!far_from(&unit, &moved, &at(1.0e3)), "rays starting at the object");
        assert!(!far_from(&[], &[], &at(1.0e6)));
    }

    #[test]
    fn world_boxes_follow_the_transform() {
        let m = Mat4::from_translation(Vec3::new(10.0, 0.0, 0.0)) * Mat4::from_scale(Vec3::splat(2.0));
        let b = world_boxes(&[cube(Vec3::ZERO, 1.0)], &[m]);
        assert_eq!(b[0].min, Vec3::new(8.0, -2.0, -2.0));
        assert_eq!(b[0].max, Vec3::new(12.0, 2.0, 2.0));
    }

    #[test]
    fn an_object_is_far_where_its_translation_passes_sixteen_times_its_size() {
        let unit = [cube(Vec3::ZERO, 1.0)];
        let at = |x: f32, scale: f32| {
            [Mat4::from_translation(Vec3::new(x, 0.0, 0.0)) * Mat4::from_scale(Vec3::splat(scale))]
        };
        // Half the diagonal of a cube of side 2: sqrt(3).
        let size = 3.0f32.sqrt();
        assert!(!far_instances(&unit, &at(FAR_FACTOR * size * 0.99, 1.0)));
        assert!(far_instances(&unit, &at(FAR_FACTOR * size * 1.01, 1.0)));
        // Scaled up, the same place is near again.
        assert!(!far_instances(&unit, &at(FAR_FACTOR * size * 1.01, 2.0)));
        assert!(far_instances(&unit, &at(1.0e4, 1.0)));
        assert!(!far_instances(&[], &[]));
    }
}
