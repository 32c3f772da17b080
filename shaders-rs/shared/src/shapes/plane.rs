//! Bounded planes in object space: the plane y = 0 with normal +y, limited to the rectangle
//! |x| <= a.x, |z| <= a.y, or, for a disk (b.x = 1), to x^2 + z^2 <= a.x^2.

use super::uv::{flat, ShapeUv};
use crate::layout::Primitive;
use crate::surface::SurfaceHit;
use glam::{Vec2, Vec3, Vec4};

/// `Primitive::b.x` of a disk.
pub const DISK: f32 = 1.0;

/// Where the ray meets the bounded plane within `[t_min, t_max]`, if it does. A ray parallel
/// to the plane (direction.y = 0) never meets it: no division by zero.
pub fn intersect(origin: Vec3, direction: Vec3, primitive: &Primitive, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    if direction.y == 0.0 {
        return None;
    }
    let t = -origin.y / direction.y;
    if !(t >= t_min && t <= t_max) {
        return None;
    }
    let p = origin + direction * t;
    let a = primitive.a;
    let inside =
        if primitive.b.x == DISK { p.x * p.x + p.z * p.z <= a.x * a.x } else { p.x.abs() <= a.x && p.z.abs() <= a.y };
    if inside {
        Some(SurfaceHit { t, normal: Vec3::Y })
    } else {
        None
    }
}

/// The texture coordinates at `p` (`shapes::uv`): the rectangle or the disk's square holds the
/// image once, u along +x and v along +z (seen from +y, with -z up).
pub fn uv(primitive: &Primitive, p: Vec3, _n: Vec3) -> ShapeUv {
    let a = primitive.a;
    let half = if primitive.b.x == DISK { Vec2::splat(a.x) } else { Vec2::new(a.x, a.y) };
    flat(p, half, 1.0)
}

/// The sphere the primitive lies in (xyz: centre, w: radius, object space): where
/// `transform::stage_ray` brings a ray that starts far from it, before the transform.
pub fn bound(primitive: &Primitive) -> Vec4 {
    Vec4::new(0.0, 0.0, 0.0, primitive.a.truncate().truncate().length())
}

/// The plane's scene kinds: a rectangle and a disk in the object's xz plane, facing +y.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPE: super::spec::ShapeSpec = super::spec::ShapeSpec {
    kinds: &[
        super::spec::ShapeKind {
            name: "rectangle",
            about: "a rectangle in the xz plane, facing +y; `size` is its extent along x and z",
            params: &[super::spec::Param::positive_each("size", super::spec::ParamType::Pair)],
            check: super::spec::no_check,
            relations: "",
            count: super::spec::one,
            primitives: |v| {
                let [x, z] = v.pair("size");
                bounded(glam::Vec4::new(x / 2.0, z / 2.0, 0.0, 0.0), 0.0)
            },
            mitsuba: |v| {
                let [x, z] = v.pair("size");
                super::mitsuba::plane(super::mitsuba::MitsubaKind::Rectangle, x / 2.0, z / 2.0)
            },
        },
        super::spec::ShapeKind {
            name: "disk",
            about: "a disk in the xz plane, facing +y",
            params: &[super::spec::Param::positive("radius")],
            check: super::spec::no_check,
            relations: "",
            count: super::spec::one,
            primitives: |v| {
                let r = v.number("radius");
                bounded(glam::Vec4::new(r, r, 0.0, 0.0), DISK)
            },
            mitsuba: |v| {
                let r = v.number("radius");
                super::mitsuba::plane(super::mitsuba::MitsubaKind::Disk, r, r)
            },
        },
    ],
    glsl_constants: &[("PLANE_DISK", DISK)],
};

/// A rectangle (half extents in `a.xy`) or disk (`a.x` radius, `disk` = DISK) in y = 0. Its box
/// gets a thickness of a thousandth of its size: zero-thickness boxes are legal in Vulkan but
/// leave grazing rays to each implementation's slab test.
#[cfg(not(target_arch = "spirv"))]
fn bounded(a: glam::Vec4, disk: f32) -> Vec<(Primitive, super::spec::Aabb)> {
    let half = Vec3::new(a.x, a.x.max(a.y) * 1e-3, a.y);
    let primitive = Primitive { a, b: glam::Vec4::new(disk, 0.0, 0.0, 0.0), tint: glam::Vec4::ONE };
    vec![(primitive, super::spec::Aabb::centered(half))]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    fn rect(hx: f32, hz: f32) -> Primitive {
        Primitive { a: Vec4::new(hx, hz, 0.0, 0.0), b: Vec4::ZERO, tint: Vec4::ONE }
    }

    #[test]
    fn hits_inside_and_misses_outside() {
        let down = Vec3::new(0.0, -1.0, 0.0);
        let t = |o: Vec3, p: &Primitive| intersect(o, down, p, 0.0, 10.0).map(|h| h.t);
        assert_eq!(t(Vec3::new(0.5, 2.0, -0.5), &rect(1.0, 1.0)), Some(2.0));
        assert_eq!(t(Vec3::new(1.5, 2.0, 0.0), &rect(1.0, 1.0)), None);
        let disk = Primitive { b: Vec4::new(DISK, 0.0, 0.0, 0.0), ..rect(1.0, 0.0) };
        assert_eq!(t(Vec3::new(0.8, 2.0, 0.8), &disk), None);
        assert_eq!(t(Vec3::new(0.6, 2.0, 0.6), &disk), Some(2.0));
    }

    #[test]
    fn parallel_and_receding_rays_miss() {
        assert!(intersect(Vec3::new(0.0, 0.0, -5.0), Vec3::Z, &rect(1.0, 1.0), 0.0, 10.0).is_none());
        assert!(intersect(Vec3::new(0.0, 1.0, 0.0), Vec3::Y, &rect(1.0, 1.0), 0.0, 10.0).is_none());
    }
}
