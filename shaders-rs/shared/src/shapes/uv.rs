//! Texture coordinates on the procedural shapes: each shape's `uv` gives the (u, v) of its
//! parametrisation at an object-space point of its surface, and their gradients, which carry
//! the ray cone's footprint into texture space (`texture::shape_footprint`). The conventions
//! every shape follows (twinray's guide, *Scene format* has the table): each piece holds the image once,
//! seen from outside it is not mirrored, and v runs down the image (v = 0 at its top), as in
//! glTF. Shapes about the y axis turn u once around it, growing to the right of a viewer
//! outside who has +y up, and run v from the top (+y) down.

use glam::{Vec2, Vec3};
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

/// A procedural shape's texture coordinates at a point, and their object-space gradients:
/// moving by `e` along the surface moves them by (`du . e`, `dv . e`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeUv {
    /// The coordinates at the point.
    pub uv: Vec2,
    /// The object-space gradient of u.
    pub du: Vec3,
    /// The object-space gradient of v.
    pub dv: Vec3,
}

/// Smallest squared distance from an axis that gradients divide by: at the axis (a sphere's
/// poles, a cone's apex) they are very large, so the footprint picks the coarsest level, as a
/// rasteriser's derivatives would there; never infinite.
const AXIS_EPSILON2: f32 = 1.0e-30;

/// The turn of `q` about the y axis as a coordinate in [0, 1] (0.5 on +x, growing towards -z:
/// to the right of a viewer outside with +y up), and its gradient.
pub fn around_y(q: Vec3) -> (f32, Vec3) {
    let rho2 = (q.x * q.x + q.z * q.z).max(AXIS_EPSILON2);
    let u = (-q.z).atan2(q.x) * (0.5 / core::f32::consts::PI) + 0.5;
    (u, Vec3::new(q.z, 0.0, -q.x) * (0.5 / core::f32::consts::PI / rho2))
}

/// A disk or rectangle of half extents `half` (x, z) in a plane y = const, seen from the side
/// `up` (+1: from +y, -1: from -y): u along +x, v down the image.
pub fn flat(p: Vec3, half: Vec2, up: f32) -> ShapeUv {
    let (w, h) = (2.0 * half.x, 2.0 * half.y * up);
    ShapeUv { uv: Vec2::new(0.5 + p.x / w, 0.5 + p.z / h), du: Vec3::X / w, dv: Vec3::Z / h }
}

/// A capped shape of revolution about y (a cylinder or cone of `radius` and `half_height`) at
/// `p`, where its intersection reported the normal `n`: a cap (the normal along y, as the
/// intersections report caps) as a disk seen from outside, the side by the turn about y and
/// the height from the top.
pub fn revolved(p: Vec3, n: Vec3, radius: f32, half_height: f32) -> ShapeUv {
    if n.x == 0.0 && n.z == 0.0 {
        return flat(p, Vec2::splat(radius), if n.y < 0.0 { -1.0 } else { 1.0 });
    }
    let (u, du) = around_y(p);
    let height = 2.0 * half_height;
    ShapeUv { uv: Vec2::new(u, 0.5 - p.y / height), du, dv: -Vec3::Y / height }
}

#[cfg(test)]
mod tests {
    use super::super::{intersect_shape, shape, shape_uv};
    use crate::layout::Primitive;
    use glam::{Vec3, Vec4};

    /// Every shape, hit from all around: (name, primitive).
    fn shapes() -> Vec<(&'static str, Primitive)> {
        let p = |a: Vec4, b: f32| Primitive { a, b: Vec4::new(b, 0.0, 0.0, 0.0), tint: Vec4::ONE };
        vec![
            ("sphere", p(Vec4::new(0.3, -0.2, 0.1, 1.0), 0.0)),
            ("plane", p(Vec4::new(2.0, 1.0, 0.0, 0.0), 0.0)),
            ("plane", p(Vec4::new(1.5, 0.0, 0.0, 0.0), super::super::plane::DISK)),
            ("box", p(Vec4::new(1.0, 2.0, 0.5, 0.0), 0.0)),
            ("cylinder", p(Vec4::new(1.0, 1.5, 0.0, 0.0), 0.0)),
            ("cone", p(Vec4::new(1.0, 1.0, 0.0, 0.0), 0.0)),
            ("torus", p(Vec4::new(1.5, 0.4, 0.0, 0.0), 0.0)),
        ]
    }

    /// Hits on each shape from rays out of a sphere of directions, aimed near its centre:
    /// (kind, primitive, point, reported normal).
    fn hits() -> Vec<(u32, Primitive, Vec3, Vec3)> {
        let mut out = Vec::new();
        for (name, primitive) in shapes() {
            let kind = shape(name).unwrap().hit_kind;
            for i in 0..400 {
                let (a, b) = (i as f32 * 2.399_963, (i as f32 + 0.5) / 400.0);
                let (z, r) = (1.0 - 2.0 * b, (1.0 - (1.0 - 2.0 * b).powi(2)).sqrt());
                let origin = Vec3::new(r * a.cos(), z, r * a.sin()) * 6.0;
                let aim = Vec3::new((i % 7) as f32 * 0.1 - 0.3, (i % 5) as f32 * 0.1 - 0.2, (i % 3) as f32 * 0.1);
                if let Some(hit) = intersect_shape(kind, origin, aim - origin, &primitive, 0.0, 1.0e30) {
                    out.push((kind, primitive, origin + (aim - origin) * hit.t, hit.normal));
                }
            }
        }
        out
    }

    /// The gradients are the coordinates' rates of change along the surface: a step along it
    /// (in the tangent plane) changes them by the gradients' dot products, to first order.
    #[test]
    fn gradients_match_finite_differences() {
        let hits = hits();
        assert!(hits.len() > 2000, "{} hits", hits.len());
        for (kind, primitive, p, n) in hits {
            let s = shape_uv(kind, &primitive, p, n);
            let n = n.normalize();
            for e in [n.any_orthonormal_vector(), n.cross(n.any_orthonormal_vector())] {
                let h = 1.0e-3;
                let there = shape_uv(kind, &primitive, p + e * h, n).uv;
                let mut change = (there - s.uv) / h;
                // u wraps once around shapes of revolution.
                if change.x.abs() > 100.0 {
                    change.x -= change.x.signum() / h;
                }
                let expected = glam::Vec2::new(s.du.dot(e), s.dv.dot(e));
                let tolerance = 0.02 * expected.length().max(0.05) + 0.02;
                assert!((change - expected).length() < tolerance, "kind {kind} at {p}: {change} against {expected}");
            }
        }
    }

    /// Seen from outside, the image is not mirrored: u grows to the viewer's right and v down,
    /// so du x dv points into the surface.
    #[test]
    fn images_read_unmirrored_from_outside() {
        for (kind, primitive, p, n) in hits() {
            let s = shape_uv(kind, &primitive, p, n);
            let flat = kind == shape("plane").unwrap().hit_kind;
            // The plane is one-sided: it faces +y, whichever side the ray came from.
            let n = if flat { Vec3::Y } else { n };
            assert!(s.du.cross(s.dv).dot(n) < 0.0, "kind {kind} at {p}, normal {n}: du {} dv {}", s.du, s.dv);
            assert!((0.0..=1.0).contains(&s.uv.x) && (-1e-6..=1.0 + 1e-6).contains(&s.uv.y), "{}", s.uv);
        }
    }

    /// Known points: the sphere's top is v = 0 and its bottom v = 1; its +x meridian u = 0.5;
    /// a box's +z face reads the image upright, its top-left corner at uv (0, 0).
    #[test]
    fn known_points() {
        let sphere = Primitive { a: Vec4::new(0.0, 0.0, 0.0, 2.0), b: Vec4::ZERO, tint: Vec4::ONE };
        let kind = shape("sphere").unwrap().hit_kind;
        assert!(shape_uv(kind, &sphere, Vec3::new(0.0, 2.0, 0.0), Vec3::Y).uv.y.abs() < 1e-6);
        assert!((shape_uv(kind, &sphere, Vec3::new(0.0, -2.0, 0.0), -Vec3::Y).uv.y - 1.0).abs() < 1e-6);
        let equator = shape_uv(kind, &sphere, Vec3::new(2.0, 0.0, 0.0), Vec3::X).uv;
        assert!((equator - glam::Vec2::new(0.5, 0.5)).length() < 1e-6, "{equator}");
        let cube = Primitive { a: Vec4::new(1.0, 1.0, 1.0, 0.0), b: Vec4::ZERO, tint: Vec4::ONE };
        let kind = shape("box").unwrap().hit_kind;
        let corner = shape_uv(kind, &cube, Vec3::new(-1.0, 1.0, 1.0), Vec3::Z).uv;
        assert!(corner.length() < 1e-6, "{corner}");
    }
}
