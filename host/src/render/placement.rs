//! Placements: each an independent making of every set's pipeline, SBT and descriptors over a
//! fresh upload of the scene, in an order of its own, each giving one median per set.
//!
//! Where the driver puts a pipeline's code moves its trace time. Measured on the H100 (issue
//! 26, `bench/reports/timing/`): two salted copies of one GLSL set built one after the other
//! and traced interleaved took 2.33 and 2.26 ms on cylinder at 16 spp, the slower being
//! whichever was built first, every time, in every process; tracing them in the other order,
//! or moving their SBTs, changed nothing; making one to three other pipelines first moved
//! each copy's time (2.18 to 2.33 ms) and which copy was slower. Freed code is reused: a
//! pipeline built after another was released lands where that one was.
//!
//! So within a placement the sets do not share the GPU at once: each is built, warmed up,
//! timed and released before the next is built, and every set of the placement runs from the
//! same place. Placements differ in where that is: each pair of placements first makes
//! `spacers` pipelines that it keeps, moving the code of what follows. The orders are the
//! rows of a Williams design ([`orders`]): every set at every position, and after every other
//! set, equally often, each order followed by its reverse so that a drift of the GPU's clocks
//! over a placement reaches every set alike. A ratio's uncertainty is the spread of the placements' ratios
//! (`util::interval`): how much a set's time owes to where its code landed, and to drift.
//!
//! A render of several placements first renders one more whose times it drops: on the H100 the
//! first placement of a process ran 5% slower than the rest (sphere at 16 spp: 2.47 and 2.37
//! ms against 2.33), and the first after a second of idle GPU (the bench writing images) up to
//! 3x (7.2 ms), though each set had its 200 ms of warm-up traces: the clocks take longer than
//! that to settle. (The floor is now 1000 ms, `prepare::MIN_WARM_MS`.)

use super::libraries::Libraries;
use super::pipeline::ScenePipeline;
use super::upload::UploadedScene;
use crate::error::Result;
use crate::shaders::ShaderSet;
use crate::util::interval::RatioInterval;
use crate::vk::context::{Context, PipelineKind};
use serde::Serialize;
use std::sync::Arc;
use twinray_shared::random::SplitMix64;

/// Placements `compare` and `bench` time over unless told otherwise: three pairs of orders.
pub const DEFAULT_PLACEMENTS: u32 = 6;

/// The order of each placement of `sets` sets: the rows of a Williams design, cycled (see
/// [`design`]). A set's time depends on where it comes in a placement and on which set was
/// built and released just before it: on the H100 (issue 40, swarm at 16 spp, `bench --null`,
/// so three sets) the same comparison gave Rust/GLSL 1.116 in three processes with
/// `--sets glsl,rust` and 0.991 in three with `--sets rust,glsl`, each interval (±3%)
/// excluding the other's estimate, when pairs of a shuffled order and its reverse left the
/// second set never in the middle. Over a whole number of the design's rows every set comes
/// at every position, and after every other set, equally often, so the label order cannot
/// favour one.
pub fn orders(sets: usize, placements: u32) -> Vec<Vec<usize>> {
    let rows = design(sets);
    (0..placements.max(1) as usize).map(|p| rows[p % rows.len()].clone()).collect()
}

/// A Williams design for `n` sets: `n` orders (`2n` for odd `n`) in which every set takes
/// every position equally often and follows every other set equally often; each order is
/// followed by its reverse, so that a drift of the GPU's clocks reaches every set alike.
pub fn design(n: usize) -> Vec<Vec<usize>> {
    if n <= 1 {
        return vec![vec![0; n]];
    }
    // 0, 1, n-1, 2, n-2, ...: consecutive differences that take every value once.
    let mut first = vec![0];
    let (mut low, mut high) = (1, n - 1);
    while first.len() < n {
        first.push(low);
        low += 1;
        if first.len() < n {
            first.push(high);
            high -= 1;
        }
    }
    let rows: Vec<Vec<usize>> = (0..n).map(|r| first.iter().map(|x| (x + r) % n).collect()).collect();
    let mut out: Vec<Vec<usize>> = Vec::with_capacity(2 * n);
    for row in rows {
        let reverse: Vec<usize> = row.iter().rev().copied().collect();
        // For even n the design holds each row's reverse already.
        if !out.contains(&row) {
            out.push(row);
            out.push(reverse);
        }
    }
    out
}

/// Spacer pipelines placement `p` makes first: 0, 0, 1, 1, ..., 7, 7, 0, ... (each pair of
/// orders at one place). Eight places, so that up to eight rounds of `--processes` time eight
/// different ones: a repeated place times the same as before (to 0.5% on the H100), and
/// would narrow an interval over places without adding one.
pub fn spacers(p: usize) -> u32 {
    ((p / 2) % PLACES) as u32
}

/// The places [`spacers`] cycles through.
pub const PLACES: usize = 8;

/// The placement round `round` of a measurement in rounds of `placements` placements each
/// starts at: past every placement of the rounds before, rounded up to a pair, since each
/// pair of placements makes the same spacers. Each round then times at places of its own.
pub fn round_start(round: u32, placements: u32) -> u32 {
    round * placements.next_multiple_of(2)
}

/// Which of `sets` timed sets each spacer of placement `p` copies: drawn with a fixed seed
/// per placement, so that the pipelines made before the timed ones are of every kind timed.
/// On the H100 the set list decided a regime of the whole process (Rust or GLSL at its
/// alone speed, the other 4-7% slower; `bench/reports/inspect-h100/`), which spacers of
/// the GLSL set alone never reached.
pub fn spacer_sets(p: usize, sets: usize) -> Vec<usize> {
    let mut rng = SplitMix64(SEED ^ (p as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
    (0..spacers(p)).map(|_| (rng.next_u64() % sets.max(1) as u64) as usize).collect()
}

/// The seed of the spacers' draws: fixed, so that a command repeats its placements exactly.
const SEED: u64 = 0x7417_2a79_5eed_0026;

/// Pipelines made only to be kept while a placement's sets are built and timed, so that their
/// code lands further on: salted copies of the timed sets (`ShaderSet::copy`, numbered from
/// 1000 so that no timed set shares their code), drawn by [`spacer_sets`].
pub(super) struct Spacers {
    _pipelines: Vec<ScenePipeline>,
    _libraries: Libraries,
}

impl Spacers {
    pub fn new(ctx: &Arc<Context>, scene: &UploadedScene, sets: &[(ShaderSet, PipelineKind)]) -> Result<Spacers> {
        let libraries = Libraries::default();
        let plan = &scene.data.plan;
        let pipelines = sets
            .iter()
            .enumerate()
            .map(|(k, (set, kind))| {
                let linking = (*kind == PipelineKind::Libraries).then_some(&libraries);
                ScenePipeline::new(ctx, &set.copy(1000 + k as u32), plan, plan.render_raygen(), linking)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Spacers { _pipelines: pipelines, _libraries: libraries })
    }
}

/// One set's times by placement.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PlacementTimes {
    /// The median GPU milliseconds of the set's timed traces in each placement.
    pub median_ms: Vec<f64>,
    /// The set's position (0: built and traced first in each round) in each placement.
    pub position: Vec<u32>,
    /// Timed alone in processes (`render::Isolation`): the placement each round's process
    /// started at (`--first-placement`), whose layouts it timed. Empty otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub first_placement: Vec<u32>,
    /// Rounds whose process was slow and was timed again (`render::isolated::RETIME_ABOVE`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub retimed: Vec<Retimed>,
}

/// A round timed twice: slow, then again at the same place.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Retimed {
    pub round: u32,
    /// The geometric means of the first process's and the second's placements (ms).
    pub first_ms: f64,
    pub again_ms: f64,
}

impl Retimed {
    /// The line the bench prints for it: `what` names the scene, sample count and set.
    pub fn line(&self, what: &str) -> String {
        let (round, first, again) = (self.round, self.first_ms, self.again_ms);
        let kept = if again < first { "the second kept" } else { "the first kept: a slow place" };
        format!("{what}: round {round}'s process ran slow ({first:.3} ms); timed again: {again:.3} ms, {kept}")
    }
}

impl PlacementTimes {
    /// `Retimed::line` for each round timed again, each after `indent` and ending in a newline:
    /// what `bench` and `compare` print, so that a re-timed round is never silent.
    pub fn retimed_lines(&self, indent: &str, what: &str) -> String {
        self.retimed.iter().map(|r| format!("{indent}{}\n", r.line(what))).collect()
    }

    /// The ratio of these times to `other`'s, placement by placement, with its interval.
    pub fn ratio_to(&self, other: &PlacementTimes) -> Option<RatioInterval> {
        RatioInterval::paired(&self.median_ms, &other.median_ms)
    }
}

#[cfg(test)]
mod tests {
    use super::orders;

    #[test]
    fn every_set_takes_every_place_and_follows_every_other_equally_often() {
        for sets in 1..=7 {
            let rows = super::design(sets);
            assert_eq!(rows.len(), if sets % 2 == 1 && sets > 1 { 2 * sets } else { sets }, "{sets} sets");
            let mut at = vec![vec![0; sets]; sets];
            let mut after = vec![vec![0; sets]; sets];
            for row in &rows {
                let mut sorted = row.clone();
                sorted.sort();
                assert_eq!(sorted, (0..sets).collect::<Vec<_>>(), "a permutation");
                for (position, &set) in row.iter().enumerate() {
                    at[set][position] += 1;
                }
                for pair in row.windows(2) {
                    after[pair[1]][pair[0]] += 1;
                }
            }
            let each = rows.len() / sets.max(1);
            assert!(at.iter().flatten().all(|&n| n == each), "{sets} sets: positions {at:?}");
            for (set, row) in after.iter().enumerate() {
                let others: Vec<_> = row.iter().enumerate().filter(|(o, _)| *o != set).map(|(_, n)| *n).collect();
                assert!(others.windows(2).all(|w| w[0] == w[1]), "{sets} sets: predecessors {after:?}");
            }
            for pair in rows.chunks(2).filter(|p| p.len() == 2) {
                assert_eq!(pair[1], pair[0].iter().rev().copied().collect::<Vec<_>>(), "each order, then its reverse");
            }
        }
        assert_eq!(orders(3, 0).len(), 1, "at least one placement");
        let counts: Vec<u32> = (0..2 * super::PLACES).map(super::spacers).collect();
        assert_eq!(counts[..6], [0, 0, 1, 1, 2, 2], "each pair of placements at one place");
        for n in 0..super::PLACES as u32 {
            assert_eq!(counts.iter().filter(|&&c| c == n).count(), 2, "every place once per cycle: {counts:?}");
        }
        assert_eq!(orders(3, 6), super::design(3), "six placements of three sets: the whole design");
        assert_eq!(orders(2, 6).len(), 6);
    }

    #[test]
    fn a_retimed_round_says_which_time_it_kept() {
        let slow = super::Retimed { round: 5, first_ms: 4.389, again_ms: 2.45 };
        assert_eq!(
            slow.line("box 16 spp rust"),
            "box 16 spp rust: round 5's process ran slow (4.389 ms); timed again: 2.450 ms, the second kept"
        );
        let place = super::Retimed { again_ms: 4.5, ..slow };
        assert!(place.line("x").ends_with("the first kept: a slow place"));
        let times = super::PlacementTimes { retimed: vec![slow, place], ..Default::default() };
        let lines = times.retimed_lines("  ", "set b");
        assert_eq!(lines.lines().count(), 2, "{lines}");
        assert!(lines.starts_with("  set b: round 5's") && lines.ends_with("a slow place\n"), "{lines}");
        assert_eq!(super::PlacementTimes::default().retimed_lines("  ", "set b"), "");
    }
}
