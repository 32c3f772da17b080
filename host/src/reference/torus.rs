//! The torus of the f64 reference: sphere tracing its exact signed distance and bisecting the
//! sign change, so that a quartic-solver bug cannot hide in both this and the shaders.

use super::ray::{first, Candidate, RefRay, Verdict};
use glam::DVec3;

/// Signed distance to the torus (exact, so sphere tracing never steps past the surface).
fn torus_distance(p: DVec3, major: f64, minor: f64) -> f64 {
    let ring = (p.x * p.x + p.z * p.z).sqrt() - major;
    (ring * ring + p.y * p.y).sqrt() - minor
}

pub(super) fn torus(ray: &RefRay, major: f64, minor: f64) -> Verdict {
    let length = ray.direction.length();
    let g = |t: f64| torus_distance(ray.at(t), major, minor);
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
            let p = ray.at(root);
            let ring = DVec3::new(p.x, 0.0, p.z).normalize() * major;
            let grazed = closest_pass <= tol || (!inside && shallow(&g, root, tol, length));
            return first(ray, vec![Candidate { t: root, normal: p - ring, ambiguous: grazed }]);
        }
        if dist > previous {
            closest_pass = closest_pass.min(previous);
        }
        previous = dist;
        let p = ray.at(t);
        let leaving = !inside && p.length() > major + minor && p.dot(ray.direction) > 0.0;
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
