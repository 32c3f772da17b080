//! Judging a probe run against the f64 reference: false hits and misses on the rays the
//! reference decides (ambiguous ones apart), and the error of t and of the normal.

use super::case::Generated;
use super::case::ProbeCase;
use super::run::{count_written, judgeable, no_payload, Launched, Records};
use super::split::THROUGH;
use super::split::{relative, split, AgreedHit, TErrorSplit};
use crate::reference::condition::{condition_multiple, t_condition};
use crate::reference::scene::SceneVerdict;
use crate::reference::stage::{lines, stage_of};
use crate::render::Written;
use crate::util::stats::Quantiles;
use glam::DVec3;
use serde::Serialize;
use twinray_shared::bindings::{NO_HIT, PROBE_NO_PAYLOAD};
use twinray_shared::layout::{ProbeRay, ProbeResult};

/// The accuracy of one probe run against the reference; serialised as `probe --json` prints it.
#[derive(Clone, Debug, Serialize)]
pub struct ProbeReport {
    pub case: String,
    pub set: String,
    pub device: String,
    pub rays: usize,
    /// Rays the reference decides (hit or miss); the others are within float noise of a
    /// boundary and are not counted as errors.
    pub decided: usize,
    pub ambiguous: usize,
    pub false_hits: usize,
    pub false_misses: usize,
    /// Both hit, but different objects.
    pub wrong_object: usize,
    /// Both hit the same object, the set more than `THROUGH` (relative) beyond the reference:
    /// the ray went through the surface the reference hits first and met the object again
    /// behind it (a gap between a mesh's triangles, where `edges` rays are aimed).
    pub through: usize,
    /// |t - t_ref| / t_ref over rays both hit.
    pub relative_t_error: Quantiles,
    /// The relative t error in units of its condition, error / (κ u), over the same hits
    /// (`reference::condition`): near 1 or below, as good as rounding the inputs allows.
    pub condition_multiple: Quantiles,
    /// The hit with the largest condition multiple, if any hit.
    pub worst_conditioned: Option<WorstHit>,
    /// |t - t_ref| in f32 ULPs of t_ref, 99th percentile.
    pub ulp_error_p99: f64,
    /// Angle between the normals, radians, 99th percentile.
    pub normal_angle_error_p99: f64,
    /// The relative t error split into the stages' own and the driver's transform's, over the
    /// hits the reference agrees with; none without a witness pass (the compute renderer's
    /// probe has none, nor a set from a folder without the `probe_witness` module).
    pub t_error_by_source: Option<TErrorSplit>,
    /// Median GPU milliseconds of tracing every ray once, and per million rays.
    pub gpu_ms: Option<f64>,
    pub gpu_ms_per_million_rays: Option<f64>,
    /// Per generator of the case: the rays it made, and how many of them the set hit.
    pub generators: Vec<Generated>,
    /// Where the GPU's coordinates were centred, launch by launch (`probe::run::Launched`);
    /// empty for one launch at world coordinates.
    pub launches: Vec<Launched>,
    /// The scene features the stages were specialised for (`features::names`): `far-instances`
    /// where an object lies far for its size from the GPU's origin or from where the rays start.
    pub features: String,
    /// Rays whose record the set never wrote (still the sentinel; judged as nothing else), and
    /// hits it wrote with a NaN or infinite t or normal.
    pub written: Written,
    /// False when the set left records unwritten or non-finite, or answered a decided ray
    /// otherwise than the reference (a false hit, a false miss, a wrong object).
    pub pass: bool,
    /// Why `pass` is false.
    pub failures: Vec<String>,
}

/// The failure of a report whose set answered decided rays otherwise than the reference (false
/// hits, false misses, wrong objects); none when it answered every one as the reference does.
pub fn wrong_answers(r: &ProbeReport) -> Option<String> {
    let (hits, misses, objects) = (r.false_hits, r.false_misses, r.wrong_object);
    (hits + misses + objects > 0).then(|| {
        format!(
            "{} decided rays answered otherwise than the f64 reference: {hits} false hits, {misses} false misses, \
             {objects} wrong object",
            hits + misses + objects
        )
    })
}

/// One hit named by a report: the ray's index in the case, its relative t error, the
/// condition κ of its t and the error in units of κ u.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct WorstHit {
    pub ray: usize,
    pub relative_error: f64,
    pub condition: f64,
    pub multiple: f64,
}

fn ulp(x: f32) -> f64 {
    let x = x.abs();
    f64::from(f32::from_bits(x.to_bits() + 1) - x)
}

/// How one ray's result compares with the reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Within float noise of a boundary: either answer is right.
    Ambiguous,
    /// Both miss, or both hit the same object.
    Agrees,
    FalseHit,
    FalseMiss,
    WrongObject,
    /// The set never wrote this ray's record.
    Unwritten,
    /// The ray's hit or miss stage wrote no payload.
    NoPayload,
}

impl Outcome {
    /// The word `--rays-out` writes.
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Ambiguous => "ambiguous",
            Outcome::Agrees => "agrees",
            Outcome::FalseHit => "false_hit",
            Outcome::FalseMiss => "false_miss",
            Outcome::WrongObject => "wrong_object",
            Outcome::Unwritten => "unwritten",
            Outcome::NoPayload => "no_payload",
        }
    }
}

/// One ray judged: its reference verdict and the outcome of the result against it.
pub struct Judged {
    pub ray: ProbeRay,
    pub verdict: SceneVerdict,
    pub outcome: Outcome,
}

/// The outcome of a record with `ids` (written or not) against the reference's `verdict`.
pub fn outcome(verdict: SceneVerdict, written: bool, ids: glam::UVec4) -> Outcome {
    let got_hit = ids.w != NO_HIT;
    match verdict {
        _ if ids.w == PROBE_NO_PAYLOAD => Outcome::NoPayload,
        _ if !written => Outcome::Unwritten,
        SceneVerdict::Ambiguous => Outcome::Ambiguous,
        SceneVerdict::Miss if got_hit => Outcome::FalseHit,
        SceneVerdict::Miss => Outcome::Agrees,
        SceneVerdict::Hit { .. } if !got_hit => Outcome::FalseMiss,
        SceneVerdict::Hit { object, .. } if ids.x as usize != object => Outcome::WrongObject,
        SceneVerdict::Hit { .. } => Outcome::Agrees,
    }
}

/// Each result against the reference of its ray, in order.
pub fn judge(case: &ProbeCase, results: &[ProbeResult]) -> Vec<Judged> {
    case.reference_rays()
        .iter()
        .zip(results)
        .map(|(ray, result)| {
            let o = ray.origin.truncate().as_dvec3();
            let d = ray.direction.truncate().as_dvec3();
            let verdict = case.reference.trace(o, d, f64::from(ray.origin.w), f64::from(ray.direction.w));
            let outcome = outcome(verdict, super::run::record_written(result), result.ids);
            Judged { ray: *ray, verdict, outcome }
        })
        .collect()
}

/// Judges each result against the reference of its ray; with the records of the witness pass,
/// splits the t error by source.
pub fn evaluate(case: &ProbeCase, records: Records<'_>, set: &str, device: &str, gpu_ms: Option<f64>) -> ProbeReport {
    let results = records.results;
    let mut report = ProbeReport {
        case: case.file.name.clone(),
        set: set.into(),
        device: device.into(),
        rays: case.rays.len(),
        decided: 0,
        ambiguous: 0,
        false_hits: 0,
        false_misses: 0,
        wrong_object: 0,
        through: 0,
        relative_t_error: Quantiles::default(),
        condition_multiple: Quantiles::default(),
        worst_conditioned: None,
        ulp_error_p99: 0.0,
        normal_angle_error_p99: 0.0,
        t_error_by_source: None,
        gpu_ms,
        gpu_ms_per_million_rays: gpu_ms.map(|ms| ms * 1e6 / case.rays.len().max(1) as f64),
        generators: case.generated.clone(),
        launches: records.launches.to_vec(),
        features: twinray_shared::features::names(records.features),
        written: count_written(results),
        pass: true,
        failures: Vec::new(),
    };
    report.failures = report.written.problems(set, "rays");
    report.pass = report.failures.is_empty();
    let (mut rel, mut ulps, mut angles, mut multiples) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let judged = judge(case, results);
    for (i, (judged, result)) in judged.iter().zip(results).enumerate() {
        match judged.outcome {
            Outcome::Ambiguous => report.ambiguous += 1,
            Outcome::FalseHit => report.false_hits += 1,
            Outcome::FalseMiss => report.false_misses += 1,
            Outcome::WrongObject => report.wrong_object += 1,
            Outcome::Unwritten | Outcome::NoPayload => {}
            Outcome::Agrees => {
                if let SceneVerdict::Hit { t, normal, object } = judged.verdict {
                    let got_t = f64::from(result.normal_t.w);
                    report.through += usize::from(went_through(got_t, t));
                    rel.push(relative(got_t, t));
                    let hit = conditioned(case, &judged.ray, (object, t, normal), relative(got_t, t), i);
                    if report.worst_conditioned.is_none_or(|w| hit.multiple > w.multiple) {
                        report.worst_conditioned = Some(hit);
                    }
                    multiples.push(hit.multiple);
                    ulps.push((got_t - t).abs() / ulp(t as f32));
                    let n = result.normal_t.truncate().normalize().as_dvec3();
                    angles.push(n.dot(normal).clamp(-1.0, 1.0).acos());
                }
            }
        }
    }
    let unjudged = report.written.unwritten + report.written.no_payload_rays;
    report.decided = report.rays - report.ambiguous - unjudged as usize;
    let stages = judged.iter().zip(results).filter(|(_, r)| no_payload(r)).map(|(j, _)| &j.verdict);
    report.failures.extend(no_payload_lines(&case.scene, stages, set));
    // A verdict, not only figures: a ray decided otherwise than the reference fails the case.
    report.failures.extend(wrong_answers(&report));
    report.pass = report.failures.is_empty();
    let all = &judged;
    for (generated, judged) in report.generators.iter_mut().zip(generator_spans(case)) {
        let hits = |range: std::ops::Range<usize>, results: &[ProbeResult]| {
            results[range].iter().filter(|r| judgeable(r) && r.ids.w != NO_HIT).count()
        };
        generated.hit = Some(hits(judged.clone(), results));
        generated.through = Some(
            all[judged.clone()]
                .iter()
                .zip(&results[judged])
                .filter(|(j, r)| match j.verdict {
                    SceneVerdict::Hit { t, .. } => {
                        j.outcome == Outcome::Agrees && went_through(f64::from(r.normal_t.w), t)
                    }
                    _ => false,
                })
                .count(),
        );
    }
    report.t_error_by_source = records.witness.map(|witness| {
        let hits =
            judged.iter().zip(results).zip(witness).enumerate().filter_map(|(i, ((judged, result), witness))| {
                let SceneVerdict::Hit { t, .. } = judged.verdict else { return None };
                let driver = records.driver.and_then(|d| d.get(i));
                let hit = AgreedHit { ray: &judged.ray, t_ref: t, result, witness, driver };
                (judged.outcome == Outcome::Agrees).then_some(hit)
            });
        split(&case.reference, hits)
    });
    report.relative_t_error = Quantiles::of(rel);
    report.condition_multiple = Quantiles::of(multiples);
    report.ulp_error_p99 = Quantiles::of(ulps).p99;
    report.normal_angle_error_p99 = Quantiles::of(angles).p99;
    report
}

/// Ray `index`'s hit (`object`, t and normal of the reference) with its condition and the
/// multiple `relative_error` is of it.
fn conditioned(
    case: &ProbeCase,
    ray: &ProbeRay,
    (object, t, normal): (usize, f64, DVec3),
    relative_error: f64,
    index: usize,
) -> WorstHit {
    let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
    let condition = t_condition(&case.reference.objects[object], o, d, t, normal);
    WorstHit { ray: index, relative_error, condition, multiple: condition_multiple(relative_error, condition) }
}

/// The lines naming the stage each ray with no payload went to, by the reference's `verdicts`.
fn no_payload_lines<'a>(
    scene: &crate::scene::Scene,
    verdicts: impl Iterator<Item = &'a SceneVerdict>,
    set: &str,
) -> Vec<String> {
    let mut verdicts = verdicts.peekable();
    // Most probes have none: build the scene's data only for those that do.
    if verdicts.peek().is_none() {
        return Vec::new();
    }
    let data = scene.build();
    let mut counts = std::collections::BTreeMap::new();
    for v in verdicts {
        *counts.entry(stage_of(&data, v)).or_insert(0) += 1;
    }
    lines(&counts, set, "by where the f64 reference sends each")
}

/// Whether a hit at `got` on the object the reference hits at `t` lies beyond it by more than
/// `THROUGH`.
pub(crate) fn went_through(got: f64, t: f64) -> bool {
    got > t && relative(got, t) > THROUGH
}

/// The index range of each generator's rays among the case's rays (explicit rays first).
fn generator_spans(case: &ProbeCase) -> Vec<std::ops::Range<usize>> {
    let mut start = case.file.rays.len();
    case.generated
        .iter()
        .map(|g| {
            start += g.made;
            start - g.made..start
        })
        .collect()
}

/// Writes one CSV row per ray (`probe --rays-out`): the ray, the reference's answer, and for
/// each set its hit, t, object, normal and outcome.
pub fn write_rays_csv(
    out: &mut impl std::io::Write,
    case: &ProbeCase,
    sets: &[(&str, &[ProbeResult])],
) -> std::io::Result<()> {
    let mut header = String::from("ray,ox,oy,oz,dx,dy,dz,t_min,t_max,ref_hit,ref_t,ref_object,ref_ambiguous");
    for (name, _) in sets {
        for column in ["hit", "t", "object", "nx", "ny", "nz", "outcome"] {
            header += &format!(",{}_{column}", csv_name(name));
        }
    }
    writeln!(out, "{header}")?;
    let judged: Vec<Vec<Judged>> = sets.iter().map(|(_, results)| judge(case, results)).collect();
    for (i, ray) in case.reference_rays().iter().enumerate() {
        let (o, d) = (ray.origin, ray.direction);
        let mut row = format!("{i},{},{},{},{},{},{},{},{}", o.x, o.y, o.z, d.x, d.y, d.z, o.w, d.w);
        row += &match judged.first().map(|j| j[i].verdict) {
            Some(SceneVerdict::Hit { object, t, .. }) => format!(",1,{t},{object},0"),
            Some(SceneVerdict::Miss) => ",0,,,0".into(),
            Some(SceneVerdict::Ambiguous) | None => ",,,,1".into(),
        };
        for ((_, results), judged) in sets.iter().zip(&judged) {
            let r = results[i];
            row += &if r.ids.w == NO_HIT || !judgeable(&r) {
                ",0,,,,,".into()
            } else {
                let n = r.normal_t;
                format!(",1,{},{},{},{},{}", n.w, r.ids.x, n.x, n.y, n.z)
            };
            row += &format!(",{}", judged[i].outcome.name());
        }
        writeln!(out, "{row}")?;
    }
    Ok(())
}

/// A set's label as a CSV column prefix: letters, digits and '_' only.
fn csv_name(set: &str) -> String {
    set.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect()
}

impl ProbeReport {
    /// The text `twinray probe` prints.
    pub fn summary(&self) -> String {
        let t = &self.relative_t_error;
        let ms = match (self.gpu_ms, self.gpu_ms_per_million_rays) {
            (Some(ms), Some(per)) => format!("GPU {ms:.3} ms ({per:.3} ms per million rays)"),
            _ => "GPU time n/a".into(),
        };
        let failures: String = self.failures.iter().map(|f| format!("  FAIL: {f}\n")).collect();
        failures + &format!(
            "case {} with {} on {}: {} rays, {} decided, {} ambiguous\n  false hits {}, false misses {}, wrong object {}, through the first surface {}\n  relative t error: median {:.2e}, p99 {:.2e}, max {:.2e}; ULP error p99 {:.1}\n  normal angle error p99 {:.2e} rad\n  {ms}\n",
            self.case, self.set, self.device, self.rays, self.decided, self.ambiguous, self.false_hits,
            self.false_misses, self.wrong_object, self.through, t.median, t.p99, t.max, self.ulp_error_p99, self.normal_angle_error_p99
        ) + &self.condition_line() + &match &self.t_error_by_source {
            Some(split) => format!("  {}\n", split.summary()),
            None => "  relative t error by source: n/a (no witness pass: the compute renderer's probe, or a folder set without probe_witness)\n".into(),
        } + &if self.generators.is_empty() { String::new() } else { format!("  generators: {}\n", self.generators_made()) }
            + &self.launches_line()
            + &format!("  scene features: {}\n", self.features)
    }

    /// The t error in units of its condition, and the hit where it is largest.
    pub fn condition_line(&self) -> String {
        let Some(w) = &self.worst_conditioned else { return String::new() };
        let c = &self.condition_multiple;
        format!(
            "  t error in units of its condition, error / (κ u): median {:.2}, p99 {:.2}, max {:.2} (ray {}: error {:.2e}, κ {:.3e})\n",
            c.median, c.p99, c.max, w.ray, w.relative_error, w.condition
        )
    }

    /// Where the GPU's coordinates were centred, when not at the world origin in one launch.
    pub fn launches_line(&self) -> String {
        if self.launches.is_empty() {
            return String::new();
        }
        let each: Vec<String> = self
            .launches
            .iter()
            .map(|l| format!("({}, {}, {}) for {}", l.origin[0], l.origin[1], l.origin[2], l.rays))
            .collect();
        format!("  local origins, by what the rays meet: {}\n", each.join("; "))
    }

    /// Per generator, the rays it made and how many of them the set hit.
    pub fn generators_made(&self) -> String {
        let each = self.generators.iter().map(|g| match g.hit {
            Some(hit) => format!("{} made {}, {hit} hit, {} through", g.kind, g.made, g.through.unwrap_or(0)),
            None => format!("{} made {}", g.kind, g.made),
        });
        each.collect::<Vec<_>>().join("; ")
    }
}
