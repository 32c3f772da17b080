//! The chosen launches against world coordinates and against each ray launched alone: a case
//! probed at the origins twinray chooses (`scene::launches`), again with the GPU at the world
//! origin, and a sample of its rays each launched at its own start, with one set, ray by ray.
//! The local origin exists to make rays more accurate; a case where it makes one ray wrong that
//! world coordinates get right, or makes the relative t error's p99 grow, is a failure, and so is
//! a ray whose error at its launch is more than `ALONE_SLACK` times what it is alone (`twinray
//! stability --against-world`, `tests/origin.rs`).

use super::case::ProbeCase;
use super::report::{judge, outcome, went_through, Judged, Outcome};
use super::run::{probe, probe_alone, record_written, Launched, ProbeOutput, ProbeResult};
use super::split::relative;
use crate::error::Result;
use crate::reference::condition::{t_condition, F32_UNIT_ROUNDOFF};
use crate::reference::scene::SceneVerdict;
use crate::sets::ShaderSet;
use crate::util::stats::Quantiles;
use crate::vk::context::Context;
use std::sync::Arc;

/// How much the chosen origins' p99 may exceed world coordinates' before it counts as grown:
/// two binades. The chosen origins move every ray exactly and leave it at most a quarter of
/// its world magnitude, so the ray and what lies near it are rounded at a smaller magnitude;
/// but a ray the problem
/// makes ill-conditioned (a graze, a thin squashed shape hit again by its own surface rays)
/// turns any change of rounding, even a smaller one, into an error larger or smaller by a
/// factor of a few, and a p99 over a few dozen such hits follows them. On lavapipe, whose
/// world-to-object matrix changes with the translation, the chosen p99 exceeded world
/// coordinates' in 64 of 400 random rows (200 cases, both sets), by at most 2.5 times, the
/// median ratio 0.87; on the H200 in none of 300. A single origin for rays far apart, the
/// defect this check is for, grew it 38 to 1000 times (docs/numerics.md, "The local origin").
pub const P99_SLACK: f64 = 4.0;

/// How much larger a ray's relative t error may be at the chosen origins than launched alone,
/// at its own start: 2 times the larger of its error alone and κ u, what rounding the problem's
/// inputs allows (`reference::condition`). Below κ u an error is the noise of any rounding, and
/// a ray rounded 1e-9 alone and 3e-9 in its launch has lost nothing the problem held.
pub const ALONE_SLACK: f64 = 2.0;

/// Rays of a case launched alone, at most: each is a launch of its own (a TLAS rebuilt and a
/// trace), so a case's hits are sampled evenly.
pub const ALONE_RAYS: usize = 96;

/// A sample of a case's rays, at the chosen origins and each launched alone.
#[derive(Clone, Debug, serde::Serialize)]
pub struct AloneCheck {
    /// Rays compared: hits the reference decides, sampled evenly.
    pub rays: usize,
    /// Rays wrong at the chosen origins that get it right alone, or whose error there exceeds
    /// `ALONE_SLACK` times the larger of their error alone and κ u.
    pub grown: usize,
    /// The largest ratio of a ray's error at the chosen origins to the larger of its error alone
    /// and κ u.
    pub largest: f64,
}

/// One side of the comparison: the case's rays as one placement of the GPU's origin got them.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Side {
    /// Rays the reference decides.
    pub decided: usize,
    /// False hits, false misses, wrong objects and rays through the first surface.
    pub wrong: usize,
    /// The relative t error's p99 over hits on the right object.
    pub p99: f64,
}

/// A case with one set at its chosen origins and at world coordinates.
#[derive(Clone, Debug, serde::Serialize)]
pub struct OriginCheck {
    pub case: String,
    pub set: String,
    /// The chosen launches; empty where the scene is probed at world coordinates anyway (no
    /// object far from the world origin for its size, or `gpu_origin = "world"`).
    pub launches: Vec<Launched>,
    pub chosen: Side,
    pub world: Side,
    /// The chosen launches against rays launched alone.
    pub alone: AloneCheck,
    /// Rays wrong at the chosen origins that world coordinates get right.
    pub worse_rays: usize,
    /// Rays right at the chosen origins that world coordinates get wrong.
    pub better_rays: usize,
    /// What makes the chosen origins worse; empty when they are not.
    pub failures: Vec<String>,
}

/// Probes `case` with `set` at its chosen origins and at world coordinates (once: rays
/// launched at the world origin anyway are not probed twice), one untimed pass each.
pub fn check(ctx: &Arc<Context>, case: &ProbeCase, set: &ShaderSet) -> Result<OriginCheck> {
    let out = probe(ctx, &case.scene, set, &case.rays, 0, 1)?;
    let chosen_rays = fates(case, &out);
    // Launched at the world origin alone, the rays already saw the scene as world coordinates
    // show it: the same GPU copy, the same rays.
    let at_world = out.launches.iter().all(|l| l.origin == [0.0; 3]);
    let world_rays = match case.scene.at_world_origin() {
        std::borrow::Cow::Owned(world) if !at_world => fates(case, &probe(ctx, &world, set, &case.rays, 0, 1)?),
        _ => chosen_rays.clone(),
    };
    let alone = against_alone(ctx, (case, set), &out)?;
    let pairs = || chosen_rays.iter().zip(&world_rays);
    let worse_rays = pairs().filter(|(c, w)| c.wrong && w.right).count();
    let better_rays = pairs().filter(|(c, w)| c.right && w.wrong).count();
    let (chosen, world) = (side(&chosen_rays), side(&world_rays));
    let mut failures = Vec::new();
    if worse_rays > 0 {
        failures.push(format!("{worse_rays} rays wrong at the chosen origins that world coordinates get right"));
    }
    if chosen.p99 > P99_SLACK * world.p99 {
        failures.push(format!("relative t p99 grew from {:.2e} at world coordinates to {:.2e}", world.p99, chosen.p99));
    }
    if alone.grown > 0 {
        failures.push(format!(
            "{} of {} rays more than {ALONE_SLACK} times worse than launched alone (largest {:.1})",
            alone.grown, alone.rays, alone.largest
        ));
    }
    Ok(OriginCheck {
        case: case.file.name.clone(),
        set: set.to_string(),
        launches: out.launches,
        chosen,
        world,
        alone,
        worse_rays,
        better_rays,
        failures,
    })
}

/// A sample of the case's decided hits probed each alone (`run::probe_alone`), against what
/// the chosen launches gave them (`out`).
fn against_alone(ctx: &Arc<Context>, (case, set): (&ProbeCase, &ShaderSet), out: &ProbeOutput) -> Result<AloneCheck> {
    let judged = judge(case, &out.results);
    let hits: Vec<usize> = judged
        .iter()
        .enumerate()
        .filter(|(_, j)| matches!(j.verdict, SceneVerdict::Hit { .. }))
        .map(|(i, _)| i)
        .collect();
    let sample: Vec<usize> = hits.iter().step_by(hits.len().div_ceil(ALONE_RAYS).max(1)).copied().collect();
    if sample.is_empty() || out.launches.is_empty() {
        return Ok(AloneCheck { rays: 0, grown: 0, largest: 0.0 });
    }
    let alone = probe_alone(ctx, &case.scene, set, &case.rays, &sample)?;
    let (mut grown, mut largest) = (0, 0.0f64);
    for (&i, result) in sample.iter().zip(&alone) {
        let SceneVerdict::Hit { object, t, normal } = judged[i].verdict else { continue };
        let fate = |r: &ProbeResult| fate(&judged[i], r);
        let (chosen, by_itself) = (fate(&out.results[i]), fate(result));
        let ray = judged[i].ray;
        let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
        let floor = t_condition(&case.reference.objects[object], o, d, t, normal) * F32_UNIT_ROUNDOFF;
        let ratio = match (chosen.error, by_itself.error) {
            (Some(c), Some(a)) => c / a.max(floor),
            _ if chosen.wrong && by_itself.right => f64::INFINITY,
            _ => 0.0,
        };
        grown += usize::from(ratio > ALONE_SLACK);
        largest = largest.max(ratio);
    }
    Ok(AloneCheck { rays: sample.len(), grown, largest })
}

/// One ray's fate: decided or not, wrong or right, and its relative t error where it hit the
/// reference's object and did not go through it.
#[derive(Clone, Copy)]
struct Fate {
    decided: bool,
    wrong: bool,
    right: bool,
    error: Option<f64>,
}

fn fates(case: &ProbeCase, out: &ProbeOutput) -> Vec<Fate> {
    judge(case, &out.results).iter().zip(&out.results).map(|(j, r)| fate(j, r)).collect()
}

/// The fate of the result `r` of the ray judged as `j` (its outcome may be another result's:
/// only its verdict and ray are read).
fn fate(j: &Judged, r: &ProbeResult) -> Fate {
    let outcome = outcome(j.verdict, record_written(r), r.ids);
    let got = f64::from(r.normal_t.w);
    let t_ref = match j.verdict {
        SceneVerdict::Hit { t, .. } if outcome == Outcome::Agrees => Some(t),
        _ => None,
    };
    let through = t_ref.is_some_and(|t| went_through(got, t));
    let wrong = through || matches!(outcome, Outcome::FalseHit | Outcome::FalseMiss | Outcome::WrongObject);
    Fate {
        decided: outcome != Outcome::Ambiguous,
        wrong,
        right: outcome == Outcome::Agrees && !through,
        error: t_ref.filter(|_| !through).map(|t| relative(got, t)),
    }
}

fn side(fates: &[Fate]) -> Side {
    Side {
        decided: fates.iter().filter(|f| f.decided).count(),
        wrong: fates.iter().filter(|f| f.wrong).count(),
        p99: Quantiles::of(fates.iter().filter_map(|f| f.error).collect()).p99,
    }
}

/// The table `twinray stability --against-world` prints: a row per case and set.
pub fn table(checks: &[OriginCheck]) -> String {
    let mut s = format!(
        "{:<28} {:<5} {:>14} {:>7} {:>13} {:>13} {:>6} {:>6} {:>10} {:>10} {:>12} {:>8}  verdict\n",
        "case",
        "set",
        "local origins",
        "decided",
        "wrong chosen",
        "wrong world",
        "worse",
        "better",
        "p99 chosen",
        "p99 world",
        "grown/alone",
        "largest"
    );
    for c in checks {
        let verdict =
            if c.failures.is_empty() { "not worse".to_string() } else { format!("WORSE: {}", c.failures.join("; ")) };
        let local = c.launches.iter().filter(|l| l.origin != [0.0; 3]).count();
        let launches = match (local, c.launches.len()) {
            (0, _) => "none".to_string(),
            (n, all) if n == all => n.to_string(),
            (n, _) => format!("{n} + world"),
        };
        let alone = format!("{}/{}", c.alone.grown, c.alone.rays);
        s += &format!(
            "{:<28} {:<5} {:>14} {:>7} {:>13} {:>13} {:>6} {:>6} {:>10.2e} {:>10.2e} {alone:>12} {:>8.2}  {verdict}\n",
            c.case,
            c.set,
            launches,
            c.chosen.decided,
            c.chosen.wrong,
            c.world.wrong,
            c.worse_rays,
            c.better_rays,
            c.chosen.p99,
            c.world.p99,
            c.alone.largest
        );
    }
    s
}
