//! The object-space ray of an instance, computed by the stages from the world ray and the
//! instance's transform rather than read from `ObjectRayOriginKHR`: the driver's transform
//! applies the whole world-to-object matrix in f32, `M⁻¹ o + t'` with `t' = -M⁻¹ T`, and for an
//! instance far from the world origin both terms are large and cancel, so the object-space
//! origin carries an error of the order of the world coordinates' ulp (2.5e-4 relative t error
//! on lavapipe for a shape 1e4 away seen from 10 units, twinray's guide, *Numerics*). Taking the
//! instance's translation off the world origin first, `M⁻¹ (o - T)`, rounds `o - T` at the
//! magnitude of the ray's distance from the instance, not of the world coordinates: the bound
//! of pbrt's transformed-point error analysis (Pharr, Jakob and Humphreys, *Physically Based
//! Rendering*, 3rd ed., §3.9.4), γ₃ |M⁻¹| |o - T|, with |o - T| in place of |o| + |T|.
//!
//! That still rounds at the ray's distance from the object, and a grazing ray turns a small
//! sideways error into a large one along it. So a robust routine's ray is first brought near
//! its primitive ([`near_ray`]): the origin moved along the world ray to the sphere twice the
//! primitive's bound, with `o - T` and the move both computed without rounding at the
//! distance, then transformed. The rounding is then of the order of the object's size.
//! The GLSL twins are in transform.glsl.

use crate::exact::moved_origin;
use crate::features::{Features, FAR_INSTANCES};
use glam::{Mat3, Vec3, Vec4};
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

/// The ray an intersection routine is handed: object space, its origin `shift` along the world
/// ray. A hit at `t` on it is at `shift + t` on the world ray.
#[derive(Clone, Copy)]
pub struct StageRay {
    /// The object-space origin.
    pub origin: Vec3,
    /// The object-space direction (the world direction transformed: t keeps its scale).
    pub direction: Vec3,
    /// How far along the world ray the origin was moved (0 where it was not).
    pub shift: f32,
}

impl StageRay {
    /// The world ray's `[t_min, t_max]` in this ray's parameter.
    #[inline(always)]
    pub fn range(&self, t_min: f32, t_max: f32) -> (f32, f32) {
        (t_min - self.shift, t_max - self.shift)
    }

    /// The world ray's parameter of this ray's `t`, for a hit found within [`StageRay::range`]
    /// of `t_max`: no more than `t_max`, where adding the shift back rounds past it (a query's
    /// generated intersection must lie within the ray's range).
    #[inline(always)]
    pub fn world_t(&self, t: f32, t_max: f32) -> f32 {
        let world = self.shift + t;
        if world > t_max {
            t_max
        } else {
            world
        }
    }
}

/// The object-space origin and direction of the world ray (`origin`, `direction`) for an
/// instance whose object-to-world translation is `translation` and whose world-to-object
/// transform has the 3x3 part `inverse`. The direction has no translation to lose: it is the
/// driver's own product. The ray parameter t is the same in both spaces.
#[inline(always)]
pub fn object_ray(origin: Vec3, direction: Vec3, translation: Vec3, inverse: Mat3) -> (Vec3, Vec3) {
    (inverse * (origin - translation), inverse * direction)
}

/// The sphere a ray is brought to, in bounds (the radius of `shapes::shape_bound`'s sphere),
/// so that its origin is rounded at no more than this many times the object's size. Twice
/// keeps the moved origin away from the surface, where routines take a root at the origin for
/// the ray's own (`surface::self_reach2`).
pub const NEAR_BOUNDS: f32 = 2.0;

/// How far from its primitive, in bounds, a ray may start and still be transformed where it
/// starts; one farther is brought onto the [`NEAR_BOUNDS`] sphere, whatever its distance. A
/// nearer ray would gain less than 1.5 from the move and pay the moved origin's own rounding:
/// from 2 bounds, `box-face-plane`'s p99 went from 9.4e-8 to 1.4e-7 on lavapipe, from 3 it
/// stayed. The threshold was 16 once, and a torus 1,000 units across grazed from 2,000 (4
/// bounds) kept a p99 of 1.4e-5 on the H200 (twinray's guide, *Numerics*, "A ray brought near its
/// primitive").
pub const FAR_BOUNDS: f32 = 3.0;

/// Where the ray (`from` the centre of a sphere of radius `radius`, `direction`) enters the
/// sphere [`NEAR_BOUNDS`] times that radius, or, missing it, its point nearest the centre; 0
/// where that lies behind.
#[inline(always)]
fn entry(from: Vec3, direction: Vec3, radius: f32) -> f32 {
    let reach = NEAR_BOUNDS * radius;
    let a = direction.dot(direction);
    let nearest = -from.dot(direction) / a;
    let closest = from + direction * nearest;
    let room = reach * reach - closest.dot(closest);
    let entry = if room > 0.0 { nearest - (room / a).sqrt() } else { nearest };
    if entry > 0.0 {
        entry
    } else {
        0.0
    }
}

/// The world ray (`origin`, `direction`) for an instance with object-to-world translation
/// `translation` and world-to-object 3x3 part `inverse`, in object space; where it starts
/// farther than [`FAR_BOUNDS`] from the primitive in the sphere `bound` (object space: xyz
/// centre, w radius; a zero radius brings no ray anywhere), first brought onto the sphere
/// [`NEAR_BOUNDS`] times as large.
///
/// The plain object-space origin `M⁻¹ (o - T)` says whether the ray is far and how far to move
/// it; the moved origin `(o - T) + shift d` comes from `exact::moved_origin`, rounded at its own
/// size, about twice the bound, and is then transformed. A ray that stays where it starts is
/// the plain one, bit for bit, and costs one more dot product and comparison.
#[inline(always)]
pub fn near_ray(origin: Vec3, direction: Vec3, translation: Vec3, inverse: Mat3, bound: Vec4) -> StageRay {
    let (plain, object_direction) = object_ray(origin, direction, translation, inverse);
    let from = plain - bound.truncate();
    let reach = FAR_BOUNDS * bound.w;
    let mut ray = StageRay { origin: plain, direction: object_direction, shift: 0.0 };
    // `&`, not `&&`: both are comparisons, and rust-gpu writes a short circuit as a branch.
    if (bound.w > 0.0) & (from.dot(from) > reach * reach) {
        let shift = entry(from, object_direction, bound.w);
        if shift > 0.0 {
            ray.origin = inverse * moved_origin(origin, translation, direction, shift);
            ray.shift = shift;
        }
    }
    ray
}

/// The ray an intersection stage uses: its own ([`near_ray`] of the world ray, `bound` its
/// primitive's, zero for the naive routines) where the scene has far instances
/// (`features::FAR_INSTANCES`, a specialisation constant, so the other branch is compiled
/// out), else the `driver`'s, which costs nothing and is as good near the origin.
#[inline(always)]
pub fn stage_ray(
    features: Features,
    driver: (Vec3, Vec3),
    (origin, direction): (Vec3, Vec3),
    (translation, inverse): (Vec3, Mat3),
    bound: Vec4,
) -> StageRay {
    if features.has::<FAR_INSTANCES>() {
        near_ray(origin, direction, translation, inverse, bound)
    } else {
        StageRay { origin: driver.0, direction: driver.1, shift: 0.0 }
    }
}

/// The t of a hit the driver found on the triangle `p` (object space) of an instance, measured
/// again by the stages where the scene has far instances: on the triangle's plane, from the
/// world ray brought near the triangle first ([`triangle_ray`]). The driver transforms a ray
/// where it starts, and a ray that starts far from a small triangle, grazing it, comes back with
/// the rounding of its distance over the angle; the driver still decides which triangle is hit
/// (and whether any is), the stages only how far along the ray. The driver's `t` where the scene
/// has no far instances (a specialisation constant: the branch is compiled out), or where
/// [`plane_t`] keeps it.
#[inline(always)]
pub fn triangle_t(features: Features, world: (Vec3, Vec3), placed: (Vec3, Mat3), p: [Vec3; 3], t: f32) -> f32 {
    if features.has::<FAR_INSTANCES>() {
        plane_t(&triangle_ray(world, placed, p), p, t)
    } else {
        t
    }
}

/// The world ray (`origin`, `direction`) in the object space of an instance (`translation`,
/// world-to-object 3x3 part `inverse`), brought near the triangle `p` first ([`near_ray`], the
/// sphere about its centroid through its farthest corner).
#[inline(always)]
pub fn triangle_ray((origin, direction): (Vec3, Vec3), (translation, inverse): (Vec3, Mat3), p: [Vec3; 3]) -> StageRay {
    let centre = (p[0] + p[1] + p[2]) * (1.0 / 3.0);
    let (a, b, c) = ((p[0] - centre).length(), (p[1] - centre).length(), (p[2] - centre).length());
    // Explicit comparisons: the GPU's FMax is undefined for NaN.
    let ab = if a > b { a } else { b };
    let radius = if ab > c { ab } else { c };
    near_ray(origin, direction, translation, inverse, centre.extend(radius))
}

/// Where `ray` (from [`triangle_ray`]) meets the plane of triangle `p`, on the world ray; `t`
/// where the ray was not moved (it starts within [`FAR_BOUNDS`] of the triangle, where the move
/// would gain little) or meets the plane edge-on.
#[inline(always)]
pub fn plane_t(ray: &StageRay, p: [Vec3; 3], t: f32) -> f32 {
    let normal = (p[1] - p[0]).cross(p[2] - p[0]);
    let along = normal.dot(ray.direction);
    // `&`, not `&&`: see `near_ray`.
    if (ray.shift > 0.0) & (along != 0.0) {
        ray.shift + normal.dot(p[0] - ray.origin) / along
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    type M = [[f64; 3]; 3];

    /// Rows of the rotation by `angle` about the unit `axis` (Rodrigues).
    fn turn(axis: [f64; 3], angle: f64) -> M {
        let (s, c) = angle.sin_cos();
        let [x, y, z] = axis;
        let k = 1.0 - c;
        [
            [c + x * x * k, x * y * k - z * s, x * z * k + y * s],
            [y * x * k + z * s, c + y * y * k, y * z * k - x * s],
            [z * x * k - y * s, z * y * k + x * s, c + z * z * k],
        ]
    }

    fn apply(m: &M, v: [f64; 3]) -> [f64; 3] {
        m.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
    }

    /// An instance turned by `angle` about `axis` (any length) and scaled by `scale`: its 3x3
    /// part, the f32 world-to-object matrix the stages multiply by, and that matrix exactly in
    /// f64 (to judge the stages against the matrix they have).
    fn turned_scaled(axis: [f64; 3], angle: f64, scale: [f64; 3]) -> (M, Mat3, M) {
        let n = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
        let rot = turn(axis.map(|x| x / n), angle);
        let m: M = [0, 1, 2].map(|i| [0, 1, 2].map(|j| rot[i][j] * scale[j]));
        let inv_rows: M = [0, 1, 2].map(|i| [0, 1, 2].map(|j| rot[j][i] / scale[i]));
        let inverse =
            Mat3::from_cols(f32s(inv_rows.map(|r| r[0])), f32s(inv_rows.map(|r| r[1])), f32s(inv_rows.map(|r| r[2])));
        let inv: M = [0, 1, 2].map(|i| [0, 1, 2].map(|j| f64::from(inverse.col(j)[i])));
        (m, inverse, inv)
    }

    fn transpose(m: &M) -> M {
        [0, 1, 2].map(|i| [m[0][i], m[1][i], m[2][i]])
    }

    fn f32s(v: [f64; 3]) -> Vec3 {
        Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
    }

    fn distance(a: Vec3, b: [f64; 3]) -> f64 {
        let d = [f64::from(a.x) - b[0], f64::from(a.y) - b[1], f64::from(a.z) - b[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    }

    /// A unit shape's instance turned about an oblique axis and moved 3e4 from the origin; rays
    /// from 5 units away. The stages' form keeps the object-space origin within a few ulp of
    /// its size; applying the whole matrix at once (the driver's form) loses about the world
    /// coordinates' ulp.
    #[test]
    fn the_translation_taken_off_first_keeps_the_origin_at_its_own_scale() {
        let n = (1.0f64 + 4.0 + 9.0).sqrt();
        let rot = turn([1.0 / n, 2.0 / n, 3.0 / n], 0.7);
        let inv = transpose(&rot);
        let t = [30000.0, -20000.5, 12345.25];
        let inverse = Mat3::from_cols(f32s(inv.map(|r| r[0])), f32s(inv.map(|r| r[1])), f32s(inv.map(|r| r[2])));
        let t_inv = apply(&inv, t).map(|x| -x);
        let (mut stages, mut whole) = (0.0f64, 0.0f64);
        for k in 0..64 {
            let local = [(k as f64 * 0.37).sin(), (k as f64 * 0.11).cos(), -5.0];
            let moved = apply(&rot, local);
            let world = f32s([moved[0] + t[0], moved[1] + t[1], moved[2] + t[2]]);
            // The truth: the f32 world origin, exactly transformed.
            let w = [f64::from(world.x), f64::from(world.y), f64::from(world.z)];
            let truth = apply(&inv, [w[0] - t[0], w[1] - t[1], w[2] - t[2]]);
            let (o, _) = object_ray(world, Vec3::Z, f32s(t), inverse);
            stages = stages.max(distance(o, truth));
            let driver = inverse * world + f32s(t_inv);
            whole = whole.max(distance(driver, truth));
        }
        assert!(stages < 4e-6, "the stages' form is {stages:e} off");
        assert!(whole > 1e-4, "the whole matrix at once was {whole:e} off: the case is not hard");
    }

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// A cylinder's instance (radius 1, half height 1) scaled by (1, 5, 0.2), turned about an
    /// oblique axis and moved 1e4 from the origin, grazed by rays from 1,000 units away. Brought
    /// near first, the object-space origin lies within a few ulps of the object's size of the
    /// exact object-space ray, at the parameter `shift`; transformed from where it starts,
    /// within the ulps of its distance, which a grazing ray turns into t error.
    #[test]
    fn a_ray_brought_near_first_is_rounded_at_the_objects_size() {
        let (m, inverse, inv) = turned_scaled([2.0, -1.0, 3.0], 0.9, [1.0, 5.0, 0.2]);
        let t = [10000.0, -3000.25, 7000.5];
        let bound = Vec4::new(0.0, 0.0, 0.0, 2.0f32.sqrt());
        let (mut near, mut plain) = (0.0f64, 0.0f64);
        for k in 0..64 {
            let a = k as f64 * 0.41;
            // A point on the side, and a direction nearly tangent to the side there.
            let target = apply(&m, [a.cos(), (a * 3.0).sin() * 0.9, a.sin()]);
            let tangent = apply(&m, [-a.sin(), 0.05 * (a * 5.0).cos(), a.cos()]);
            let length = dot(tangent, tangent).sqrt();
            let d = f32s(tangent.map(|x| x / length));
            let dw = [f64::from(d.x), f64::from(d.y), f64::from(d.z)];
            let o = f32s([0, 1, 2].map(|i| t[i] + target[i] - 1000.0 * dw[i]));
            let ow = [f64::from(o.x), f64::from(o.y), f64::from(o.z)];
            let (line_o, line_d) = (apply(&inv, [0, 1, 2].map(|i| ow[i] - t[i])), apply(&inv, dw));
            let ray = near_ray(o, d, f32s(t), inverse, bound);
            assert!(ray.shift > 900.0 && ray.shift < 1000.0, "shift {}", ray.shift);
            let at = [0, 1, 2].map(|i| line_o[i] + f64::from(ray.shift) * line_d[i]);
            near = near.max(distance(ray.origin, at));
            plain = plain.max(distance(object_ray(o, d, f32s(t), inverse).0, line_o));
        }
        // f32's ulp at 3 units (the moved origin) is 2.4e-7; at 1,000 units, 6.1e-5.
        assert!(near < 4e-6, "brought near: {near:e} off");
        assert!(plain > 1e-5, "transformed from the start: {plain:e} off, the case is not hard");
    }

    /// A triangle of a turned, squashed instance 1e4 out, grazed from 1,000 units: its t measured
    /// on its plane from the ray brought near it is within a few ulps of the exact one; the
    /// driver's form (the whole world-to-object matrix applied where the ray starts) is not.
    #[test]
    fn a_triangle_grazed_from_afar_is_measured_near_it() {
        let (m, inverse, inv) = turned_scaled([1.0, 2.0, -2.0], 0.6, [1.0, 4.0, 0.3]);
        let t = [10000.0, -3000.25, 7000.5];
        let p = [Vec3::new(-0.5, -0.4, 0.1), Vec3::new(0.6, -0.3, 0.0), Vec3::new(0.0, 0.5, -0.1)];
        let pd = p.map(|v| [f64::from(v.x), f64::from(v.y), f64::from(v.z)]);
        let normal = {
            let (a, b) = ([0, 1, 2].map(|i| pd[1][i] - pd[0][i]), [0, 1, 2].map(|i| pd[2][i] - pd[0][i]));
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        };
        let t_inv = apply(&inv, t).map(|x| -x);
        let (mut stages, mut driver) = (0.0f64, 0.0f64);
        // The world normal: the inverse's transpose applied to the object one.
        let up = [0, 1, 2].map(|j| (0..3).map(|i| inv[i][j] * normal[i]).sum::<f64>());
        for k in 0..64 {
            let (u, v) = (0.1 + 0.3 * (k as f64 * 0.7).sin().abs(), 0.1 + 0.3 * (k as f64 * 1.3).cos().abs());
            // A point of the triangle, and a direction 0.5 to 2 degrees off its plane.
            let q = [0, 1, 2].map(|i| pd[0][i] + u * (pd[1][i] - pd[0][i]) + v * (pd[2][i] - pd[0][i]));
            let target = apply(&m, q);
            let (c, s) = (k as f64).sin_cos();
            let along = apply(&m, [0, 1, 2].map(|i| c * (pd[1][i] - pd[0][i]) + s * (pd[2][i] - pd[0][i])));
            let tilt = (0.5 + 1.5 * (k as f64 / 64.0)).to_radians();
            let (la, lu) = (dot(along, along).sqrt(), dot(up, up).sqrt());
            let dir = [0, 1, 2].map(|i| along[i] / la * tilt.cos() - up[i] / lu * tilt.sin());
            let d = f32s(dir);
            let dw = [f64::from(d.x), f64::from(d.y), f64::from(d.z)];
            let o = f32s([0, 1, 2].map(|i| t[i] + target[i] - 1000.0 * dw[i]));
            let ow = [f64::from(o.x), f64::from(o.y), f64::from(o.z)];
            // The exact t: the f32 ray against the f32 triangle, through the f32 matrix.
            let (lo, ld) = (apply(&inv, [0, 1, 2].map(|i| ow[i] - t[i])), apply(&inv, dw));
            let exact = dot(normal, [0, 1, 2].map(|i| pd[0][i] - lo[i])) / dot(normal, ld);
            let got = triangle_t(Features::all(), (o, d), (f32s(t), inverse), p, -1.0);
            stages = stages.max((f64::from(got) - exact).abs() / exact);
            let driven =
                plane_t(&StageRay { origin: inverse * o + f32s(t_inv), direction: inverse * d, shift: 1.0 }, p, -1.0);
            driver = driver.max((f64::from(driven) - 1.0 - exact).abs() / exact);
        }
        assert!(stages < 1e-6, "measured near the triangle: {stages:e} off");
        assert!(driver > 1e-5, "the driver's form: {driver:e} off, the case is not hard");
        // Without far instances the driver's t stands.
        assert_eq!(triangle_t(Features::new(0), (Vec3::ZERO, Vec3::X), (Vec3::ZERO, Mat3::IDENTITY), p, 7.0), 7.0);
    }

    /// A ray that starts within twice the bound, and the naive routines' zero bound, keep the
    /// ray where it starts: the same bits as the plain transform.
    #[test]
    fn a_ray_near_already_or_without_a_bound_is_not_moved() {
        let inverse = Mat3::from_diagonal(Vec3::new(0.5, 2.0, 1.0));
        let (t, d) = (Vec3::new(300.0, -20.0, 5.0), Vec3::new(0.3, -0.2, 0.9).normalize());
        for (o, bound) in [
            (t + Vec3::new(0.5, 0.2, -1.5), Vec4::new(0.0, 0.0, 0.0, 1.0)),
            (t - d * 500.0, Vec4::ZERO),
            (t + d * 10.0, Vec4::new(0.0, 0.0, 0.0, 1.0)),
        ] {
            let ray = near_ray(o, d, t, inverse, bound);
            let (plain_o, plain_d) = object_ray(o, d, t, inverse);
            assert_eq!(ray.shift, 0.0);
            assert_eq!((ray.origin, ray.direction), (plain_o, plain_d));
        }
    }
}
