//! Thin tori (r/R from 1e-2 down to 1e-3) seen edge-on and nearly edge-on from up to 1e4
//! away, and rays leaving their surface: the shared f32 torus routine must give no false hit
//! or false miss on any ray the f64 reference decides. The GPU cases are in
//! `probes/stability/torus-thin-*.toml`; this runs the same math on the CPU, where a slip shows
//! up before any GPU run.

use glam::{DVec3, Vec3, Vec4};
use twinray_host::reference::shapes::{intersect, RefRay, RefShape, Verdict};
use twinray_host::reference::surface;
use twinray_shared::layout::Primitive;
use twinray_shared::offset::offset_ray;
use twinray_shared::shapes::torus;

#[derive(Default, Debug)]
struct Tally {
    decided: usize,
    wrong: Vec<String>,
}

impl Tally {
    /// Fails unless at least `min_decided` rays were decided and none of them wrong.
    fn assert_none_wrong(&self, min_decided: usize) {
        assert!(self.decided >= min_decided, "only {} rays decided", self.decided);
        let shown = self.wrong[..self.wrong.len().min(20)].join("\n");
        assert!(self.wrong.is_empty(), "{} of {} decided rays wrong:\n{shown}", self.wrong.len(), self.decided);
    }

    fn check(&mut self, minor: f32, origin: Vec3, direction: Vec3) {
        let reference = intersect(
            &RefShape::Torus { major: 1.0, minor: f64::from(minor) },
            &RefRay {
                origin: origin.as_dvec3(),
                direction: direction.as_dvec3(),
                t_min: 0.0,
                t_max: 1e30,
                noise_floor: 0.0,
            },
        );
        let primitive = Primitive { a: Vec4::new(1.0, minor, 0.0, 0.0), b: Vec4::ZERO, tint: Vec4::ONE };
        let got = torus::intersect(origin, direction, &primitive, 0.0, 1e30);
        let wrong = match (reference, got) {
            (Verdict::Ambiguous, _) => return,
            (Verdict::Miss, Some(h)) => Some(format!("false hit at t {}", h.t)),
            (Verdict::Hit { t, .. }, None) => Some(format!("false miss (t {t})")),
            _ => None,
        };
        self.decided += 1;
        if let Some(w) = wrong {
            self.wrong.push(format!("r {minor}: {w} for {origin} + t {direction}"));
        }
    }
}

/// Parallel rays from `distance` away, `elevation` degrees above the torus's plane, across a
/// grid over its projected band (1.5 times its half height, 1.05 times its half width).
fn band_rays(tally: &mut Tally, minor: f32, distance: f32, elevation: f32) {
    let e = elevation.to_radians();
    let forward = Vec3::new(0.0, -e.sin(), e.cos());
    let up = Vec3::new(0.0, e.cos(), e.sin());
    let half_v = 1.5 * (minor + (1.0 + minor) * e.sin());
    for i in 0..120 {
        for j in 0..60 {
            let u = -1.05 * (1.0 + minor) + 2.1 * (1.0 + minor) * (i as f32 + 0.5) / 120.0;
            let v = -half_v + 2.0 * half_v * (j as f32 + 0.5) / 60.0;
            let origin = Vec3::X * u + up * v - forward * distance;
            tally.check(minor, origin, forward);
        }
    }
}

/// Rays leaving points drawn all over the tube, offset as shadow rays are, into the outer
/// hemisphere.
fn surface_rays(tally: &mut Tally, minor: f32) {
    let mut state = 12345u64;
    let mut next = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..3000 {
        let (p, n) = surface::sample(&RefShape::Torus { major: 1.0, minor: f64::from(minor) }, &mut next);
        let z = 2.0 * next() - 1.0;
        let phi = std::f64::consts::TAU * next();
        let mut d = DVec3::new((1.0 - z * z).sqrt() * phi.cos(), (1.0 - z * z).sqrt() * phi.sin(), z);
        if d.dot(n) < 0.0 {
            d = -d;
        }
        tally.check(minor, offset_ray(p.as_vec3(), n.as_vec3()), d.as_vec3());
    }
}

#[test]
fn thin_tori_edge_on_from_afar_have_no_false_answers() {
    let mut tally = Tally::default();
    for minor in [1e-2f32, 3e-3, 1e-3] {
        for distance in [1e1f32, 1e2, 1e3, 1e4] {
            for elevation in [0.0f32, 0.05, 0.5, 5.0] {
                band_rays(&mut tally, minor, distance, elevation);
            }
        }
    }
    tally.assert_none_wrong(50_000);
}

#[test]
fn rays_leaving_thin_tori_have_no_false_answers() {
    let mut tally = Tally::default();
    for minor in [1e-2f32, 3e-3, 1e-3] {
        surface_rays(&mut tally, minor);
    }
    tally.assert_none_wrong(8000);
}
