//! Axis-aligned box centred at the object's origin with half extents `Primitive::a.xyz`: the
//! slab test of pbrt-v3 (after Ize 2013), whose t_far is widened by 1 + 2 gamma_3 where it is
//! compared with t_near, so that rounding cannot make a ray through an edge miss. The widening
//! is a margin of the comparison only: a ray leaving the box from inside gets its exit as
//! computed, not 2 gamma_3 (3.6e-7) long. NaN-safe: an axis the ray is parallel to is decided by
//! position, never by 0 * inf, and every min/max is an explicit comparison (the GPU's FMin/FMax
//! are undefined for NaN).

use super::uv::ShapeUv;
use crate::layout::Primitive;
use crate::surface::SurfaceHit;
use glam::{Vec2, Vec3, Vec4};

/// gamma_3 = 3 eps / (1 - 3 eps), eps = 2^-24 (pbrt's bound on three rounded operations).
pub const GAMMA_3: f32 = 3.0 * 5.960_464_5e-8 / (1.0 - 3.0 * 5.960_464_5e-8);

/// Slab interval so far, with the axis that set each end; `far` as computed, unwidened.
#[derive(Clone, Copy)]
struct Slabs {
    near: f32,
    far: f32,
    near_axis: Vec3,
    far_axis: Vec3,
    empty: bool,
}

/// Narrows `s` by the slab |x| <= h of one axis (`unit` is that axis). In place: rust-gpu
/// writes a `Slabs` passed along by value as a struct with phis at each branch (as it does an
/// `Option`, `surface::Nearest`).
fn slab(s: &mut Slabs, o: f32, d: f32, h: f32, unit: Vec3) {
    if d == 0.0 {
        let outside = o < -h || o > h;
        s.empty = s.empty || outside;
        return;
    }
    let inv = 1.0 / d;
    let a = (-h - o) * inv;
    let b = (h - o) * inv;
    let (t0, t1) = if a <= b { (a, b) } else { (b, a) };
    let sign = if d > 0.0 { 1.0 } else { -1.0 };
    if t0 > s.near {
        s.near = t0;
        s.near_axis = unit * -sign;
    }
    if t1 < s.far {
        s.far = t1;
        s.far_axis = unit * sign;
    }
    // Widening the least t_far is widening each (a product by a constant above 1 rounds
    // monotonically), so the interval is empty exactly where pbrt's is.
    s.empty = s.empty || s.near > s.far * (1.0 + 2.0 * GAMMA_3);
}

/// The entry point (or the exit, for a ray starting inside) within `[t_min, t_max]`.
pub fn intersect(origin: Vec3, direction: Vec3, primitive: &Primitive, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    let h = primitive.a;
    let mut s = Slabs { near: -f32::MAX, far: f32::MAX, near_axis: Vec3::ZERO, far_axis: Vec3::ZERO, empty: false };
    slab(&mut s, origin.x, direction.x, h.x, Vec3::X);
    slab(&mut s, origin.y, direction.y, h.y, Vec3::Y);
    slab(&mut s, origin.z, direction.z, h.z, Vec3::Z);
    if s.empty {
        None
    } else if s.near >= t_min && s.near <= t_max {
        Some(SurfaceHit { t: s.near, normal: s.near_axis })
    } else if s.far >= t_min && s.far <= t_max {
        Some(SurfaceHit { t: s.far, normal: s.far_axis })
    } else {
        None
    }
}

/// The texture coordinates at `p` on the face its intersection's normal `n` names
/// (`shapes::uv`): each face holds the image once, seen from outside; the four sides with +y
/// up, the top with -z up and the bottom with +z up.
pub fn uv(primitive: &Primitive, p: Vec3, n: Vec3) -> ShapeUv {
    let h = Vec3::new(primitive.a.x, primitive.a.y, primitive.a.z);
    let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
    // The face's right and up directions, seen from outside.
    let (right, up) = if ax >= ay && ax >= az {
        (Vec3::new(0.0, 0.0, if n.x < 0.0 { 1.0 } else { -1.0 }), Vec3::Y)
    } else if az >= ay {
        (Vec3::new(if n.z < 0.0 { -1.0 } else { 1.0 }, 0.0, 0.0), Vec3::Y)
    } else {
        (Vec3::X, Vec3::new(0.0, 0.0, if n.y < 0.0 { 1.0 } else { -1.0 }))
    };
    let (width, height) = (2.0 * right.abs().dot(h), 2.0 * up.abs().dot(h));
    ShapeUv { uv: Vec2::new(0.5 + p.dot(right) / width, 0.5 - p.dot(up) / height), du: right / width, dv: -up / height }
}

/// The sphere the primitive lies in (xyz: centre, w: radius, object space): where
/// `transform::stage_ray` brings a ray that starts far from it, before the transform.
pub fn bound(primitive: &Primitive) -> Vec4 {
    Vec4::new(0.0, 0.0, 0.0, primitive.a.truncate().length())
}

/// The box's scene kind: an axis-aligned box centred at the origin.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPE: super::spec::ShapeSpec = super::spec::ShapeSpec {
    kinds: &[super::spec::ShapeKind {
        name: "box",
        about: "an axis-aligned box; `size` is its extent along x, y and z",
        params: &[super::spec::Param::positive_each("size", super::spec::ParamType::Triple)],
        check: super::spec::no_check,
        relations: "",
        count: super::spec::one,
        primitives: |v| {
            let half = Vec3::from(v.triple("size")) / 2.0;
            super::spec::single(half.extend(0.0), half)
        },
        mitsuba: |v| super::mitsuba::cube(Vec3::from(v.triple("size")) / 2.0),
    }],
    glsl_constants: &[("BOX_GAMMA_3", GAMMA_3)],
};

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    fn unit_box() -> Primitive {
        Primitive { a: Vec4::new(1.0, 2.0, 3.0, 0.0), b: Vec4::ZERO, tint: Vec4::ONE }
    }

    #[test]
    fn enters_through_the_facing_side() {
        let hit = intersect(Vec3::new(-5.0, 0.5, 0.5), Vec3::X, &unit_box(), 0.0, 100.0).unwrap();
        assert_eq!((hit.t, hit.normal), (4.0, -Vec3::X));
        let inside = intersect(Vec3::ZERO, Vec3::Y, &unit_box(), 0.0, 100.0).unwrap();
        assert_eq!((inside.t, inside.normal), (2.0, Vec3::Y));
    }

    /// The widening is the comparison's margin, not the answer's: exits from inside come back
    /// as computed (within an ulp or two of the true exit, as often short as long), and a ray
    /// through an edge, where rounding may put t_near just past t_far, still hits.
    #[test]
    fn exits_are_not_widened_and_edges_still_hit() {
        let b = unit_box();
        let mut rng = crate::random::SplitMix64(90);
        let (mut long, mut short) = (0, 0);
        for _ in 0..2000 {
            let o = Vec3::new(rng.unit() - 0.5, 2.0 * rng.unit() - 1.0, 3.0 * rng.unit() - 1.5);
            let d = Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5).normalize();
            let hit = intersect(o, d, &b, 0.0, 100.0).unwrap();
            let exact = [0, 1, 2]
                .iter()
                .map(|&k| {
                    let (o, d, h) = (f64::from(o[k]), f64::from(d[k]), f64::from(b.a[k]));
                    if d > 0.0 {
                        (h - o) / d
                    } else {
                        (-h - o) / d
                    }
                })
                .fold(f64::INFINITY, f64::min);
            let error = (f64::from(hit.t) - exact) / exact;
            assert!(error.abs() < 3.0 * 5.96e-8, "exit {} against {exact}: {error:e}", hit.t);
            long += usize::from(error > 0.0);
            short += usize::from(error < 0.0);
        }
        assert!(long > 200 && short > 200, "exits {long} long, {short} short");
        // Across the edge x = 1, y = 2 at 45 degrees, touching it only: t_near and t_far meet.
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        let edge = intersect(Vec3::new(1.0, 2.0, 0.0) - d * 3.0, d, &b, 0.0, 100.0);
        assert!(edge.is_some_and(|h| (h.t - 3.0).abs() < 1e-5));
    }

    /// A ray lying in a face plane (d_i = 0, o_i = +-h_i) gives 0 * inf = NaN in the textbook
    /// slab test; here it hits (the face is inclusive) and never returns NaN.
    #[test]
    fn rays_in_a_face_plane_are_decided_without_nan() {
        let hit = intersect(Vec3::new(-5.0, 2.0, 0.0), Vec3::X, &unit_box(), 0.0, 100.0).unwrap();
        assert_eq!(hit.t, 4.0);
        assert!(intersect(Vec3::new(-5.0, 2.0001, 0.0), Vec3::X, &unit_box(), 0.0, 100.0).is_none());
    }

    #[test]
    fn rays_leaving_a_face_miss() {
        let p = crate::offset::offset_ray(Vec3::new(1.0, 0.3, 0.3), Vec3::X);
        assert!(intersect(p, Vec3::new(1.0, 0.5, 0.0).normalize(), &unit_box(), 0.0, 100.0).is_none());
    }
}
