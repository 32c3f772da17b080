//! Origins of secondary rays: Wächter and Binder, "A Fast and Robust Method for Avoiding
//! Self-Intersection" (Ray Tracing Gems ch. 6). The point moves along the geometric normal by a
//! number of ULPs that scales with its magnitude, so shadow rays start off the surface at any
//! distance from the origin and can use t_min = 0 (twinray's guide, *Numerics*).

use glam::Vec3;

/// Below this magnitude a coordinate moves by a fixed step instead of by ULPs.
pub const OFFSET_ORIGIN: f32 = 1.0 / 32.0;
/// The fixed step near the origin, times the normal.
pub const OFFSET_FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// ULPs to move, times the normal.
pub const OFFSET_INT_SCALE: f32 = 256.0;
/// What `offset_hit` moves at least, times the normal, relative to the ray's reach: 256 ULPs
/// of it (2^-15).
pub const OFFSET_REACH_SCALE: f32 = 1.0 / 32768.0;

fn offset_component(p: f32, n: f32) -> f32 {
    if p.abs() < OFFSET_ORIGIN {
        return p + OFFSET_FLOAT_SCALE * n;
    }
    let of = (OFFSET_INT_SCALE * n) as i32;
    let step = if p < 0.0 { -of } else { of };
    f32::from_bits((p.to_bits() as i32).wrapping_add(step) as u32)
}

/// `p` moved off the surface along `n` (unit, pointing to the side the new ray leaves from).
pub fn offset_ray(p: Vec3, n: Vec3) -> Vec3 {
    Vec3::new(offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z))
}

/// `p`, a hit at ray parameter `t` along a unit direction, moved off the surface along `n`:
/// `offset_ray`, and at least 256 ULPs of the ray's reach (max |p_i| + t) along each axis.
/// Ray Tracing Gems assumes a hit point accurate to its own ULPs; o + t d carries the rounding
/// of the ray's origin and of t, which grows with |o| + t <= max |p_i| + t. Near the world
/// origin and far from the eye the two differ: `twinray crosscheck` found a disk 9 units from
/// the eye shadowing itself where |z| was in [1/32, 1/16), 256 ULPs of z being 1e-6 and the
/// hit point's error 2e-6 (twinray's guide, *Shading model*).
///
/// Near the origin it takes no fixed step (`OFFSET_FLOAT_SCALE`, a length in scene units), only
/// the reach's: the same scene modelled 1e4 times smaller has every point within 1/32 of the
/// origin, and a fixed step of 1/65536 there let shadow rays start past thin occluders. So the
/// offset scales with the scene, whatever its unit.
pub fn offset_hit(p: Vec3, n: Vec3, t: f32) -> Vec3 {
    let step = (p.abs().max_element() + t.abs()) * OFFSET_REACH_SCALE;
    let component = |p: f32, n: f32| {
        let ulps = if p.abs() < OFFSET_ORIGIN { p } else { offset_component(p, n) };
        let reach = p + step * n;
        if n >= 0.0 {
            ulps.max(reach)
        } else {
            ulps.min(reach)
        }
    };
    Vec3::new(component(p.x, n.x), component(p.y, n.y), component(p.z, n.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The step off the surface is the same fraction of the scene at any unit: a point near
    /// the origin, seen from 10 units, scaled by 10^k.
    #[test]
    fn offset_hit_scales_with_the_scene() {
        let (p, n, t) = (Vec3::new(0.01, -0.02, 0.005), Vec3::new(0.0, 0.6, 0.8), 10.0);
        let one = offset_hit(p, n, t) - p;
        for k in -4..=4 {
            let s = 10f32.powi(k);
            let moved = (offset_hit(p * s, n, t * s) - p * s) / s;
            assert!((moved - one).length() < 1e-3 * one.length(), "10^{k}: {moved} against {one}");
        }
    }

    #[test]
    fn moves_to_the_normal_side_at_any_magnitude() {
        for scale in [0.01f32, 1.0, 100.0, 2.0e4, 1.0e6] {
            let p = Vec3::new(scale, -scale, scale * 0.5);
            let n = Vec3::new(1.0, 1.0, -1.0).normalize();
            let q = offset_ray(p, n);
            assert!((q - p).dot(n) > 0.0, "no progress along the normal at {scale}");
            assert!((q - p).length() < scale.max(1.0) * 1e-3, "moved too far at {scale}");
        }
    }

    /// A disk facing the eye from 9 units away, hit where |z| is in [1/32, 1/16). The hit point
    /// o + t d is computed as the stages compute it (t from the ray in object space), then
    /// put up to 4 ULPs of the ray's reach below the surface: the rounding a GPU's transforms
    /// and fused multiply-adds may add (on lavapipe such points shadowed a band of the disk).
    /// From `offset_hit` every shadow ray starts on the lit side (checked in f64); from
    /// `offset_ray` some do not.
    #[test]
    fn hits_far_from_the_eye_near_the_origin_leave_their_surface() {
        let n = Vec3::new(0.0, 75f32.to_radians().cos(), 75f32.to_radians().sin());
        let center = Vec3::new(0.3, 0.5, 0.0);
        let eye = Vec3::new(0.0, 3.5, 9.0);
        let world_to_object =
            (glam::Mat4::from_translation(center) * glam::Mat4::from_rotation_x(75f32.to_radians())).inverse();
        let side = |q: Vec3| (0..3).map(|i| (f64::from(q[i]) - f64::from(center[i])) * f64::from(n[i])).sum::<f64>();
        let (mut ulps_below, mut total) = (0, 0);
        for i in 0..4000 {
            let target = center + Vec3::new(0.4 * (i % 40) as f32 / 40.0, -0.05 - 0.1 * (i / 40) as f32 / 100.0, 0.0);
            let target = target - n * (target - center).dot(n);
            let d = (target - eye).normalize();
            let o = world_to_object.transform_point3(eye);
            let t = -o.y / world_to_object.transform_vector3(d).y;
            let p = eye + d * t;
            if !(1.0 / 32.0..1.0 / 16.0).contains(&p.z.abs()) {
                continue;
            }
            let p = p - n * (4.0 * (p.abs().max_element() + t) * f32::EPSILON * (i % 5) as f32 / 4.0);
            total += 1;
            ulps_below += usize::from(side(offset_ray(p, n)) <= 0.0);
            assert!(side(offset_hit(p, n, t)) > 0.0, "below the surface from {p} at t {t}");
        }
        assert!(total > 500, "{total} points in the binade");
        assert!(ulps_below > total / 10, "offset_ray failed {ulps_below} of {total}: the case tests little");
    }

    #[test]
    fn offset_hit_moves_no_less_than_offset_ray_and_not_far() {
        for scale in [0.01f32, 1.0, 100.0, 2.0e4] {
            let p = Vec3::new(scale, -scale, scale * 0.5);
            let n = Vec3::new(1.0, 1.0, -1.0).normalize();
            let (q, r) = (offset_ray(p, n), offset_hit(p, n, 10.0));
            assert!((r - p).dot(n) >= (q - p).dot(n), "at {scale}");
            assert!((r - p).length() < (scale + 10.0) * 1e-4, "moved too far at {scale}");
        }
    }
}
