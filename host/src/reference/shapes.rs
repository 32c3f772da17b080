//! The f64 reference for every shape: an independent evaluation, not the f32 shader math run
//! again. Quadrics use the cancellation-free forms in f64; the torus is found by sphere
//! tracing its exact signed distance in f64 and bisecting the sign change, so a quartic-solver
//! bug cannot hide in both; so is any shape of [`TRACED`], by its distance; triangles use
//! Moller-Trumbore in f64.
//!
//! Each answer is a hit, a miss, or `Ambiguous`: the ray passes within a few f32 ULPs of
//! tangency, of a rim or edge, or of t_min, where rounding the f32 input alone could flip
//! hit and miss. Ambiguous rays are reported apart and never counted as errors.

use super::ray::{first, Candidate, F32_EPS};
pub use super::ray::{RefRay, Verdict, AMBIGUOUS_ULPS};
use super::traced::{own, torus, traced};
pub use super::traced::{TracedShape, TRACED};
use crate::sets::own::OwnShapeRef;
use glam::DVec3;
use glam::DVec4;
use twinray_shared::custom::Parameters;
use twinray_shared::layout::Primitive;
use twinray_shared::shapes::plane::DISK;

/// A shape in its own object space, with the meaning of `twinray_shared`'s primitives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RefShape {
    /// Centre and radius.
    Sphere { center: DVec3, radius: f64 },
    /// In y = 0, half extents along x and z.
    Rectangle { half_x: f64, half_z: f64 },
    /// In y = 0, about the origin.
    Disk { radius: f64 },
    /// Axis-aligned, half extents.
    Box { half: DVec3 },
    /// Capped, about y.
    Cylinder { radius: f64, half_height: f64 },
    /// Capped, about y, apex at +half_height.
    Cone { radius: f64, half_height: f64 },
    /// About y: ring radius `major`, tube radius `minor`.
    Torus { major: f64, minor: f64 },
    /// One triangle of a mesh.
    Triangle { p: [DVec3; 3] },
    /// A shape of [`TRACED`], with its primitive's `a`.
    Traced { shape: &'static TracedShape, a: DVec4 },
    /// A crate's own shape, known by the signed distance the crate defines, with its
    /// primitive's parameters and box (min, max).
    Own { shape: OwnShapeRef, parameters: Parameters, bounds: (DVec3, DVec3) },
}

/// The true answer for `ray` and `shape`.
pub fn intersect(shape: &RefShape, ray: &RefRay) -> Verdict {
    match *shape {
        RefShape::Sphere { center, radius } => sphere(ray, center, radius),
        RefShape::Rectangle { half_x, half_z } => plane(ray, |p| (half_x - p.x.abs()).min(half_z - p.z.abs())),
        RefShape::Disk { radius } => plane(ray, |p| radius - (p.x * p.x + p.z * p.z).sqrt()),
        RefShape::Box { half } => aabox(ray, half),
        RefShape::Cylinder { radius, half_height } => cylinder(ray, radius, half_height),
        RefShape::Cone { radius, half_height } => cone(ray, radius, half_height),
        RefShape::Torus { major, minor } => torus(ray, major, minor),
        RefShape::Triangle { p } => triangle(ray, p),
        RefShape::Traced { shape, a } => traced(ray, shape, a),
        RefShape::Own { shape, parameters, bounds: (min, max) } => {
            own(ray, shape, &parameters, min.abs().max(max.abs()).length())
        }
    }
}

/// The reference of one primitive of a registered shape, read as its intersection stage reads
/// it (`twinray_shared::shapes`); `None` for a shape this reference does not know.
pub fn from_primitive(shape: &str, p: &Primitive) -> Option<RefShape> {
    let a = p.a.as_dvec4();
    Some(match shape {
        "sphere" => RefShape::Sphere { center: a.truncate(), radius: a.w },
        "plane" if p.b.x == DISK => RefShape::Disk { radius: a.x },
        "plane" => RefShape::Rectangle { half_x: a.x, half_z: a.y },
        "box" => RefShape::Box { half: a.truncate() },
        "cylinder" => RefShape::Cylinder { radius: a.x, half_height: a.y },
        "cone" => RefShape::Cone { radius: a.x, half_height: a.y },
        "torus" => RefShape::Torus { major: a.x, minor: a.y },
        _ => RefShape::Traced { shape: TRACED.iter().find(|t| t.name == shape)?, a },
    })
}

/// Radius of a sphere about the object's origin that holds the shape.
pub fn bounding_radius(shape: &RefShape) -> f64 {
    match *shape {
        RefShape::Sphere { center, radius } => center.length() + radius,
        RefShape::Rectangle { half_x, half_z } => half_x.hypot(half_z),
        RefShape::Disk { radius } => radius,
        RefShape::Box { half } => half.length(),
        RefShape::Cylinder { radius, half_height } | RefShape::Cone { radius, half_height } => {
            radius.hypot(half_height)
        }
        RefShape::Torus { major, minor } => major + minor,
        RefShape::Triangle { p } => p.iter().map(|v| v.length()).fold(0.0, f64::max),
        RefShape::Traced { shape, a } => (shape.half_extent)(a).length(),
        RefShape::Own { bounds: (min, max), .. } => min.abs().max(max.abs()).length(),
    }
}

/// Roots of a t^2 + 2 half_b t + c (stable form), with `tangent` when the discriminant
/// is within noise of zero.
fn quadratic(a: f64, half_b: f64, c: f64, discriminant: f64) -> Vec<f64> {
    if discriminant < 0.0 || (a == 0.0 && half_b == 0.0) {
        return Vec::new();
    }
    let q = -(half_b + half_b.signum() * discriminant.sqrt());
    let mut roots = Vec::new();
    if q != 0.0 {
        roots.push(c / q);
    }
    if a != 0.0 {
        roots.push(q / a);
    }
    roots
}

fn sphere(ray: &RefRay, center: DVec3, radius: f64) -> Verdict {
    let (o, d) = (ray.origin - center, ray.direction);
    let a = d.dot(d);
    let half_b = o.dot(d);
    let perp = o - d * (half_b / a);
    let miss_by = perp.length() - radius;
    if miss_by.abs() <= ray.tolerance(-half_b / a) {
        return Verdict::Ambiguous;
    }
    let discriminant = a * (radius * radius - perp.dot(perp));
    let c = o.dot(o) - radius * radius;
    let roots = quadratic(a, half_b, c, discriminant);
    let candidates = roots.into_iter().map(|t| Candidate { t, normal: ray.at(t) - center, ambiguous: false }).collect();
    first(ray, candidates)
}

/// The plane y = 0 limited by `inside(p) >= 0` (signed distance to the rim).
fn plane(ray: &RefRay, inside: impl Fn(DVec3) -> f64) -> Verdict {
    let (o, d) = (ray.origin, ray.direction);
    if o.y.abs() <= ray.tolerance(0.0) {
        return Verdict::Ambiguous; // the ray starts in the plane
    }
    if d.y == 0.0 {
        return Verdict::Miss;
    }
    let t = -o.y / d.y;
    let margin = inside(ray.at(t));
    let band = ray.edge_band(t, DVec3::Y);
    if margin < -band {
        return Verdict::Miss;
    }
    first(ray, vec![Candidate { t, normal: DVec3::Y, ambiguous: margin.abs() <= band }])
}

fn aabox(ray: &RefRay, half: DVec3) -> Verdict {
    // Moving the ray sideways by the tolerance is moving every face by it: if the box grown by
    // the tolerance and the box shrunk by it disagree, the ray passes within noise of an edge,
    // a corner, or a face's plane (nearly along the face).
    let reaches = |half: DVec3| slabs(ray, half).filter(|(_, far)| far.0 >= ray.t_min);
    let Some((near, _)) = reaches(half + ray.tolerance(0.0)) else {
        return Verdict::Miss;
    };
    let tol = ray.tolerance(0.0).max(ray.tolerance(near.0.max(0.0)));
    let grown = reaches(half + tol).is_some();
    let shrunk = half.min_element() > tol && reaches(half - tol).is_some();
    match slabs(ray, half) {
        Some((near, far)) if grown == shrunk => first(
            ray,
            vec![
                Candidate { t: near.0, normal: near.1, ambiguous: false },
                Candidate { t: far.0, normal: far.1, ambiguous: false },
            ],
        ),
        None if !grown => Verdict::Miss,
        _ => Verdict::Ambiguous,
    }
}

/// The latest slab entry and earliest exit of the box `half` (t and the normal there), or
/// `None` when the slabs do not overlap.
fn slabs(ray: &RefRay, half: DVec3) -> Option<((f64, DVec3), (f64, DVec3))> {
    let (o, d) = (ray.origin, ray.direction);
    let mut near = (f64::NEG_INFINITY, DVec3::ZERO);
    let mut far = (f64::INFINITY, DVec3::ZERO);
    for axis in 0..3 {
        let (oi, di, hi) = (o[axis], d[axis], half[axis]);
        if di == 0.0 {
            if oi.abs() > hi {
                return None;
            }
            continue;
        }
        let (a, b) = ((-hi - oi) / di, (hi - oi) / di);
        let (t0, t1) = if a <= b { (a, b) } else { (b, a) };
        let unit = DVec3::AXES[axis];
        if t0 > near.0 {
            near = (t0, unit * -di.signum());
        }
        if t1 < far.0 {
            far = (t1, unit * di.signum());
        }
    }
    (near.0 <= far.0).then_some((near, far))
}

fn cylinder(ray: &RefRay, radius: f64, half_height: f64) -> Verdict {
    let (o, d) = (ray.origin, ray.direction);
    let mut candidates = Vec::new();
    let a = d.x * d.x + d.z * d.z;
    let from_axis = (o.x * o.x + o.z * o.z).sqrt();
    // A ray parallel to the axis meets no side, unless it runs along it within noise.
    if a <= 1e-24 * d.dot(d) && (from_axis - radius).abs() <= ray.tolerance(0.0) {
        return Verdict::Ambiguous;
    }
    if a > 1e-24 * d.dot(d) {
        let half_b = o.x * d.x + o.z * d.z;
        let cross = o.x * d.z - o.z * d.x;
        let closest = cross.abs() / a.sqrt(); // distance from the axis at closest approach
                                              // A tangency counts only on the finite side: a ray nearly along the axis (as rotated
                                              // instances make them) grazes the infinite cylinder far beyond the caps.
        let t_closest = -half_b / a;
        let on_side = ray.at(t_closest).y.abs() <= half_height + ray.tolerance(t_closest);
        if on_side && (closest - radius).abs() <= ray.tolerance(t_closest) {
            return Verdict::Ambiguous;
        }
        let discriminant = a * radius * radius - cross * cross;
        for t in quadratic(a, half_b, o.x * o.x + o.z * o.z - radius * radius, discriminant) {
            let p = ray.at(t);
            let rim = half_height - p.y.abs();
            let normal = DVec3::new(p.x, 0.0, p.z);
            let band = ray.edge_band(t, normal);
            if rim >= -band {
                candidates.push(Candidate { t, normal, ambiguous: rim.abs() <= band });
            }
        }
    }
    if d.y != 0.0 {
        for y in [half_height, -half_height] {
            let t = (y - o.y) / d.y;
            let p = ray.at(t);
            let rim = radius - (p.x * p.x + p.z * p.z).sqrt();
            let band = ray.edge_band(t, DVec3::Y);
            if rim >= -band {
                candidates.push(Candidate {
                    t,
                    normal: DVec3::new(0.0, y.signum(), 0.0),
                    ambiguous: rim.abs() <= band,
                });
            }
        }
    }
    first(ray, candidates)
}

fn cone(ray: &RefRay, radius: f64, half_height: f64) -> Verdict {
    let height = 2.0 * half_height;
    let cos2 = height * height / (height * height + radius * radius);
    let apex = DVec3::new(0.0, half_height, 0.0);
    let (d, co) = (ray.direction, ray.origin - apex);
    let (dv, cov) = (-d.y, -co.y);
    let a = dv * dv - cos2 * d.dot(d);
    let half_b = dv * cov - d.dot(co) * cos2;
    let c = cov * cov - co.dot(co) * cos2;
    let discriminant = half_b * half_b - a * c;
    // Tangency: the two intersection points (real or complex) within noise of each other.
    // Tangency: where the implicit function F = (cp.v)^2 - cos^2 |cp|^2 along the ray peaks,
    // F = -disc / a, the ray's distance from the surface is |F| / |grad F|. Only a tangency on
    // the finite nappe, between apex and base, counts.
    if a != 0.0 {
        let t_peak = -half_b / a;
        let cp = ray.at(t_peak) - apex;
        let gradient = (DVec3::new(0.0, cp.y, 0.0) - cp * cos2) * 2.0;
        let depth = (discriminant / a).abs() / gradient.length().max(1e-300);
        let along = -cp.y;
        let tol = ray.tolerance(t_peak);
        if depth <= tol && along >= -tol && along <= height + tol {
            return Verdict::Ambiguous;
        }
    }
    let mut candidates = Vec::new();
    for t in quadratic(a, half_b, c, discriminant) {
        let cp = ray.at(t) - apex;
        let along = -cp.y;
        let normal = cp * cos2 - DVec3::new(0.0, cp.y, 0.0);
        // The band is along the surface; `along` is its share on the axis (times cos).
        let band = ray.edge_band(t, normal);
        if along >= -band && along <= height + band {
            let ambiguous = along.abs() <= band || (along - height).abs() <= band;
            candidates.push(Candidate { t, normal, ambiguous });
        }
    }
    if d.y != 0.0 {
        let t = (-half_height - ray.origin.y) / d.y;
        let p = ray.at(t);
        let rim = radius - (p.x * p.x + p.z * p.z).sqrt();
        let band = ray.edge_band(t, DVec3::Y);
        if rim >= -band {
            candidates.push(Candidate { t, normal: -DVec3::Y, ambiguous: rim.abs() <= band });
        }
    }
    first(ray, candidates)
}

fn triangle(ray: &RefRay, p: [DVec3; 3]) -> Verdict {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let normal = e1.cross(e2);
    let h = ray.direction.cross(e2);
    let det = e1.dot(h);
    let s = ray.origin - p[0];
    if det.abs() <= AMBIGUOUS_ULPS * F32_EPS * e1.length() * h.length() {
        // Within noise of parallel to the plane: in it within noise, or beside it and missing.
        let off_plane = s.dot(normal).abs() / normal.length();
        return if off_plane <= ray.tolerance(0.0) { Verdict::Ambiguous } else { Verdict::Miss };
    }
    let u = s.dot(h) / det;
    let q = s.cross(e1);
    let v = ray.direction.dot(q) / det;
    let t = e2.dot(q) / det;
    let edge = u.min(v).min(1.0 - u - v);
    // Barycentric units: distance over the triangle's size, sqrt(2 area).
    let tol = ray.edge_band(t, normal) / normal.length().sqrt().max(1e-30);
    if edge < -tol {
        return Verdict::Miss;
    }
    first(ray, vec![Candidate { t, normal, ambiguous: edge.abs() <= tol }])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> RefRay {
        RefRay { origin: DVec3::from(o), direction: DVec3::from(d), t_min: 0.0, t_max: 1e30, noise_floor: 0.0 }
    }

    fn t_of(v: Verdict) -> f64 {
        match v {
            Verdict::Hit { t, .. } => t,
            other => panic!("expected a hit, got {other:?}"),
        }
    }

    #[test]
    fn known_answers() {
        let s = RefShape::Sphere { center: DVec3::ZERO, radius: 1.0 };
        assert_eq!(t_of(intersect(&s, &ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]))), 4.0);
        assert_eq!(intersect(&s, &ray([0.0, 2.0, -5.0], [0.0, 0.0, 1.0])), Verdict::Miss);
        assert_eq!(intersect(&s, &ray([0.0, 1.0, -5.0], [0.0, 0.0, 1.0])), Verdict::Ambiguous, "tangent");
        let b = RefShape::Box { half: DVec3::new(1.0, 2.0, 3.0) };
        assert_eq!(t_of(intersect(&b, &ray([-5.0, 0.5, 0.5], [1.0, 0.0, 0.0]))), 4.0);
        assert_eq!(intersect(&b, &ray([-5.0, 2.0, 0.0], [1.0, 0.0, 0.0])), Verdict::Ambiguous, "in a face plane");
        let c = RefShape::Cylinder { radius: 1.0, half_height: 2.0 };
        assert_eq!(t_of(intersect(&c, &ray([0.5, 5.0, 0.0], [0.0, -1.0, 0.0]))), 3.0);
        let k = RefShape::Cone { radius: 1.0, half_height: 1.0 };
        assert!((t_of(intersect(&k, &ray([-5.0, 0.0, 0.0], [1.0, 0.0, 0.0]))) - 4.5).abs() < 1e-12);
        let r = RefShape::Rectangle { half_x: 1.0, half_z: 1.0 };
        assert_eq!(t_of(intersect(&r, &ray([0.5, 2.0, 0.5], [0.0, -1.0, 0.0]))), 2.0);
        let tri = RefShape::Triangle { p: [DVec3::ZERO, DVec3::X, DVec3::Y] };
        assert_eq!(t_of(intersect(&tri, &ray([0.2, 0.2, -1.0], [0.0, 0.0, 1.0]))), 1.0);
    }

    #[test]
    fn torus_by_sphere_tracing_matches_the_closed_form() {
        let t = RefShape::Torus { major: 1.0, minor: 0.25 };
        for y in [-0.2f64, 0.0, 0.1, 0.24] {
            let exact = 5.0 - 1.0 - (0.0625 - y * y).sqrt();
            let got = t_of(intersect(&t, &ray([-5.0, y, 0.0], [1.0, 0.0, 0.0])));
            assert!((got - exact).abs() < 1e-12 * exact, "y {y}: {got} vs {exact}");
        }
        assert_eq!(intersect(&t, &ray([0.0, 5.0, 0.0], [0.0, -1.0, 0.0])), Verdict::Miss, "through the hole");
        assert_eq!(intersect(&t, &ray([-5.0, 0.25, 0.0], [1.0, 0.0, 0.0])), Verdict::Ambiguous, "grazing the top");
    }
}
