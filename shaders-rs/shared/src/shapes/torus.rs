//! Torus about the object's y axis, centred at its origin: ring radius R = `a.x` in the xz
//! plane, tube radius r = `a.y`. The recipe of twinray's guide, *Numerics*: work with R = 1 and a unit
//! direction; move the origin along the ray onto the bounding sphere of radius R + 2r (not
//! R + r: grazing rays would be lost); solve the quartic from there with Inigo Quilez's closed
//! form; add the shift back; polish each root with Newton steps on the distance function
//! g(p) = |(|p_xz| - 1, p_y)| - r.
//!
//! Two additions for thin tubes (r/R down to 1e-3), where the f32 quartic's coefficients are
//! too coarse (its features are r^2 against terms of 1) to tell a near miss from a hit:
//! - a polished root counts only if g there is within `ROOT_TOLERANCE` of 0, which drops the
//!   quartic's phantom roots (false hits);
//! - near the two places where the ray passes closest to the ring circle (found by Newton steps
//!   on the squared distance to it), the ray hits if that distance is below r, decided by g
//!   alone, and the entry and exit there come from a parabola of that distance, polished like
//!   the quartic's roots (the roots the quartic lost: false misses).
//!
//! One change to the recipe: the origin moves to the sphere's entry point even when that lies
//! behind it (max(0, entry), the usual form, keeps origins inside the sphere). A ray starting on
//! the torus, as every shadow ray from it does, would otherwise give the quartic a root at 0
//! (k0 = 0), which the solver's 1/t branch divides by; from the entry point the self root is
//! an ordinary root, found accurately and then dropped.

use super::sphere;
use super::uv::{around_y, ShapeUv};
use crate::layout::Primitive;
use crate::surface::{Nearest, SurfaceHit};
use glam::{Vec2, Vec3, Vec4};
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

/// Relative distance from the surface, |g| / r, under which a ray's origin lies on the torus
/// (a shadow ray leaving it): the root nearest 0 is then its own origin, not a hit.
pub const ON_SURFACE: f32 = 1.0e-3;
/// Largest |g| at a polished root, relative to the magnitude of its point (R = 1): 8 f32
/// ULPs. A candidate farther from the surface is no root.
pub const ROOT_TOLERANCE: f32 = 8.0 * f32::EPSILON;
/// For a ray that starts on the surface, roots within this many tube radii of its origin are
/// the origin itself.
pub const SELF_BAND: f32 = 4.0 * ON_SURFACE;

/// Roots of the torus quartic for a unit-direction ray from `o` (R = 1, tube radius `r`), in
/// the ray's parameter; up to four, as (valid, value) pairs.
fn quartic_roots(o: Vec3, d: Vec3, r: f32) -> [(bool, f32); 4] {
    let none = [(false, 0.0); 4];
    let m = o.dot(o);
    let n = o.dot(d);
    let k = (m - r * r - 1.0) / 2.0;
    let mut k3 = n;
    let mut k2 = n * n + d.y * d.y + k;
    let mut k1 = k * n + o.y * d.y;
    let mut k0 = k * k + o.y * o.y - r * r;
    // Keep |c1| away from zero by solving for 1/t when it is small.
    let inverted = (k3 * (k3 * k3 - k2) + k1).abs() < 0.01;
    if inverted {
        core::mem::swap(&mut k1, &mut k3);
        k0 = 1.0 / k0;
        k1 *= k0;
        k2 *= k0;
        k3 *= k0;
    }
    let c2 = (2.0 * k2 - 3.0 * k3 * k3) / 3.0;
    let c1 = 2.0 * (k3 * (k3 * k3 - k2) + k1);
    let c0 = (k3 * (k3 * (-3.0 * k3 * k3 + 4.0 * k2) - 8.0 * k1) + 4.0 * k0) / 3.0;
    let q = c2 * c2 + c0;
    let rr = 3.0 * c0 * c2 - c2 * c2 * c2 - c1 * c1;
    let h = rr * rr - q * q * q;
    let z = if h < 0.0 {
        let sq = q.sqrt();
        2.0 * sq * ((rr / (sq * q)).acos() / 3.0).cos()
    } else {
        let sq = (h.sqrt() + rr.abs()).powf(1.0 / 3.0);
        let sign = if rr > 0.0 {
            1.0
        } else if rr < 0.0 {
            -1.0
        } else {
            0.0
        };
        sign * (sq + q / sq).abs()
    };
    let z = c2 - z;
    let mut d1 = z - 3.0 * c2;
    let mut d2 = z * z - 3.0 * c0;
    if d1.abs() < 1.0e-4 {
        if d2 < 0.0 {
            return none;
        }
        d2 = d2.sqrt();
    } else {
        if d1 < 0.0 {
            return none;
        }
        d1 = (d1 / 2.0).sqrt();
        d2 = c1 / d1;
    }
    let undo = |t: f32| if inverted { 2.0 / t } else { t };
    let mut roots = none;
    let h1 = d1 * d1 - z + d2;
    if h1 > 0.0 {
        let s = h1.sqrt();
        roots[0] = (true, undo(-d1 - s - k3));
        roots[1] = (true, undo(-d1 + s - k3));
    }
    let h2 = d1 * d1 - z - d2;
    if h2 > 0.0 {
        let s = h2.sqrt();
        roots[2] = (true, undo(d1 - s - k3));
        roots[3] = (true, undo(d1 + s - k3));
    }
    roots
}

/// Signed distance from `p` to the torus (R = 1, tube radius `r`), and its gradient.
fn distance(p: Vec3, r: f32) -> (f32, Vec3) {
    let ring = (p.x * p.x + p.z * p.z).sqrt();
    let radial = ring - 1.0;
    let g = (radial * radial + p.y * p.y).sqrt();
    let grad =
        if ring > 0.0 && g > 0.0 { Vec3::new(p.x / ring * radial, p.y, p.z / ring * radial) / g } else { Vec3::Y };
    (g - r, grad)
}

/// One Newton step on g from `s`.
fn polish_step(o: Vec3, d: Vec3, r: f32, s: f32) -> f32 {
    let (g, grad) = distance(o + d * s, r);
    let slope = grad.dot(d);
    if slope.abs() > 1.0e-6 {
        s - g / slope
    } else {
        s
    }
}

/// `s` moved onto the surface along the ray by Newton steps on g (written out, not a loop:
/// see twinray's guide, *Rust stages* on loops NVIDIA's driver miscompiles).
fn polish(o: Vec3, d: Vec3, r: f32, s: f32) -> f32 {
    let s = polish_step(o, d, r, s);
    let s = polish_step(o, d, r, s);
    polish_step(o, d, r, s)
}

/// One Newton step towards a local minimum of D(s) = (ring - 1)^2 + y^2 - r^2, the squared
/// distance from the ray's point to the ring circle less r^2: on D'/2 and D''/2.
fn approach_step(o: Vec3, d: Vec3, s: f32) -> f32 {
    let p = o + d * s;
    let ring = (p.x * p.x + p.z * p.z).sqrt();
    if ring <= 0.0 {
        return s;
    }
    let ring1 = (p.x * d.x + p.z * d.z) / ring;
    let ring2 = (d.x * d.x + d.z * d.z - ring1 * ring1) / ring;
    let radial = ring - 1.0;
    let slope = radial * ring1 + p.y * d.y;
    let curvature = ring1 * ring1 + radial * ring2 + d.y * d.y;
    if curvature > 0.0 {
        s - slope / curvature
    } else {
        s
    }
}

/// Where near `s` the ray passes closest to the ring circle.
fn closest_approach(o: Vec3, d: Vec3, s: f32) -> f32 {
    let s = approach_step(o, d, s);
    let s = approach_step(o, d, s);
    let s = approach_step(o, d, s);
    approach_step(o, d, s)
}

/// Where the ray's projection on the ring's plane crosses the ring (or passes nearest it,
/// or where the ray crosses the plane when it runs along the axis): the two places near which
/// the ray passes closest to the ring circle.
fn ring_crossings(o: Vec3, d: Vec3) -> (f32, f32) {
    let flat = d.x * d.x + d.z * d.z;
    if flat < 1.0e-6 {
        let s = -o.y * d.y;
        return (s, s);
    }
    let nearest = -(o.x * d.x + o.z * d.z) / flat;
    let (x, z) = (o.x + d.x * nearest, o.z + d.z * nearest);
    let half = ((1.0 - x * x - z * z) / flat).max(0.0).sqrt();
    (nearest - half, nearest + half)
}

/// What turning a guess of a root into a hit needs.
struct Candidate {
    o: Vec3,
    d: Vec3,
    start: Vec3,
    r: f32,
    shift: f32,
    to_t: f32,
    on_surface: bool,
    t_min: f32,
    /// Newton steps on each root, and the check that it lies on the surface (off only in the
    /// naive variant).
    polish: bool,
}

impl Candidate {
    /// Takes into `best` the root that `guess` (from `start`) polishes to, if it lies on the
    /// surface and is a nearer hit in range (and not the ray's own origin when it starts on it).
    fn consider(&self, best: &mut Nearest, (valid, guess): (bool, f32)) {
        if !valid {
            return;
        }
        let s = if self.polish { polish(self.start, self.d, self.r, guess) } else { guess };
        if self.polish {
            // A root of the f32 quartic that is no root of g: for a thin tube the quartic's
            // coefficients are too coarse to tell a near miss from a hit; g is not.
            let p = self.start + self.d * s;
            let g = distance(p, self.r).0;
            let on_surface = g.abs() <= ROOT_TOLERANCE * p.length().max(1.0);
            if !on_surface {
                return;
            }
        }
        let s = s + self.shift;
        if self.on_surface && s.abs() <= SELF_BAND * self.r {
            return;
        }
        let t = s * self.to_t;
        // Checked before the normal is made, which only a hit taken needs.
        if t >= self.t_min && t <= best.limit() {
            let p = self.o + self.d * s;
            let ring = Vec3::new(p.x, 0.0, p.z).normalize();
            best.take(SurfaceHit { t, normal: p - ring });
        }
    }

    /// Takes into `best` the entry or exit of the tube near `around`, where the ray passes
    /// closest to the ring: found from the distance function alone, they catch the roots a
    /// thin tube's quartic loses.
    fn consider_approach(&self, best: &mut Nearest, around: f32) {
        let s = closest_approach(self.start, self.d, around);
        let p = self.start + self.d * s;
        let ring = (p.x * p.x + p.z * p.z).sqrt();
        let dist = ((ring - 1.0) * (ring - 1.0) + p.y * p.y).sqrt();
        if dist >= self.r {
            return;
        }
        // D is nearly a parabola about its minimum: D(s) = D(m) + D''(m)/2 (s - m)^2.
        let ring1 = if ring > 0.0 { (p.x * self.d.x + p.z * self.d.z) / ring } else { 0.0 };
        let ring2 = if ring > 0.0 { (self.d.x * self.d.x + self.d.z * self.d.z - ring1 * ring1) / ring } else { 0.0 };
        let curvature = (ring1 * ring1 + (ring - 1.0) * ring2 + self.d.y * self.d.y).max(1.0e-12);
        let half = ((self.r - dist) * (self.r + dist) / curvature).sqrt();
        self.consider(best, (true, s - half));
        self.consider(best, (true, s + half));
    }
}

/// The nearest hit of the ray (`origin`, `direction`, object space) on the torus `primitive`
/// (a.x ring radius, a.y tube radius) with t in [`t_min`, `t_max`], or `None`.
pub fn intersect(origin: Vec3, direction: Vec3, primitive: &Primitive, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    let (big_r, small_r) = (primitive.a.x, primitive.a.y);
    let r = small_r / big_r;
    let length = direction.length();
    let d = direction / length;
    let o = origin / big_r;
    // Ray parameter s in the scaled space, with t = s * R / |d|.
    let to_t = big_r / length;
    let bound = sphere::roots(o, d, Vec3::ZERO, 1.0 + 2.0 * r);
    if !bound.hit || bound.far < 0.0 {
        return None;
    }
    let shift = bound.near;
    let start = o + d * shift;
    let on_surface = distance(o, r).0.abs() <= ON_SURFACE * r;
    // The four roots one by one, not by index: rust-gpu turns an index's bounds-check panic
    // path inside a loop into control flow NVIDIA's driver miscompiles (see the shaders' trace.rs).
    let [r0, r1, r2, r3] = quartic_roots(start, d, r);
    let candidate = Candidate { o, d, start, r, shift, to_t, on_surface, t_min, polish: true };
    let mut best = Nearest::new(t_min, t_max);
    candidate.consider(&mut best, r0);
    candidate.consider(&mut best, r1);
    candidate.consider(&mut best, r2);
    candidate.consider(&mut best, r3);
    let (near, far) = ring_crossings(start, d);
    candidate.consider_approach(&mut best, near);
    candidate.consider_approach(&mut best, far);
    best.hit()
}

/// The quartic solved from the ray's own origin, without the shift onto the bounding sphere,
/// without polish and without self-root rejection. Kept on purpose: on lavapipe it gets 544,
/// 782 and 692 of about 2300 decided rays wrong from 40, 400 and 4000 away (twinray's guide, *Numerics*,
/// `torus-far-*`).
pub fn naive_intersect(
    origin: Vec3,
    direction: Vec3,
    primitive: &Primitive,
    t_min: f32,
    t_max: f32,
) -> Option<SurfaceHit> {
    let (big_r, small_r) = (primitive.a.x, primitive.a.y);
    let r = small_r / big_r;
    let length = direction.length();
    let d = direction / length;
    let o = origin / big_r;
    let to_t = big_r / length;
    let [r0, r1, r2, r3] = quartic_roots(o, d, r);
    let candidate = Candidate { o, d, start: o, r, shift: 0.0, to_t, on_surface: false, t_min, polish: false };
    let mut best = Nearest::new(t_min, t_max);
    candidate.consider(&mut best, r0);
    candidate.consider(&mut best, r1);
    candidate.consider(&mut best, r2);
    candidate.consider(&mut best, r3);
    best.hit()
}

/// The texture coordinates at `p` (`shapes::uv`): u by the turn about y, v by the turn about
/// the tube, 0.5 on the outer equator and growing downwards there (the seam on the inner
/// equator).
pub fn uv(primitive: &Primitive, p: Vec3, _n: Vec3) -> ShapeUv {
    let (u, du) = around_y(p);
    let rho = (p.x * p.x + p.z * p.z).max(1.0e-30).sqrt();
    let out = rho - primitive.a.x;
    let psi = p.y.atan2(out);
    // The gradient of psi = atan2(y, rho - R).
    let d_psi = (Vec3::Y * out - Vec3::new(p.x, 0.0, p.z) * (p.y / rho)) / (out * out + p.y * p.y).max(1.0e-30);
    let turn = 0.5 / core::f32::consts::PI;
    ShapeUv { uv: Vec2::new(u, 0.5 - psi * turn), du, dv: -d_psi * turn }
}

/// The sphere the primitive lies in (xyz: centre, w: radius, object space): where
/// `transform::stage_ray` brings a ray that starts far from it, before the transform.
pub fn bound(primitive: &Primitive) -> Vec4 {
    Vec4::new(0.0, 0.0, 0.0, primitive.a.x + primitive.a.y)
}

/// The torus's scene kind: about the object's y axis, centred at its origin.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPE: super::spec::ShapeSpec = super::spec::ShapeSpec {
    kinds: &[super::spec::ShapeKind {
        name: "torus",
        about: "a torus about the y axis: ring radius `major_radius` in the xz plane, tube radius `minor_radius`",
        params: &[super::spec::Param::positive("major_radius"), super::spec::Param::positive("minor_radius")],
        relations: "`minor_radius` < `major_radius`",
        check: |v| {
            let (major, minor) = (v.number("major_radius"), v.number("minor_radius"));
            if minor >= major {
                return Err(format!(
                    "minor_radius must be < major_radius (got {minor} >= {major}): a spindle torus is not supported"
                ));
            }
            Ok(())
        },
        count: super::spec::one,
        primitives: |v| {
            let (major, minor) = (v.number("major_radius"), v.number("minor_radius"));
            let outer = major + minor;
            super::spec::single(glam::Vec4::new(major, minor, 0.0, 0.0), Vec3::new(outer, minor, outer))
        },
        mitsuba: |v| super::mitsuba::torus(v.number("major_radius"), v.number("minor_radius")),
    }],
    glsl_constants: &[
        ("TORUS_ON_SURFACE", ON_SURFACE),
        ("TORUS_ROOT_TOLERANCE", ROOT_TOLERANCE),
        ("TORUS_SELF_BAND", SELF_BAND),
    ],
};

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    fn torus(big: f32, small: f32) -> Primitive {
        Primitive { a: Vec4::new(big, small, 0.0, 0.0), b: Vec4::ZERO, tint: Vec4::ONE }
    }

    #[test]
    fn hits_the_tube_in_front() {
        // Along the x axis at height 0: tube surfaces at x = -1.25, -0.75, 0.75, 1.25.
        let hit = intersect(Vec3::new(-5.0, 0.0, 0.0), Vec3::X, &torus(1.0, 0.25), 0.0, 100.0).unwrap();
        assert!((hit.t - 3.75).abs() < 1e-5, "{}", hit.t);
        assert!(hit.normal.x < 0.0);
        // Through the hole, along y: no hit.
        assert!(intersect(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y, &torus(1.0, 0.25), 0.0, 100.0).is_none());
    }

    /// Seen from far away, the unshifted quartic gets 24-34% of rays wrong
    /// (twinray's guide, *Numerics*, `torus-far-*`); with the shift and the polish the answer matches the exact one, and t is
    /// relatively accurate.
    #[test]
    fn far_camera_keeps_hit_miss_and_t() {
        for distance in [40.0f32, 400.0, 4000.0] {
            for i in 0..201 {
                let y = -0.4 + 0.8 * i as f32 / 200.0;
                if (y.abs() - 0.25).abs() < 1e-3 {
                    continue; // within float noise of tangency
                }
                let o = Vec3::new(-distance, y, 0.0);
                let hit = intersect(o, Vec3::X, &torus(1.0, 0.25), 0.0, 2.0 * distance);
                assert_eq!(hit.is_some(), y.abs() < 0.25, "y {y} at {distance}");
                if let Some(h) = hit {
                    let exact = f64::from(distance) - 1.0 - (0.0625 - f64::from(y) * f64::from(y)).sqrt();
                    let rel = (f64::from(h.t) - exact).abs() / exact;
                    assert!(rel < 1e-5, "relative error {rel} at y {y}, distance {distance}");
                }
            }
        }
    }

    #[test]
    fn scaled_instance_direction_keeps_ray_parameter() {
        let hit = intersect(Vec3::new(-5.0, 0.0, 0.0), Vec3::X * 2.0, &torus(1.0, 0.25), 0.0, 100.0).unwrap();
        assert!((hit.t - 1.875).abs() < 1e-5, "{}", hit.t);
    }

    /// Shadow rays from points all over the tube, leaving within 60 degrees of the normal:
    /// none may hit the torus at its own origin (a hit across the hole is far away).
    #[test]
    fn rays_leaving_anywhere_on_the_tube_never_self_hit() {
        let (big, small) = (0.7f32, 0.25f32);
        let mut self_hits = 0;
        for i in 0..2000u32 {
            let u = crate::random::random(1, i, 0, 0) * std::f32::consts::TAU;
            let v = crate::random::random(1, i, 0, 1) * std::f32::consts::TAU;
            let center = Vec3::new(u.cos(), 0.0, u.sin()) * big;
            let n = Vec3::new(u.cos() * v.cos(), v.sin(), u.sin() * v.cos());
            let p = crate::offset::offset_ray(center + n * small, n);
            let tilt = Vec3::new(crate::random::random(1, i, 0, 2), crate::random::random(1, i, 0, 3), 0.5) - 0.5;
            let d = (n + tilt).normalize();
            if let Some(hit) = intersect(p, d, &torus(big, small), 0.0, 100.0) {
                if hit.t < 1e-3 * small {
                    self_hits += 1;
                }
            }
        }
        assert_eq!(self_hits, 0, "of 2000 rays leaving the surface");
    }

    #[test]
    fn rays_leaving_the_outer_surface_miss() {
        for k in 0..200 {
            let a = k as f32 * 0.031;
            let n = Vec3::new(a.cos(), 0.0, a.sin());
            let p = crate::offset::offset_ray(n * 1.25, n);
            assert!(intersect(p, (n + Vec3::Y * 0.2).normalize(), &torus(1.0, 0.25), 0.0, 100.0).is_none(), "{k}");
        }
    }
}
