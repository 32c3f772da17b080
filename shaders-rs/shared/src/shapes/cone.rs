//! Capped cone about the object's y axis, centred at its origin: apex at y = `a.y`, base of
//! radius `a.x` at y = -`a.y`. The quadratic of twinray's guide, *Numerics* with apex A, axis v = -y and
//! cos^2 of the half-angle; roots as c / q and q / a with the stable q, since a -> 0 for rays
//! parallel to a generator. Only the nappe between apex and base counts, plus the base disk.
//!
//! The discriminant uses the cone's Lagrange-identity form, the analogue of the cylinder's:
//! with w = co x d, b'^2 - ac = cos^2 (sin^2 |w|^2 - (w.v)^2). The textbook b'^2 - ac cancels
//! when the roots are close (rays down the axis, hitting near the apex: relative t error
//! 4e-5 found by the property tests against the f64 reference); this form has no large terms.
//! Every coefficient is scaled by h^2 + r^2 so that no rounded cos^2 enters (see `intersect`).

use super::sphere::ON_SURFACE;
use super::uv::{revolved, ShapeUv};
use crate::exact::point_at;
use crate::layout::Primitive;
use crate::surface::{is_self_root, self_reach2, stable_roots, Nearest, SurfaceHit};
use glam::{Vec3, Vec4};

/// The nearest hit of the ray (`origin`, `direction`, object space) on the capped cone
/// `primitive` (a.x radius, a.y half height) with t in [`t_min`, `t_max`], or `None`.
pub fn intersect(origin: Vec3, direction: Vec3, primitive: &Primitive, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    let (r, half_height) = (primitive.a.x, primitive.a.y);
    let height = 2.0 * half_height;
    // cos^2 = h^2 / (h^2 + r^2) and sin^2 = r^2 / (h^2 + r^2), but the quadratic is multiplied
    // through by h^2 + r^2 so that no rounded angle enters it: for rays nearly parallel to a
    // generator the hit moves by (angle error) / (angle between ray and generator).
    let (h2, r2) = (height * height, r * r);
    let apex = Vec3::new(0.0, half_height, 0.0);
    let (d, co) = (direction, origin - apex);
    // v = -y: d.v = -d.y, co.v = -co.y; the perpendicular parts are the xz components.
    let (dv, cov) = (-d.y, -co.y);
    let a = r2 * dv * dv - h2 * (d.x * d.x + d.z * d.z);
    let half_b = r2 * dv * cov - h2 * (d.x * co.x + d.z * co.z);
    let c = r2 * cov * cov - h2 * (co.x * co.x + co.z * co.z);
    let w = co.cross(d);
    let discriminant = h2 * (r2 * (w.x * w.x + w.z * w.z) - h2 * w.y * w.y);
    let mut best = Nearest::new(t_min, t_max);
    if discriminant >= 0.0 {
        let on_surface = c.abs() <= ON_SURFACE * (r2 + h2) * co.dot(co);
        // The cone's scale at the origin is its distance from the apex.
        let reach2 = self_reach2(on_surface, co.dot(co), d.dot(d));
        let (r0, r1) = stable_roots(a, half_b, c, discriminant);
        side(&mut best, (origin, d), (apex, height), (h2, r2), (r0, r1), reach2);
        side(&mut best, (origin, d), (apex, height), (h2, r2), (r1, r0), reach2);
    }
    if d.y != 0.0 {
        let t = (-half_height - origin.y) / d.y;
        let p = origin + d * t;
        if p.x * p.x + p.z * p.z <= r * r {
            best.take(SurfaceHit { t, normal: -Vec3::Y });
        }
    }
    best.hit()
}

/// The side at `root` (the other root `other`), polished, if it is no self root and lies
/// between the apex and the base.
fn side(
    best: &mut Nearest,
    (o, d): (Vec3, Vec3),
    (apex, height): (Vec3, f32),
    (h2, r2): (f32, f32),
    (root, other): (Option<f32>, Option<f32>),
    reach2: f32,
) {
    if let Some(t) = root {
        if !is_self_root(reach2, t, other) {
            let t = polish(o, apex, d, (h2, r2), t);
            let cp = point_at(o, d, t) - apex;
            let along = -cp.y; // distance below the apex along the axis
            if along >= 0.0 && along <= height {
                // Outward normal (h^2 + r^2) (cos^2 cp - (cp.v) v), with v = -y.
                best.take(SurfaceHit { t, normal: Vec3::new(h2 * cp.x, -r2 * cp.y, h2 * cp.z) });
            }
        }
    }
}

/// Largest Newton correction taken, relative to t: a polish, never a jump to another root.
pub const POLISH_LIMIT: f32 = 0.1;

/// Root `t` after one Newton step on the cone's implicit function at the hit point. From an
/// origin near the surface, c is a small difference of large terms (relative error 5e-5 at a
/// tenth of a percent from the surface, for rays along a generator); at the hit point the
/// function is evaluated from small, accurate coordinates (`point_at`: accurate without a
/// fused multiply-add, which lavapipe does not do).
fn polish(o: Vec3, apex: Vec3, d: Vec3, (h2, r2): (f32, f32), t: f32) -> f32 {
    // The hit point from the ray's own origin, then the apex: o - apex would round the origin
    // off the ray (by its ULPs, 1e-3 at 1e4), which a grazing ray turns into a large t error.
    let cp = point_at(o, d, t) - apex;
    let f = r2 * cp.y * cp.y - h2 * (cp.x * cp.x + cp.z * cp.z);
    let slope = 2.0 * (r2 * cp.y * d.y - h2 * (cp.x * d.x + cp.z * d.z));
    if f.abs() <= POLISH_LIMIT * t.abs() * slope.abs() {
        t - f / slope
    } else {
        t
    }
}

/// The texture coordinates at `p` (`shapes::uv`): the side by the turn about y and the height
/// from the apex, the base as a disk seen from below.
pub fn uv(primitive: &Primitive, p: Vec3, n: Vec3) -> ShapeUv {
    revolved(p, n, primitive.a.x, primitive.a.y)
}

/// The sphere the primitive lies in (xyz: centre, w: radius, object space): where
/// `transform::stage_ray` brings a ray that starts far from it, before the transform.
pub fn bound(primitive: &Primitive) -> Vec4 {
    Vec4::new(0.0, 0.0, 0.0, primitive.a.truncate().truncate().length())
}

/// The cone's scene kind: capped, about the object's y axis, centred at its origin.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPE: super::spec::ShapeSpec = super::spec::ShapeSpec {
    kinds: &[super::spec::ShapeKind {
        name: "cone",
        about: "a capped cone about the y axis, base of `radius` at y = -height/2, apex at +height/2",
        params: super::spec::RADIUS_AND_HEIGHT,
        check: super::spec::no_check,
        relations: "",
        count: super::spec::one,
        primitives: super::spec::radius_and_half_height,
        mitsuba: |v| super::mitsuba::cone(v.number("radius"), v.number("height") / 2.0),
    }],
    glsl_constants: &[("CONE_POLISH_LIMIT", POLISH_LIMIT)],
};

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    /// Apex at y = 1, base radius 1 at y = -1: half-angle atan(1/2).
    fn cone() -> Primitive {
        Primitive { a: Vec4::new(1.0, 1.0, 0.0, 0.0), b: Vec4::ZERO, tint: Vec4::ONE }
    }

    #[test]
    fn side_base_and_mirror_nappe() {
        let side = intersect(Vec3::new(-5.0, 0.0, 0.0), Vec3::X, &cone(), 0.0, 100.0).unwrap();
        assert!((side.t / 4.5 - 1.0).abs() < 1e-6, "{}", side.t); // relative, as the probes' precision targets are
        assert!(side.normal.x < 0.0 && side.normal.y > 0.0);
        let base = intersect(Vec3::new(0.2, -5.0, 0.0), Vec3::Y, &cone(), 0.0, 100.0).unwrap();
        assert_eq!((base.t, base.normal), (4.0, -Vec3::Y));
        // Above the apex the quadratic's mirror nappe is not part of the cone.
        assert!(intersect(Vec3::new(-5.0, 2.0, 0.0), Vec3::X, &cone(), 0.0, 100.0).is_none());
    }

    /// A ray parallel to a generator has a = 0: one root, found without dividing by zero.
    #[test]
    fn ray_parallel_to_a_generator() {
        let generator = Vec3::new(0.5, -1.0, 0.0).normalize(); // slope r / h of this cone
        let o = Vec3::new(-0.5, 0.0, 0.0) - generator * 3.0;
        let hit = intersect(o, generator, &cone(), 0.0, 100.0).expect("hits the base or side");
        assert!(hit.t.is_finite());
    }

    /// A ray parallel to a generator, 0.005 below the apex, from an origin 5 units up the line:
    /// the origin is within `ON_SURFACE` of the upper nappe, but the side hit near the apex is
    /// far from it and must not be dropped as the origin's own root (it was: the base won).
    #[test]
    fn generator_parallel_ray_from_near_the_surface() {
        let generator = Vec3::new(0.5, -1.0, 0.0).normalize();
        let o = Vec3::new(0.0, 1.0 - 0.005, 0.0) - generator * 5.0;
        let hit = intersect(o, generator, &cone(), 0.0, 100.0).expect("hits the side");
        // Enters the lower nappe where x = -(radius at that depth): s = -0.0025 / 0.894427.
        let t = 5.0 - 0.0025 / 0.894_427_2;
        assert!((hit.t / t - 1.0).abs() < 1e-6, "{} against {t}", hit.t);
        assert!(hit.normal.y > 0.0, "the side, not the base");
    }
}
