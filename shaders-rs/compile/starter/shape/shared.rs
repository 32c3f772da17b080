//! The shape `{shape}`, to make your own: as written, a capsule about the y axis, the points
//! within `radius` of the segment from y = -length/2 to +length/2. A primitive holds `a.x` =
//! radius and `a.y` = half the length (`SHAPE.primitives` fills them from the scene's keys).
//!
//! Two descriptions of one surface live here, on purpose apart: `intersect`, the f32 routine
//! the GPU runs, and `distance`, its definition in f64, which twinray's reference traces to
//! judge every ray of `twinray probe`. A slip in one is then a disagreement, not a copy.

#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;
use twinray_shared::glam::Vec3;
use twinray_shared::layout::Primitive;
use twinray_shared::surface::{Nearest, SurfaceHit};

/// What its intersection stage reports: one per shape of the crate, from 32 to 127.
pub const HIT_KIND: u32 = {hit_kind};

/// The nearest hit of the ray (object space) on the shape with t in [t_min, t_max].
pub fn intersect(origin: Vec3, direction: Vec3, p: &Primitive, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    let (radius, half) = (p.a.x, p.a.y);
    // From the ray's point nearest the centre, the quadratics below cancel little: a far ray's
    // own origin would leave its roots to f32's rounding of large squares.
    let t0 = -origin.dot(direction) / direction.dot(direction);
    let o = origin + direction * t0;
    let mut best = Nearest::new(t_min - t0, t_max - t0);
    // The side: at `radius` from the y axis, between the caps.
    let (oxz, dxz) = (Vec3::new(o.x, 0.0, o.z), Vec3::new(direction.x, 0.0, direction.z));
    let (a, b, c) = (dxz.dot(dxz), oxz.dot(dxz), oxz.dot(oxz) - radius * radius);
    let disc = b * b - a * c;
    if a > 0.0 && disc >= 0.0 {
        side(&mut best, o, direction, (-b - disc.sqrt()) / a, half);
        side(&mut best, o, direction, (-b + disc.sqrt()) / a, half);
    }
    // The caps: half spheres about the segment's ends, each beyond its end.
    cap(&mut best, o, direction, -half, radius);
    cap(&mut best, o, direction, half, radius);
    best.hit().map(|hit| SurfaceHit { t: hit.t + t0, normal: hit.normal })
}

fn side(best: &mut Nearest, o: Vec3, d: Vec3, t: f32, half: f32) {
    let q = o + d * t;
    if q.y.abs() <= half {
        best.take(SurfaceHit { t, normal: Vec3::new(q.x, 0.0, q.z) });
    }
}

fn cap(best: &mut Nearest, o: Vec3, d: Vec3, end: f32, radius: f32) {
    let oc = o - Vec3::new(0.0, end, 0.0);
    let (dd, b, c) = (d.dot(d), oc.dot(d), oc.dot(oc) - radius * radius);
    let disc = b * b - dd * c;
    if disc >= 0.0 {
        cap_root(best, oc, d, (-b - disc.sqrt()) / dd, end);
        cap_root(best, oc, d, (-b + disc.sqrt()) / dd, end);
    }
}

fn cap_root(best: &mut Nearest, oc: Vec3, d: Vec3, t: f32, end: f32) {
    let q = oc + d * t;
    if q.y * end >= 0.0 {
        best.take(SurfaceHit { t, normal: q });
    }
}

#[cfg(not(target_arch = "spirv"))]
pub use cpu::SHAPE;

/// What twinray's host and reference read, on the CPU only.
#[cfg(not(target_arch = "spirv"))]
mod cpu {
    use twinray_shared::custom::{CustomShape, Parameters};
    use twinray_shared::glam::{DVec3, Vec3, Vec4};
    use twinray_shared::layout::Primitive;
    use twinray_shared::shapes::spec::{single, Aabb, Param, Values};

    /// The shape as scenes name it (`kind = "{shape}"`) and the reference knows it.
    pub const SHAPE: CustomShape = CustomShape {
        name: "{shape}",
        about: "a capsule about y: `radius`, and `length` between its caps' centres",
        hit_kind: super::HIT_KIND,
        params: &[Param::positive("radius"), Param::positive("length")],
        check: |_| Ok(()),
        primitives,
        distance,
        normal,
    };

    /// One primitive: its parameters, and a box that holds it.
    fn primitives(keys: &Values) -> Vec<(Primitive, Aabb)> {
        let (radius, length) = (keys.number("radius"), keys.number("length"));
        single(Vec4::new(radius, length / 2.0, 0.0, 0.0), Vec3::new(radius, length / 2.0 + radius, radius))
    }

    /// The signed distance to the surface, negative inside, never more than the true distance
    /// (here exact): from the point to the nearest point of the segment, less the radius.
    fn distance(p: DVec3, q: &Parameters) -> f64 {
        (p - nearest_on_segment(p, q)).length() - q.a.x
    }

    /// The outward normal at a point of the surface (any length).
    fn normal(p: DVec3, q: &Parameters) -> DVec3 {
        p - nearest_on_segment(p, q)
    }

    fn nearest_on_segment(p: DVec3, q: &Parameters) -> DVec3 {
        DVec3::new(0.0, p.y.clamp(-q.a.y, q.a.y), 0.0)
    }
}
