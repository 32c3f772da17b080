//! Rays of the f64 reference and how an answer is chosen among candidate roots: what counts
//! as float noise for a ray, and when a root is ambiguous.

use glam::DVec3;

/// f32 ULPs of the ray's magnitude that count as "within float noise".
pub const AMBIGUOUS_ULPS: f64 = 16.0;
pub(super) const F32_EPS: f64 = 1.0 / 16_777_216.0;

/// A ray of the f64 reference, in the shape's own space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefRay {
    pub origin: DVec3,
    pub direction: DVec3,
    pub t_min: f64,
    pub t_max: f64,
    /// Smallest coordinate magnitude that counts for float noise (0 for a ray given in the
    /// shape's own space). A ray reaching the shape through an instance transform is rounded
    /// at the magnitude of its world-space coordinates, however small the object-space ones.
    pub noise_floor: f64,
}

/// The true answer for one ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// No hit in [t_min, t_max].
    Miss,
    /// The first hit in [t_min, t_max] and the outward unit normal there.
    Hit { t: f64, normal: DVec3 },
    /// Within float noise of a boundary case: either answer is right.
    Ambiguous,
}

impl RefRay {
    /// Distance that counts as float noise for this ray: ULPs of its coordinates' magnitude.
    pub(super) fn tolerance(&self, t: f64) -> f64 {
        let scale = self.origin.abs().max_element().max(self.at(t).abs().max_element()).max(self.noise_floor);
        AMBIGUOUS_ULPS * F32_EPS * scale.max(1e-30)
    }

    /// How far from a rim or edge a hit at `t` on a surface with `normal` is within noise:
    /// moving the ray sideways by the tolerance moves the hit along the surface by the
    /// tolerance over the cosine between ray and normal, so grazing hits have wide bands.
    pub(super) fn edge_band(&self, t: f64, normal: DVec3) -> f64 {
        let cosine = self.direction.normalize().dot(normal.normalize()).abs();
        self.tolerance(t) / cosine.max(1e-12)
    }

    pub(super) fn at(&self, t: f64) -> DVec3 {
        self.origin + self.direction * t
    }
}

/// One candidate root: its parameter, its normal, and whether it sits on a boundary.
#[derive(Clone, Copy)]
pub(super) struct Candidate {
    pub t: f64,
    pub normal: DVec3,
    pub ambiguous: bool,
}

/// The first candidate in [t_min, t_max], or `Ambiguous` if a candidate within noise of t_min
/// or t_max, or a boundary candidate, could be the first.
pub(super) fn first(ray: &RefRay, mut candidates: Vec<Candidate>) -> Verdict {
    candidates.sort_by(|a, b| a.t.total_cmp(&b.t));
    for c in candidates {
        let tol_t = ray.tolerance(c.t) / ray.direction.length();
        if c.t < ray.t_min - tol_t {
            continue;
        }
        if c.ambiguous || (c.t - ray.t_min).abs() <= tol_t || (c.t - ray.t_max).abs() <= tol_t {
            return Verdict::Ambiguous;
        }
        if c.t > ray.t_max {
            return Verdict::Miss;
        }
        return Verdict::Hit { t: c.t, normal: c.normal.normalize() };
    }
    Verdict::Miss
}
