//! The t error of a probe split by where it comes from. The intersection stages compute their
//! object-space ray from the world ray and the instance's transform, in f32
//! (`twinray_shared::transform`). The witness pass reads that ray back with the t the stages
//! reported, so the f64 reference can judge the stages against the very ray they used (their
//! own error) and, apart from it, how far the transform moved the true answer. A second
//! witness pass reads the object-space ray the driver hands a hit group, which the stages no
//! longer use: how far the driver's transform would have moved it. The stages' ray may start
//! along the world ray, brought near the primitive first; the witness says how far, and the
//! reference answers in the world ray's parameter. On lavapipe an instance
//! translated 1e4 away and seen from 10 units gets 2.5e-4 from the driver's transform, and
//! a few f32 ulps from the stages' (docs/numerics.md).

use super::run::{record_written, ProbeResult};
use crate::reference::scene::SceneReference;
use crate::reference::shapes::{RefRay, Verdict};
use crate::util::stats::Quantiles;
use glam::Vec3;
use serde::Serialize;
use twinray_shared::bindings::NO_HIT;
use twinray_shared::layout::ProbeRay;

/// What the witness pass read back for one ray (see `ProbeResult`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Witness {
    /// The object-space ray the GPU handed the hit group's stages.
    pub origin: Vec3,
    pub direction: Vec3,
    /// How far along the world ray that origin lies: the stages brought the ray near the
    /// primitive before the transform (`twinray_shared::transform::near_ray`).
    pub shift: f32,
    /// The t they reported, on the world ray.
    pub t: f32,
}

/// The witness in a record of a witness pass; none where the ray missed or the record was
/// never written.
pub fn witness(r: &ProbeResult) -> Option<Witness> {
    if !record_written(r) || r.ids.w == NO_HIT {
        return None;
    }
    let direction = Vec3::new(f32::from_bits(r.ids.x), f32::from_bits(r.ids.y), f32::from_bits(r.ids.z));
    Some(Witness { origin: r.normal_t.truncate(), direction, shift: f32::from_bits(r.ids.w), t: r.normal_t.w })
}

/// The relative t error over hits, split by source.
#[derive(Clone, Debug, Default, Serialize)]
pub struct TErrorSplit {
    /// Hits judged: the reference decides their object-space ray, and the witness pass
    /// repeated the probe's t.
    pub rays: usize,
    /// |t - t_obj| / t_obj, t_obj the f64 first hit of the object-space ray the GPU handed the
    /// stages: the stages' own error.
    pub stage: Quantiles,
    /// |t_obj - t_ref| / t_ref, t_ref the f64 first hit of the world-space ray: how far the
    /// stages' world-to-object transform moved the true answer.
    pub transform: Quantiles,
    /// The same for the object-space ray the driver hands a hit group, over the hits whose
    /// driver witness repeated the t and the reference decides: what the driver's transform
    /// would have cost. None without that witness pass.
    pub driver: Option<Quantiles>,
    /// Hits whose object-space ray the reference finds ambiguous, or a miss (left out).
    pub undecided: usize,
    /// Hits the witness pass answered with another t, or none: the GPU's answer did not repeat
    /// (left out).
    pub unrepeated: usize,
}

/// One hit the reference agrees with: the ray, the reference's t, and the probe's record.
pub struct AgreedHit<'a> {
    pub ray: &'a ProbeRay,
    pub t_ref: f64,
    pub result: &'a ProbeResult,
    pub witness: &'a ProbeResult,
    /// The record of the driver's witness pass, where there was one.
    pub driver: Option<&'a ProbeResult>,
}

/// The split over `hits`.
pub fn split<'a>(reference: &SceneReference, hits: impl Iterator<Item = AgreedHit<'a>>) -> TErrorSplit {
    let mut out = TErrorSplit::default();
    let (mut stage, mut transform, mut driver, mut driven) = (Vec::new(), Vec::new(), Vec::new(), false);
    for hit in hits {
        let t = hit.result.normal_t.w;
        driven |= hit.driver.is_some();
        // The driver's witness reports the driver's own t, which the stages measure again on a
        // triangle (`transform::triangle_t`): the same hit within a relative `THROUGH`.
        let same_hit = |w: &Witness| relative(f64::from(w.t), f64::from(t)) <= THROUGH;
        if let Some(t_obj) = hit.driver.and_then(|d| object_t(reference, &hit, d, same_hit)) {
            driver.push(relative(t_obj, hit.t_ref));
        }
        if witness(hit.witness).filter(|w| w.t.to_bits() == t.to_bits()).is_none() {
            out.unrepeated += 1;
            continue;
        }
        match object_t(reference, &hit, hit.witness, |w| w.t.to_bits() == t.to_bits()) {
            Some(t_obj) => {
                stage.push(relative(f64::from(t), t_obj));
                transform.push(relative(t_obj, hit.t_ref));
                out.rays += 1;
            }
            None => out.undecided += 1,
        }
    }
    out.stage = Quantiles::of(stage);
    out.transform = Quantiles::of(transform);
    out.driver = driven.then(|| Quantiles::of(driver));
    out
}

/// The f64 first hit of the object-space ray a witness record holds, where the witness is of the
/// probe's hit (`repeats`) and the reference decides the ray.
fn object_t(
    reference: &SceneReference,
    hit: &AgreedHit,
    record: &ProbeResult,
    repeats: impl Fn(&Witness) -> bool,
) -> Option<f64> {
    let w = witness(record).filter(repeats)?;
    let object = reference.objects.get(hit.result.ids.x as usize)?;
    // The witnessed ray starts `shift` along the world ray: its parameter is the world's less
    // the shift, exactly in f64.
    let shift = f64::from(w.shift);
    let ray = RefRay {
        origin: w.origin.as_dvec3(),
        direction: w.direction.as_dvec3(),
        t_min: f64::from(hit.ray.origin.w) - shift,
        t_max: f64::from(hit.ray.direction.w) - shift,
        // Given in the object's own space: rounded at its own magnitude.
        noise_floor: 0.0,
    };
    match object.first_hit(&ray, crate::reference::scene::Faces::Front) {
        Verdict::Hit { t, .. } => Some(shift + t),
        Verdict::Miss | Verdict::Ambiguous => None,
    }
}

/// Relative t beyond the reference's past which a hit on the same object counts as gone
/// through its first surface: ten times the largest the driver's transform alone has shown on
/// these cases (its p99 is about 7e-5).
pub const THROUGH: f64 = 1e-3;

/// |got - want| / |want|.
pub fn relative(got: f64, want: f64) -> f64 {
    (got - want).abs() / want.abs().max(1e-30)
}

impl TErrorSplit {
    /// The line `twinray probe` prints.
    pub fn summary(&self) -> String {
        let left_out = match (self.undecided, self.unrepeated) {
            (0, 0) => String::new(),
            (u, 0) => format!("; {u} left out, ambiguous in object space"),
            (u, r) => format!("; {u} left out, ambiguous in object space, {r} whose t did not repeat"),
        };
        let driver = match &self.driver {
            Some(d) => format!(" (the driver's transform would have given p99 {:.2e})", d.p99),
            None => String::new(),
        };
        format!(
            "relative t error by source, over {} hit{}: stages p99 {:.2e} (against the object-space ray they computed), their transform p99 {:.2e}{driver}{left_out}",
            self.rays,
            if self.rays == 1 { "" } else { "s" },
            self.stage.p99,
            self.transform.p99
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{MeshFiles, Scene};
    use glam::{UVec4, Vec4};

    /// A unit sphere at x = 1e4; rays along +z from z = -10 (world), t_ref = 9.
    fn reference() -> SceneReference {
        let scene = "[image]\nwidth = 4\nheight = 4\n\
                     [camera]\neye = [0.0, 0.0, -10.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_degrees = 45.0\n\
                     [materials.m]\nkind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\n\
                     [shapes.s]\nkind = \"sphere\"\nradius = 1.0\n\
                     [[objects]]\nshape = \"s\"\nmaterial = \"m\"\ntranslate = [10000.0, 0.0, 0.0]\n";
        let scene = Scene::parse(scene, "split.toml", MeshFiles::Builtin).expect("scene");
        SceneReference::new(&scene).expect("reference")
    }

    /// The record the witness pass writes for an object-space ray and t.
    fn witnessed(origin: Vec3, direction: Vec3, t: f32) -> ProbeResult {
        shifted(origin, direction, 0.0, t)
    }

    /// The record for an object-space ray that starts `shift` along the world ray.
    fn shifted(origin: Vec3, direction: Vec3, shift: f32, t: f32) -> ProbeResult {
        let d = direction.to_array().map(f32::to_bits);
        ProbeResult { normal_t: origin.extend(t), ids: UVec4::new(d[0], d[1], d[2], shift.to_bits()) }
    }

    /// A ray brought 7 units along before the transform: the reference answers the object-space
    /// ray from there (t' = 2) and puts the shift back, so the exact answer is exact.
    #[test]
    fn a_ray_brought_near_is_judged_in_the_world_rays_parameter() {
        let reference = reference();
        let ray = ProbeRay { origin: Vec4::new(10000.0, 0.0, -10.0, 0.0), direction: Vec4::new(0.0, 0.0, 1.0, 100.0) };
        let result = ProbeResult { normal_t: Vec4::new(0.0, 0.0, -1.0, 9.0), ids: UVec4::new(0, 0, 0, 1) };
        let near = shifted(Vec3::new(0.0, 0.0, -3.0), Vec3::Z, 7.0, 9.0);
        let hits = [AgreedHit { ray: &ray, t_ref: 9.0, result: &result, witness: &near, driver: None }];
        let s = split(&reference, hits.into_iter());
        assert_eq!((s.rays, s.undecided, s.unrepeated), (1, 0, 0));
        assert_eq!((s.transform.max, s.stage.max), (0.0, 0.0), "{s:?}");
    }

    #[test]
    fn the_stage_is_judged_on_the_ray_it_was_handed_and_the_transform_on_the_rest() {
        let reference = reference();
        let ray = ProbeRay { origin: Vec4::new(10000.0, 0.0, -10.0, 0.0), direction: Vec4::new(0.0, 0.0, 1.0, 100.0) };
        let result = ProbeResult { normal_t: Vec4::new(0.0, 0.0, -1.0, 9.0), ids: UVec4::new(0, 0, 0, 1) };
        // The driver moved the origin 2^-10 towards the sphere; the stage answered as before.
        let moved = witnessed(Vec3::new(0.0, 0.0, -10.0 + 0.0009765625), Vec3::Z, 9.0);
        let hits = [AgreedHit { ray: &ray, t_ref: 9.0, result: &result, witness: &moved, driver: None }];
        let s = split(&reference, hits.into_iter());
        assert_eq!((s.rays, s.undecided, s.unrepeated), (1, 0, 0));
        // The truth moved to t_obj = 9 - 2^-10, and the stage's 9 is 2^-10 off it.
        let t_obj = 9.0 - 0.0009765625;
        assert!((s.transform.max - 0.0009765625 / 9.0).abs() < 1e-15, "{s:?}");
        assert!((s.stage.max - 0.0009765625 / t_obj).abs() < 1e-15, "{s:?}");
    }

    #[test]
    fn a_witness_that_does_not_repeat_the_probe_or_missed_is_left_out() {
        let reference = reference();
        let ray = ProbeRay { origin: Vec4::new(10000.0, 0.0, -10.0, 0.0), direction: Vec4::new(0.0, 0.0, 1.0, 100.0) };
        let result = ProbeResult { normal_t: Vec4::new(0.0, 0.0, -1.0, 9.0), ids: UVec4::new(0, 0, 0, 1) };
        let other_t = witnessed(Vec3::new(0.0, 0.0, -10.0), Vec3::Z, 9.5);
        let missed = ProbeResult { normal_t: Vec4::ZERO, ids: UVec4::splat(NO_HIT) };
        // Grazing the sphere's silhouette in object space: the reference cannot decide it.
        let grazing = witnessed(Vec3::new(1.0, 0.0, -10.0), Vec3::Z, 9.0);
        let hits = [&other_t, &missed, &grazing].map(|w| AgreedHit {
            ray: &ray,
            t_ref: 9.0,
            result: &result,
            witness: w,
            driver: None,
        });
        let s = split(&reference, hits.into_iter());
        assert_eq!((s.rays, s.unrepeated, s.undecided), (0, 2, 1), "{s:?}");
        assert_eq!(witness(&missed), None);
    }
}
