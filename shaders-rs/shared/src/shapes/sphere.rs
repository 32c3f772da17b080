//! Ray/sphere intersection in the cancellation-free form of Ray Tracing Gems ch. 7
//! (Haines, Günther, Akenine-Möller); see twinray's guide, *Numerics*. Valid for any non-zero direction
//! length, so scaled instances work.

use super::uv::{around_y, ShapeUv};
use crate::layout::Primitive;
use crate::surface::SurfaceHit;
use glam::{Vec2, Vec3, Vec4};
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

/// Relative distance from the surface, |c| / r^2 (c = |o - C|^2 - r^2), under which a ray's
/// origin counts as lying on the sphere. Such a ray, a shadow ray leaving the surface, has
/// one root at its own origin that rounding may put at a small positive t: that root is not a
/// hit (twinray's guide, *Numerics*, `sphere-surface-far`: without it, 204 of 1622 decided shadow rays
/// hit their own sphere on lavapipe). A ray 256 ULPs off the surface, as
/// the Ray Tracing Gems offset places it, is well inside this band at any magnitude.
pub const ON_SURFACE: f32 = 1.0e-3;

/// The two ray parameters where a ray meets a sphere, `near <= far`; meaningless if `!hit`.
#[derive(Clone, Copy)]
pub struct SphereRoots {
    /// Whether the ray's line meets the sphere.
    pub hit: bool,
    /// The nearer ray parameter.
    pub near: f32,
    /// The farther ray parameter.
    pub far: f32,
    /// The ray starts on the surface: the root nearer to t = 0 is the origin itself.
    pub on_surface: bool,
}

/// Where the ray `origin + t * direction` meets the sphere of `center` and `radius`.
pub fn roots(origin: Vec3, direction: Vec3, center: Vec3, radius: f32) -> SphereRoots {
    let f = origin - center;
    let a = direction.dot(direction);
    let half_b = f.dot(direction);
    let c = f.dot(f) - radius * radius;
    // b'^2 - ac written as a * (r^2 - |f_perp|^2): no cancellation when the sphere is far away.
    let f_perp = f - direction * (half_b / a);
    let discriminant = a * (radius * radius - f_perp.dot(f_perp));
    let on_surface = c.abs() <= ON_SURFACE * radius * radius;
    if discriminant < 0.0 {
        return SphereRoots { hit: false, near: 0.0, far: 0.0, on_surface };
    }
    let sign = if half_b >= 0.0 { 1.0 } else { -1.0 };
    let q = -(half_b + sign * discriminant.sqrt());
    let t0 = c / q;
    let t1 = q / a;
    let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    SphereRoots { hit: true, near, far, on_surface }
}

/// The root an intersection shader reports for the interval `[t_min, t_max]`: the near one,
/// or the far one when the ray starts inside; for a ray starting on the surface, only the root
/// farther from t = 0. `None` when no candidate lies in the interval.
pub fn reported_root(roots: SphereRoots, t_min: f32, t_max: f32) -> Option<f32> {
    let t = if roots.on_surface {
        if roots.near.abs() < roots.far.abs() {
            roots.far
        } else {
            roots.near
        }
    } else if roots.near >= t_min {
        roots.near
    } else {
        roots.far
    };
    if roots.hit && t >= t_min && t <= t_max {
        Some(t)
    } else {
        None
    }
}

/// The sphere of `primitive` (centre `a.xyz`, radius `a.w`) in the common procedural form.
pub fn intersect(origin: Vec3, direction: Vec3, primitive: &Primitive, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    let s = primitive.a;
    let center = Vec3::new(s.x, s.y, s.z);
    let t = reported_root(roots(origin, direction, center, s.w), t_min, t_max)?;
    Some(SurfaceHit { t, normal: (origin + direction * t - center) / s.w })
}

/// The textbook form, as in the hello-sphere example: roots (-b' -+ sqrt(b'^2 - ac)) / a.
/// Kept on purpose, to show what the stable form buys: its discriminant cancels for distant
/// spheres (twinray's guide, *Numerics*: 632 of 4000 decided silhouette rays wrong at distance 1e4,
/// the probe case far-sphere on lavapipe).
pub fn naive_intersect(
    origin: Vec3,
    direction: Vec3,
    primitive: &Primitive,
    t_min: f32,
    t_max: f32,
) -> Option<SurfaceHit> {
    let s = primitive.a;
    let center = Vec3::new(s.x, s.y, s.z);
    let oc = origin - center;
    let a = direction.dot(direction);
    let half_b = oc.dot(direction);
    let c = oc.dot(oc) - s.w * s.w;
    let discriminant = half_b * half_b - a * c;
    if discriminant < 0.0 {
        return None;
    }
    let root = discriminant.sqrt();
    let near = (-half_b - root) / a;
    let t = if near >= t_min { near } else { (-half_b + root) / a };
    if t >= t_min && t <= t_max {
        Some(SurfaceHit { t, normal: (origin + direction * t - center) / s.w })
    } else {
        None
    }
}

/// The sphere's texture coordinates at `p` (`shapes::uv`): u about the y axis through its
/// centre, v from the top pole (0) to the bottom one (1).
pub fn uv(primitive: &Primitive, p: Vec3, _n: Vec3) -> ShapeUv {
    spherical_uv(p - Vec3::new(primitive.a.x, primitive.a.y, primitive.a.z))
}

/// The texture coordinates of a sphere about the origin at `q`: u by [`around_y`], v from the
/// polar angle, with its gradient (y q - |q|^2 e_y) / (pi |q|^2 rho), rho the distance from
/// the axis.
pub fn spherical_uv(q: Vec3) -> ShapeUv {
    let (u, du) = around_y(q);
    let r2 = q.dot(q).max(1.0e-30);
    let r = r2.sqrt();
    let rho = (q.x * q.x + q.z * q.z).max(1.0e-30).sqrt();
    let v = (q.y / r).clamp(-1.0, 1.0).acos() / core::f32::consts::PI;
    let dv = (q * q.y - Vec3::Y * r2) / (r2 * rho * core::f32::consts::PI);
    ShapeUv { uv: Vec2::new(u, v), du, dv }
}

/// The sphere the primitive lies in (xyz: centre, w: radius, object space): where
/// `transform::stage_ray` brings a ray that starts far from it, before the transform.
pub fn bound(primitive: &Primitive) -> Vec4 {
    primitive.a
}

/// The sphere's scene kinds: one sphere, and a seeded field of many.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPE: super::spec::ShapeSpec = super::spec::ShapeSpec {
    kinds: &[scene::SPHERE, scene::SPHERE_FIELD],
    glsl_constants: &[("SPHERE_ON_SURFACE", ON_SURFACE)],
};

#[cfg(not(target_arch = "spirv"))]
mod scene {
    use super::super::spec::{no_check, one, Aabb, Param, ParamType, Rule, ShapeKind, Values, MAX_PRIMITIVES};
    use crate::layout::Primitive;
    use crate::random::SplitMix64;
    use glam::{Vec3, Vec4};

    pub const SPHERE: ShapeKind = ShapeKind {
        name: "sphere",
        about: "a sphere",
        params: &[Param::positive("radius")],
        check: no_check,
        relations: "",
        count: one,
        primitives: |v| vec![sphere(Vec3::ZERO, v.number("radius"), Vec3::ONE)],
        mitsuba: |v| super::super::mitsuba::spheres([&sphere(Vec3::ZERO, v.number("radius"), Vec3::ONE).0]),
    };

    pub const SPHERE_FIELD: ShapeKind = ShapeKind {
        name: "sphere_field",
        about: "`count` spheres with centres uniform in the box and radii uniform in the range, placed by \
                SplitMix64 from `seed` (identical everywhere). Each sphere has its own colour, which \
                multiplies the material's.",
        params: &[
            Param { name: "count", ty: ParamType::Count, rule: Rule::CountUpTo(MAX_PRIMITIVES), default: None },
            Param { name: "seed", ty: ParamType::Seed, rule: Rule::Any, default: None },
            Param::finite("center_min", ParamType::Triple),
            Param::finite("center_max", ParamType::Triple),
            Param::positive("radius_min"),
            Param { name: "radius_max", ty: ParamType::Number, rule: Rule::Any, default: None },
        ],
        check: field_check,
        relations: "`center_min` <= `center_max`, `radius_max` >= `radius_min`",
        count: |v| u64::from(v.count("count")),
        primitives: field,
        mitsuba: |v| super::super::mitsuba::spheres(field(v).iter().map(|(p, _)| p)),
    };

    fn field_check(v: &Values) -> Result<(), String> {
        let (lo, hi) = (v.triple("center_min"), v.triple("center_max"));
        if (0..3).any(|i| lo[i] > hi[i]) {
            return Err("center_min must not exceed center_max".into());
        }
        let (r_min, r_max) = (v.number("radius_min"), v.number("radius_max"));
        if !(r_max >= r_min && r_max.is_finite()) {
            return Err(format!("radius_max must be >= radius_min (got {r_max})"));
        }
        Ok(())
    }

    fn sphere(center: Vec3, radius: f32, tint: Vec3) -> (Primitive, Aabb) {
        let primitive = Primitive { a: center.extend(radius), b: Vec4::ZERO, tint: tint.extend(1.0) };
        (primitive, Aabb { min: center - Vec3::splat(radius), max: center + Vec3::splat(radius) })
    }

    fn field(v: &Values) -> Vec<(Primitive, Aabb)> {
        let mut rng = SplitMix64(v.seed("seed"));
        let (lo, hi) = (Vec3::from(v.triple("center_min")), Vec3::from(v.triple("center_max")));
        let (r_min, r_max) = (v.number("radius_min"), v.number("radius_max"));
        (0..v.count("count"))
            .map(|_| {
                let center = lo + (hi - lo) * Vec3::new(rng.unit(), rng.unit(), rng.unit());
                let radius = r_min + (r_max - r_min) * rng.unit();
                let tint = Vec3::new(rng.unit(), rng.unit(), rng.unit()) * 0.8 + Vec3::splat(0.2);
                sphere(center, radius, tint)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f64 reference root of the textbook quadratic, accurate for the well-conditioned cases here.
    fn reference(o: [f64; 3], d: [f64; 3], c: [f64; 3], r: f64) -> Option<(f64, f64)> {
        let f = [o[0] - c[0], o[1] - c[1], o[2] - c[2]];
        let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        let (a, b, cc) = (dot(d, d), 2.0 * dot(f, d), dot(f, f) - r * r);
        let disc = b * b - 4.0 * a * cc;
        (disc >= 0.0).then(|| ((-b - disc.sqrt()) / (2.0 * a), (-b + disc.sqrt()) / (2.0 * a)))
    }

    #[test]
    fn head_on_hit_gives_both_roots() {
        let roots = roots(Vec3::new(0.0, 0.0, -5.0), Vec3::Z, Vec3::ZERO, 1.0);
        assert!(roots.hit);
        assert_eq!((roots.near, roots.far), (4.0, 6.0));
    }

    #[test]
    fn clear_miss_is_a_miss() {
        let roots = roots(Vec3::new(0.0, 2.0, -5.0), Vec3::Z, Vec3::ZERO, 1.0);
        assert!(!roots.hit);
    }

    #[test]
    fn inside_start_reports_far_root() {
        let roots = roots(Vec3::ZERO, Vec3::X, Vec3::ZERO, 2.0);
        assert_eq!(reported_root(roots, 0.1, 100.0), Some(2.0));
        assert_eq!(reported_root(roots, 0.1, 1.0), None);
    }

    /// Rays leaving a sphere's surface (offset as shadow rays are) never hit the sphere itself
    /// when they head outwards, and reach the far side when they head inwards.
    #[test]
    fn rays_from_the_surface_skip_their_own_root() {
        for (i, scale) in [1.0f32, 100.0, 1.0e4].into_iter().enumerate() {
            let center = Vec3::new(3.0, -2.0, 1.0) * scale;
            for k in 0..500 {
                let a = k as f32 * 0.37 + i as f32;
                let n = Vec3::new(a.cos() * (a * 0.7).sin(), (a * 0.7).cos(), a.sin() * (a * 0.7).sin()).normalize();
                let p = crate::offset::offset_ray(center + n * scale, n);
                let out = (n + Vec3::new(0.3, 0.2, -0.1)).normalize();
                assert_eq!(
                    reported_root(roots(p, out, center, scale), 0.0, 1e30),
                    None,
                    "self-hit at scale {scale}, k {k}"
                );
                let t = reported_root(roots(p, -n, center, scale), 0.0, 1e30).expect("the far side");
                assert!((t / (2.0 * scale) - 1.0).abs() < 1e-3, "far side at {t}, scale {scale}");
            }
        }
    }

    #[test]
    fn non_unit_direction_keeps_ray_parameter() {
        let roots = roots(Vec3::new(0.0, 0.0, -5.0), Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, 1.0);
        assert_eq!((roots.near, roots.far), (2.0, 3.0));
    }

    /// A unit sphere 1e4 away, rays across its silhouette: the naive discriminant gets hit/miss
    /// wrong on 632 of 4000 such rays on lavapipe (twinray's guide, *Numerics*); this form must agree with f64 away from
    /// tangency and keep t to 1e-6 relative.
    #[test]
    fn far_sphere_matches_f64_reference() {
        let center = [0.0, 0.0, 1.0e4];
        for i in 0..2001 {
            let y = -1.2 + 2.4 * f64::from(i) / 2000.0;
            let d = [0.0, y * 1e-4, 1.0];
            let want = reference([0.0; 3], d, center, 1.0);
            let got = roots(Vec3::ZERO, Vec3::new(0.0, d[1] as f32, 1.0), Vec3::new(0.0, 0.0, 1.0e4), 1.0);
            if (y.abs() - 1.0).abs() < 1e-3 {
                continue; // within float noise of tangency: either answer is right
            }
            assert_eq!(got.hit, want.is_some(), "ray {i} (y = {y})");
            if let Some((near, _)) = want {
                let rel = (f64::from(got.near) - near).abs() / near;
                assert!(rel < 1e-6, "ray {i}: t = {} vs {near}, relative {rel}", got.near);
            }
        }
    }
}
