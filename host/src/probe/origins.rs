//! The local origin against world coordinates: a case probed at the origins twinray chooses
//! (`scene::origin::launches`) and again with the GPU at the world origin, with one set, ray
//! by ray. The local origin exists to make rays more accurate; a case where it makes one ray
//! wrong that world coordinates get right, or makes the relative t error's p99 grow, is a
//! failure (`twinray stability --against-world`, `tests/origin.rs`).

use super::case::ProbeCase;
use super::report::{judge, went_through, Outcome};
use super::run::{probe, Launched, ProbeOutput};
use super::split::relative;
use crate::error::Result;
use crate::reference::scene::SceneVerdict;
use crate::shaders::ShaderSet;
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
    Ok(OriginCheck {
        case: case.file.name.clone(),
        set: set.to_string(),
        launches: out.launches,
        chosen,
        world,
        worse_rays,
        better_rays,
        failures,
    })
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
    judge(case, &out.results)
        .iter()
        .zip(&out.results)
        .map(|(j, r)| {
            let got = f64::from(r.normal_t.w);
            let t_ref = match j.verdict {
                SceneVerdict::Hit { t, .. } if j.outcome == Outcome::Agrees => Some(t),
                _ => None,
            };
            let through = t_ref.is_some_and(|t| went_through(got, t));
            let wrong = through || matches!(j.outcome, Outcome::FalseHit | Outcome::FalseMiss | Outcome::WrongObject);
            Fate {
                decided: j.outcome != Outcome::Ambiguous,
                wrong,
                right: j.outcome == Outcome::Agrees && !through,
                error: t_ref.filter(|_| !through).map(|t| relative(got, t)),
            }
        })
        .collect()
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
        "{:<28} {:<5} {:>14} {:>7} {:>13} {:>13} {:>6} {:>6} {:>10} {:>10}  verdict\n",
        "case",
        "set",
        "local origins",
        "decided",
        "wrong chosen",
        "wrong world",
        "worse",
        "better",
        "p99 chosen",
        "p99 world"
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
        s += &format!(
            "{:<28} {:<5} {:>14} {:>7} {:>13} {:>13} {:>6} {:>6} {:>10.2e} {:>10.2e}  {verdict}\n",
            c.case,
            c.set,
            launches,
            c.chosen.decided,
            c.chosen.wrong,
            c.world.wrong,
            c.worse_rays,
            c.better_rays,
            c.chosen.p99,
            c.world.p99
        );
    }
    s
}
