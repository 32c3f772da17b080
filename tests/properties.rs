//! The shared f32 intersection routines against the f64 reference (`twinray_host::reference`),
//! with property-based tests: random rays from 2 to 50 shape sizes away, aimed into and around
//! each shape's bounds, with random direction lengths (as in scaled instances). On every ray
//! the reference decides (ambiguous rays are skipped), hit and miss must agree and t and the
//! normal must be close. A regression in the shared math shows up here, before any GPU run.

use glam::{DVec3, Vec3, Vec4};
use proptest::prelude::*;
use twinray_host::reference::shapes::{intersect, RefRay, RefShape, Verdict};
use twinray_shared::layout::Primitive;
use twinray_shared::shapes::{boxes, cone, cylinder, plane, sphere, torus};
use twinray_shared::surface::SurfaceHit;

/// A shape under test: its f32 routine, primitive and reference twin, and its size.
struct Case {
    f32_intersect: fn(Vec3, Vec3, &Primitive, f32, f32) -> Option<SurfaceHit>,
    primitive: Primitive,
    reference: RefShape,
    half: Vec3,
    /// Largest relative t error accepted on a decided ray (see `cases`).
    max_rel_t: f64,
}

fn primitive(a: Vec4, b: Vec4) -> Primitive {
    Primitive { a, b, tint: Vec4::ONE }
}

/// Tolerances: single rays, not percentiles, so a few ULPs more than the probe suite's p99 targets
/// (1e-6 quadrics, 1e-5 torus); the GPU suite measures the percentiles.
fn cases() -> Vec<(&'static str, Case)> {
    vec![
        (
            "sphere",
            Case {
                f32_intersect: sphere::intersect,
                primitive: primitive(Vec4::new(0.0, 0.0, 0.0, 1.0), Vec4::ZERO),
                reference: RefShape::Sphere { center: DVec3::ZERO, radius: 1.0 },
                half: Vec3::ONE,
                max_rel_t: 4e-6,
            },
        ),
        (
            "rectangle",
            Case {
                f32_intersect: plane::intersect,
                primitive: primitive(Vec4::new(1.0, 0.5, 0.0, 0.0), Vec4::ZERO),
                reference: RefShape::Rectangle { half_x: 1.0, half_z: 0.5 },
                half: Vec3::new(1.0, 0.01, 0.5),
                max_rel_t: 4e-6,
            },
        ),
        (
            "disk",
            Case {
                f32_intersect: plane::intersect,
                primitive: primitive(Vec4::new(1.0, 1.0, 0.0, 0.0), Vec4::new(plane::DISK, 0.0, 0.0, 0.0)),
                reference: RefShape::Disk { radius: 1.0 },
                half: Vec3::new(1.0, 0.01, 1.0),
                max_rel_t: 4e-6,
            },
        ),
        (
            "box",
            Case {
                f32_intersect: boxes::intersect,
                primitive: primitive(Vec4::new(1.0, 0.5, 2.0, 0.0), Vec4::ZERO),
                reference: RefShape::Box { half: DVec3::new(1.0, 0.5, 2.0) },
                half: Vec3::new(1.0, 0.5, 2.0),
                max_rel_t: 4e-6,
            },
        ),
        (
            "cylinder",
            Case {
                f32_intersect: cylinder::intersect,
                primitive: primitive(Vec4::new(0.7, 1.0, 0.0, 0.0), Vec4::ZERO),
                reference: RefShape::Cylinder { radius: 0.7, half_height: 1.0 },
                half: Vec3::new(0.7, 1.0, 0.7),
                max_rel_t: 4e-6,
            },
        ),
        (
            "cone",
            Case {
                f32_intersect: cone::intersect,
                primitive: primitive(Vec4::new(0.8, 1.0, 0.0, 0.0), Vec4::ZERO),
                reference: RefShape::Cone { radius: 0.8, half_height: 1.0 },
                half: Vec3::new(0.8, 1.0, 0.8),
                max_rel_t: 4e-6,
            },
        ),
        (
            "torus",
            Case {
                f32_intersect: torus::intersect,
                primitive: primitive(Vec4::new(1.0, 0.3, 0.0, 0.0), Vec4::ZERO),
                reference: RefShape::Torus { major: 1.0, minor: 0.3 },
                half: Vec3::new(1.3, 0.3, 1.3),
                max_rel_t: 4e-5,
            },
        ),
    ]
}

fn unit(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(phi.sin() * theta.cos(), phi.cos(), phi.sin() * theta.sin())
}

/// Checks one ray; `Err` says what disagreed.
fn check(name: &str, case: &Case, origin: Vec3, direction: Vec3) -> Result<(), String> {
    let reference = intersect(
        &case.reference,
        &RefRay {
            origin: origin.as_dvec3(),
            direction: direction.as_dvec3(),
            t_min: 0.0,
            t_max: 1e6,
            noise_floor: 0.0,
        },
    );
    let got = (case.f32_intersect)(origin, direction, &case.primitive, 0.0, 1e6);
    match (reference, got) {
        (Verdict::Ambiguous, _) | (Verdict::Miss, None) => Ok(()),
        (Verdict::Miss, Some(h)) => Err(format!("{name}: false hit at t {} for {origin} + t {direction}", h.t)),
        (Verdict::Hit { t, .. }, None) => Err(format!("{name}: false miss (true t {t}) for {origin} + t {direction}")),
        (Verdict::Hit { t, normal }, Some(h)) => {
            let rel = (f64::from(h.t) - t).abs() / t.abs().max(1e-30);
            let angle = h.normal.normalize().as_dvec3().dot(normal).clamp(-1.0, 1.0).acos();
            if rel > case.max_rel_t {
                Err(format!("{name}: t {} vs {t} (relative {rel:.2e}) for {origin} + t {direction}", h.t))
            } else if angle > 1e-3 {
                Err(format!("{name}: normal off by {angle:.2e} rad for {origin} + t {direction}"))
            } else {
                Ok(())
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn shared_f32_routines_agree_with_the_f64_reference(
        shape in 0usize..7,
        distance in 2.0f32..50.0,
        theta in 0.0f32..std::f32::consts::TAU,
        phi in 0.05f32..3.09,
        aim in prop::array::uniform3(-1.3f32..1.3),
        length in 0.5f32..2.0,
    ) {
        let all = cases();
        let (name, case) = &all[shape];
        let size = case.half.max_element();
        let origin = unit(theta, phi) * distance * size;
        let target = Vec3::from(aim) * case.half;
        let direction = (target - origin).normalize() * length;
        if let Err(e) = check(name, case, origin, direction) {
            prop_assert!(false, "{}", e);
        }
    }
}
