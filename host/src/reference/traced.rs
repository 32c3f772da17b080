//! Shapes the f64 reference finds by sphere tracing an exact signed distance and bisecting the
//! sign change: the torus, and any shape of [`TRACED`]. A distance function is a few lines
//! and shares no formula with a shape's intersection routine, so a root-solver bug cannot
//! hide in both this and the shaders.

use super::ray::{first, Candidate, RefRay, Verdict};
use crate::sets::own::OwnShapeRef;
use glam::{DVec3, DVec4};
use twinray_shared::custom::Parameters;

/// A shape the reference knows by its signed distance. The three functions take a point in
/// the shape's own space and `a`, its primitive's first vector (`Primitive::a`, read as the
/// shape's intersection stage reads it).
#[derive(Debug)]
pub struct TracedShape {
    /// The registered shape's name (`twinray_shared::shapes`).
    pub name: &'static str,
    /// Signed distance to the surface, negative inside. It must be exact, or at least never
    /// more than the true distance, so that sphere tracing never steps past the surface.
    pub distance: fn(p: DVec3, a: DVec4) -> f64,
    /// The outward normal at a point of the surface (any length).
    pub normal: fn(p: DVec3, a: DVec4) -> DVec3,
    /// Half extents of a box about the origin that holds the shape.
    pub half_extent: fn(a: DVec4) -> DVec3,
}

impl PartialEq for TracedShape {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

/// The shapes the reference finds by their distance (the others are in `shapes.rs`). A shape
/// added with `cargo xtask new-shape` gets its reference here: a distance, a normal and a box.
pub const TRACED: &[TracedShape] = &[
    // A shape of your own: its `TracedShape { .. }` here (docs/tutorial.md adds a capsule).
];

/// Signed distance to the torus about y (exact).
fn torus_distance(p: DVec3, major: f64, minor: f64) -> f64 {
    let ring = (p.x * p.x + p.z * p.z).sqrt() - major;
    (ring * ring + p.y * p.y).sqrt() - minor
}

pub(super) fn torus(ray: &RefRay, major: f64, minor: f64) -> Verdict {
    let normal = |p: DVec3| p - DVec3::new(p.x, 0.0, p.z).normalize() * major;
    trace(ray, |p| torus_distance(p, major, minor), normal, major + minor)
}

/// The shape of [`TRACED`] with primitive `a`.
pub(super) fn traced(ray: &RefRay, shape: &TracedShape, a: DVec4) -> Verdict {
    let bound = (shape.half_extent)(a).length();
    trace(ray, |p| (shape.distance)(p, a), |p| (shape.normal)(p, a), bound)
}

/// A crate's own shape: its distance and normal as the crate defines them, in a sphere of
/// radius `bound` about the origin.
pub(super) fn own(ray: &RefRay, shape: OwnShapeRef, parameters: &Parameters, bound: f64) -> Verdict {
    trace(ray, |p| shape.distance(parameters, p), |p| shape.normal(parameters, p), bound)
}

/// The first crossing of `distance`'s zero along the ray, with `normal` there; `bound` is the
/// radius of a sphere about the origin that holds the surface.
fn trace(ray: &RefRay, distance: impl Fn(DVec3) -> f64, normal: impl Fn(DVec3) -> DVec3, bound: f64) -> Verdict {
    let length = ray.direction.length();
    let g = |t: f64| distance(ray.at(t));
    let mut t = ray.t_min;
    let inside = g(t) < 0.0;
    // Smallest distance at which the path passed the tube and moved away again: a graze.
    let mut closest_pass = f64::INFINITY;
    let mut previous = f64::INFINITY;
    for _ in 0..100_000 {
        let dist = g(t).abs();
        let tol = ray.tolerance(t);
        if dist <= tol * 1e-3 {
            // Converged onto the surface (an exact distance never steps across it): bracket
            // the crossing just beyond, doubling the step until the sign changes.
            let mut hi = t + tol / length;
            for _ in 0..60 {
                if (g(hi) < 0.0) != inside {
                    break;
                }
                hi = t + (hi - t) * 2.0;
            }
            if (g(hi) < 0.0) == inside {
                return Verdict::Ambiguous; // touched without crossing: tangent
            }
            let root = bisect(&g, t, hi, inside);
            let grazed = closest_pass <= tol || (!inside && shallow(&g, root, tol, length));
            return first(ray, vec![Candidate { t: root, normal: normal(ray.at(root)), ambiguous: grazed }]);
        }
        if dist > previous {
            closest_pass = closest_pass.min(previous);
        }
        previous = dist;
        let p = ray.at(t);
        let leaving = !inside && p.length() > bound && p.dot(ray.direction) > 0.0;
        if t > ray.t_max || leaving {
            break;
        }
        t += dist.max(tol * 1e-3) / length;
    }
    if closest_pass.min(previous) <= ray.tolerance(t.min(ray.t_max)) {
        Verdict::Ambiguous
    } else {
        Verdict::Miss
    }
}

/// Whether a ray entering at `entry` stays within `tol` of the surface until it leaves: a
/// graze through the tube, which a sideways move by the tolerance could turn into a miss.
/// Sphere tracing inside (steps of |g|, at least a thousandth of the tolerance) samples the
/// depth until it exceeds `tol` or the ray leaves.
fn shallow(g: &impl Fn(f64) -> f64, entry: f64, tol: f64, length: f64) -> bool {
    let mut t = entry + tol / length;
    for _ in 0..100_000 {
        let depth = -g(t);
        if depth > tol {
            return false;
        }
        if depth < 0.0 {
            return true;
        }
        t += depth.max(tol * 1e-3) / length;
    }
    true
}

/// The sign change of g between `lo` and `hi` (g(lo) on the `inside` side), to f64 precision.
fn bisect(g: &impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, inside: bool) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if (g(mid) < 0.0) == inside {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere known only by its distance, as a shape of `TRACED` is.
    const BALL: TracedShape = TracedShape {
        name: "ball",
        distance: |p, a| p.length() - a.x,
        normal: |p, _| p,
        half_extent: |a| DVec3::splat(a.x),
    };

    fn ray(origin: DVec3, direction: DVec3) -> RefRay {
        RefRay { origin, direction, t_min: 0.0, t_max: 1e30, noise_floor: 0.0 }
    }

    #[test]
    fn a_shape_known_by_its_distance_matches_the_closed_form() {
        let a = DVec4::new(2.0, 0.0, 0.0, 0.0);
        for (y, far) in [(0.0, 10.0), (1.5, 10.0), (0.5, 1.0e4)] {
            let exact = far - (4.0f64 - y * y).sqrt();
            match traced(&ray(DVec3::new(0.0, y, -far), DVec3::Z), &BALL, a) {
                Verdict::Hit { t, normal } => {
                    assert!((t - exact).abs() <= 1e-12 * far, "y {y} at {far}: t {t}, not {exact}");
                    assert!((normal - ray(DVec3::new(0.0, y, -far), DVec3::Z).at(t) / 2.0).length() < 1e-9);
                }
                other => panic!("y {y} at {far}: {other:?}"),
            }
        }
        assert_eq!(traced(&ray(DVec3::new(0.0, 2.5, -10.0), DVec3::Z), &BALL, a), Verdict::Miss);
        assert_eq!(traced(&ray(DVec3::new(0.0, 2.0, -10.0), DVec3::Z), &BALL, a), Verdict::Ambiguous, "tangent");
        let inside = traced(&ray(DVec3::ZERO, DVec3::X), &BALL, a);
        assert!(matches!(inside, Verdict::Hit { t, .. } if (t - 2.0).abs() < 1e-12), "{inside:?}");
    }
}
