//! Texture coordinates on the procedural shapes in f64, from the point alone: an independent
//! evaluation of each shape's parametrisation (`twinray_shared::shapes::uv` has the
//! conventions), for explain's reference. The piece a point lies on (a box's face, a cap) is
//! decided here by where the point is, not by the normal an intersection reported.

use super::shapes::RefShape;
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// The texture coordinates of `shape` at `p`, a point on (or within rounding of) its surface
/// in object space, with the outward normal of the piece it lies on; `None` for shapes without
/// a parametrisation here (triangles carry theirs in their vertices).
pub fn uv(shape: &RefShape, p: DVec3) -> Option<(DVec2, DVec3)> {
    Some(match *shape {
        RefShape::Sphere { center, radius: _ } => {
            let q = p - center;
            let v = (q.y / q.length()).clamp(-1.0, 1.0).acos() / PI;
            (DVec2::new(turn(q), v), q.normalize())
        }
        RefShape::Rectangle { half_x, half_z } => (flat(p, DVec2::new(half_x, half_z), 1.0), DVec3::Y),
        RefShape::Disk { radius } => (flat(p, DVec2::splat(radius), 1.0), DVec3::Y),
        RefShape::Box { half } => face(p, half),
        RefShape::Cylinder { radius, half_height } => {
            let rho = p.x.hypot(p.z);
            if half_height - p.y.abs() < radius - rho {
                cap(p, radius)
            } else {
                side(p, half_height, DVec3::new(p.x, 0.0, p.z) / rho)
            }
        }
        RefShape::Cone { radius, half_height } => {
            let rho = p.x.hypot(p.z);
            let ring = radius * (half_height - p.y) / (2.0 * half_height);
            if p.y + half_height < ring - rho {
                cap(p, radius)
            } else {
                let out = DVec3::new(p.x, 0.0, p.z) / rho;
                side(p, half_height, (out * 2.0 * half_height + DVec3::Y * radius).normalize())
            }
        }
        RefShape::Torus { major, minor: _ } => {
            let rho = p.x.hypot(p.z);
            let psi = p.y.atan2(rho - major);
            let ring = DVec3::new(p.x, 0.0, p.z) / rho;
            (DVec2::new(turn(p), 0.5 - psi / TAU), ring * psi.cos() + DVec3::Y * psi.sin())
        }
        RefShape::Triangle { .. } | RefShape::Traced { .. } | RefShape::Own { .. } => return None,
    })
}

/// The turn about y: 0.5 on +x, growing towards -z.
fn turn(q: DVec3) -> f64 {
    (-q.z).atan2(q.x) / TAU + 0.5
}

/// A rectangle of half extents `half` (x, z) in a plane y = const, seen from the side `up`.
fn flat(p: DVec3, half: DVec2, up: f64) -> DVec2 {
    DVec2::new(0.5 + p.x / (2.0 * half.x), 0.5 + up * p.z / (2.0 * half.y))
}

/// A cap of a shape of revolution: the disk seen from outside, above or below.
fn cap(p: DVec3, radius: f64) -> (DVec2, DVec3) {
    let up = if p.y < 0.0 { -1.0 } else { 1.0 };
    (flat(p, DVec2::splat(radius), up), DVec3::Y * up)
}

/// The side of a shape of revolution: the turn, and the height from the top.
fn side(p: DVec3, half_height: f64, normal: DVec3) -> (DVec2, DVec3) {
    (DVec2::new(turn(p), 0.5 - p.y / (2.0 * half_height)), normal)
}

/// The box face `p` is nearest, relative to the box's size, seen from outside.
fn face(p: DVec3, half: DVec3) -> (DVec2, DVec3) {
    let r = p / half;
    let axis = if r.x.abs() >= r.y.abs() && r.x.abs() >= r.z.abs() {
        0
    } else if r.z.abs() >= r.y.abs() {
        2
    } else {
        1
    };
    let s = if p[axis] < 0.0 { -1.0 } else { 1.0 };
    // (across, its half extent, sign), (down, its half extent, sign): u grows along `across`
    // times its sign, v along `down` times its sign.
    let ((a, sa), (d, sd)) = match axis {
        0 => ((2, -s), (1, -1.0)),
        2 => ((0, s), (1, -1.0)),
        _ => ((0, 1.0), (2, s)),
    };
    let uv = DVec2::new(0.5 + sa * p[a] / (2.0 * half[a]), 0.5 + sd * p[d] / (2.0 * half[d]));
    let mut n = DVec3::ZERO;
    n[axis] = s;
    (uv, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use twinray_shared::layout::Primitive;
    use twinray_shared::shapes::{shape, shape_uv};

    /// The f64 evaluation and the shaders' f32 one agree away from seams and edges, on every
    /// shape, at points the reference's own sampler draws on its surface.
    #[test]
    fn the_f64_coordinates_agree_with_the_shaders() {
        let cases: [(&str, [f32; 4], f32); 7] = [
            ("sphere", [0.3, -0.2, 0.1, 1.5], 0.0),
            ("plane", [2.0, 1.0, 0.0, 0.0], 0.0),
            ("plane", [1.5, 0.0, 0.0, 0.0], twinray_shared::shapes::plane::DISK),
            ("box", [1.0, 2.0, 0.5, 0.0], 0.0),
            ("cylinder", [1.0, 1.5, 0.0, 0.0], 0.0),
            ("cone", [1.0, 1.0, 0.0, 0.0], 0.0),
            ("torus", [1.5, 0.4, 0.0, 0.0], 0.0),
        ];
        let mut state = 1u64;
        let mut draw = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for (name, a, b) in cases {
            let primitive = Primitive { a: a.into(), b: [b, 0.0, 0.0, 0.0].into(), tint: [1.0; 4].into() };
            let reference = super::super::shapes::from_primitive(name, &primitive).unwrap();
            let kind = shape(name).unwrap().hit_kind;
            for _ in 0..500 {
                let (p, _) = super::super::surface::sample(&reference, &mut draw);
                let (want, n) = uv(&reference, p).unwrap();
                let got = shape_uv(kind, &primitive, p.as_vec3(), n.as_vec3()).uv.as_dvec2();
                let mut gap = (got - want).abs();
                gap.x = gap.x.min(1.0 - gap.x); // u wraps
                assert!(gap.max_element() < 1e-5, "{name} at {p}: f32 {got}, f64 {want}");
            }
        }
    }
}
