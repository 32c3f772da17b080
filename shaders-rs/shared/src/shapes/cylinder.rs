//! Capped cylinder about the object's y axis, centred at its origin: radius `a.x`, half height
//! `a.y`. The side uses the Lagrange-identity discriminant a r^2 - (o x d)_y^2, which does not
//! cancel far from the axis (twinray's guide, *Numerics*); side and caps are tested separately, with
//! inclusive comparisons, so rays through the rim are not lost.

use super::sphere::ON_SURFACE;
use super::uv::{revolved, ShapeUv};
use crate::layout::Primitive;
use crate::surface::{is_self_root, self_reach2, stable_roots, Nearest, SurfaceHit};
use glam::{Vec3, Vec4};

/// The nearest hit of the ray (`origin`, `direction`, object space) on the capped cylinder
/// `primitive` (a.x radius, a.y half height) with t in [`t_min`, `t_max`], or `None`.
pub fn intersect(origin: Vec3, direction: Vec3, primitive: &Primitive, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    solve(origin, direction, primitive, t_min, t_max, true)
}

/// The textbook form: side discriminant k1^2 - k2 k0, roots (-k1 -+ sqrt) / k2, no self-root
/// rejection. Kept on purpose: it cancels far from the axis (twinray's guide, *Numerics*: on lavapipe, 183
/// of 639 decided rays wrong in `cylinder-grazing-far`, t p99 1e-4 in `cylinder-far-1e4`).
pub fn naive_intersect(
    origin: Vec3,
    direction: Vec3,
    primitive: &Primitive,
    t_min: f32,
    t_max: f32,
) -> Option<SurfaceHit> {
    solve(origin, direction, primitive, t_min, t_max, false)
}

/// Side and caps; `robust` picks the side's discriminant and roots (the caps are the same).
fn solve(
    origin: Vec3,
    direction: Vec3,
    primitive: &Primitive,
    t_min: f32,
    t_max: f32,
    robust: bool,
) -> Option<SurfaceHit> {
    #[cfg(target_arch = "spirv")]
    use spirv_std::num_traits::Float;
    let (r, half_height) = (primitive.a.x, primitive.a.y);
    let (o, d) = (origin, direction);
    let mut best = Nearest::new(t_min, t_max);
    let a = d.x * d.x + d.z * d.z;
    if a > 0.0 {
        let half_b = o.x * d.x + o.z * d.z;
        let c = o.x * o.x + o.z * o.z - r * r;
        let cross = o.x * d.z - o.z * d.x;
        let discriminant = if robust { a * r * r - cross * cross } else { half_b * half_b - a * c };
        if discriminant >= 0.0 {
            let on_surface = robust && c.abs() <= ON_SURFACE * r * r;
            let reach2 = self_reach2(on_surface, r * r, d.dot(d));
            let (r0, r1) = if robust {
                stable_roots(a, half_b, c, discriminant)
            } else {
                let root = discriminant.sqrt();
                (Some((-half_b - root) / a), Some((-half_b + root) / a))
            };
            side(&mut best, (o, d), (r, half_height), (r0, r1), reach2);
            side(&mut best, (o, d), (r, half_height), (r1, r0), reach2);
        }
    }
    if d.y != 0.0 {
        cap(&mut best, (o, d), r, half_height);
        cap(&mut best, (o, d), r, -half_height);
    }
    best.hit()
}

/// The side at `root` (the other root `other`), if it is no self root and within the height.
fn side(
    best: &mut Nearest,
    (o, d): (Vec3, Vec3),
    (r, half_height): (f32, f32),
    (root, other): (Option<f32>, Option<f32>),
    reach2: f32,
) {
    if let Some(t) = root {
        if !is_self_root(reach2, t, other) {
            let p = o + d * t;
            if p.y.abs() <= half_height {
                best.take(SurfaceHit { t, normal: Vec3::new(p.x, 0.0, p.z) / r });
            }
        }
    }
}

/// The cap in the plane y = `y` (normal pointing away from the body).
fn cap(best: &mut Nearest, (o, d): (Vec3, Vec3), r: f32, y: f32) {
    let t = (y - o.y) / d.y;
    let p = o + d * t;
    if p.x * p.x + p.z * p.z <= r * r {
        let normal = Vec3::new(0.0, if y > 0.0 { 1.0 } else { -1.0 }, 0.0);
        best.take(SurfaceHit { t, normal });
    }
}

/// The texture coordinates at `p` (`shapes::uv`): the side by the turn about y and the height
/// from the top, each cap as a disk seen from outside.
pub fn uv(primitive: &Primitive, p: Vec3, n: Vec3) -> ShapeUv {
    revolved(p, n, primitive.a.x, primitive.a.y)
}

/// The sphere the primitive lies in (xyz: centre, w: radius, object space): where
/// `transform::stage_ray` brings a ray that starts far from it, before the transform.
pub fn bound(primitive: &Primitive) -> Vec4 {
    Vec4::new(0.0, 0.0, 0.0, primitive.a.truncate().truncate().length())
}

/// The cylinder's scene kind: capped, about the object's y axis, centred at its origin.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPE: super::spec::ShapeSpec = super::spec::ShapeSpec {
    kinds: &[super::spec::ShapeKind {
        name: "cylinder",
        about: "a capped cylinder about the y axis",
        params: super::spec::RADIUS_AND_HEIGHT,
        check: super::spec::no_check,
        relations: "",
        count: super::spec::one,
        primitives: super::spec::radius_and_half_height,
        mitsuba: |v| super::mitsuba::capped_cylinder(v.number("radius"), v.number("height") / 2.0),
    }],
    glsl_constants: &[],
};

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    fn cylinder() -> Primitive {
        Primitive { a: Vec4::new(1.0, 2.0, 0.0, 0.0), b: Vec4::ZERO, tint: Vec4::ONE }
    }

    #[test]
    fn side_cap_and_rim() {
        let side = intersect(Vec3::new(-5.0, 0.0, 0.0), Vec3::X, &cylinder(), 0.0, 100.0).unwrap();
        assert_eq!((side.t, side.normal), (4.0, -Vec3::X));
        let cap = intersect(Vec3::new(0.5, 5.0, 0.0), -Vec3::Y, &cylinder(), 0.0, 100.0).unwrap();
        assert_eq!((cap.t, cap.normal), (3.0, Vec3::Y));
        // Through the rim: x = 1 exactly at the top cap's edge.
        assert!(intersect(Vec3::new(1.0, 5.0, 0.0), -Vec3::Y, &cylinder(), 0.0, 100.0).is_some());
    }

    /// Far from the axis the textbook discriminant k1^2 - k2 k0 cancels (twinray's guide, *Numerics*,
    /// `cylinder-grazing-far`); rays across the silhouette must agree with the exact answer.
    #[test]
    fn far_silhouette_is_decided_correctly() {
        for distance in [1.0e3f32, 1.0e4] {
            for i in 0..401 {
                let x = -1.2 + 2.4 * i as f32 / 400.0;
                if (x.abs() - 1.0).abs() < 2e-3 {
                    continue; // within float noise of tangency
                }
                let o = Vec3::new(x, 0.0, -distance);
                let hit = intersect(o, Vec3::Z, &cylinder(), 0.0, 2.0 * distance);
                assert_eq!(hit.is_some(), x.abs() <= 1.0, "x {x} at {distance}");
            }
        }
    }

    #[test]
    fn rays_leaving_the_side_miss() {
        for k in 0..200 {
            let a = k as f32 * 0.031;
            let n = Vec3::new(a.cos(), 0.0, a.sin());
            let p = crate::offset::offset_ray(n + Vec3::new(0.0, 0.5, 0.0), n);
            let out = (n + Vec3::new(0.0, 0.3, 0.0)).normalize();
            assert!(intersect(p, out, &cylinder(), 0.0, 100.0).is_none(), "self-hit at {k}");
        }
    }

    /// An origin just inside the side (within `ON_SURFACE`) with a ray nearly along the axis:
    /// its nearer root, 0.4 away, is a real exit, not the origin's own root.
    #[test]
    fn near_surface_origin_keeps_a_distant_near_root() {
        let o = Vec3::new(1.0 - 4e-4, 0.0, 0.0);
        let d = Vec3::new(1e-3f32.sin(), 1e-3f32.cos(), 0.0);
        let hit = intersect(o, d, &cylinder(), 0.0, 100.0).expect("leaves through the side");
        let t = 4e-4 / 1e-3f32.sin();
        assert!((hit.t / t - 1.0).abs() < 1e-5, "{} against {t}", hit.t);
        assert!(hit.normal.x > 0.99);
    }
}
