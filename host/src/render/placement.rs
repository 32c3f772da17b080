//! Places: where a set's pipeline is made, and the rounds and orders that time sets over many.
//!
//! Where the driver puts a pipeline's code moves its trace time, by an amount of its own for
//! each set, and by the same amount again when the same allocations are made in the same order
//! (docs/measuring.md, *Places* and *Where the timing rules come from*). So a set is timed
//! over many places, and a
//! ratio's uncertainty is taken over them. A place is one making of a set's pipeline, SBT and
//! descriptors after a drawn number of spacer pipelines ([`spacer_sets`]) that it keeps while
//! the set is timed, moving where the set's code lands, with the pipeline's groups in an order
//! drawn for the place (`super::layout`), moving where each stage lies within it; freed code
//! is reused, so the set's pipeline is released before the next is made. Every set of every round has a place of its
//! own ([`place`]): a null control's copy timed where its original was timed would only
//! repeat that place's time.
//!
//! A render times its sets in rounds, each round every set once, in the orders of a Williams
//! design ([`orders`]): every set at every position, and after every other set, equally often,
//! each order followed by its reverse, so that a drift of the GPU's clocks reaches every set
//! alike. Each round gives one median per set, and a ratio's interval is taken over rounds
//! (`util::interval`).

use super::layout::LayoutDraw;
use super::libraries::Libraries;
use super::pipeline::ScenePipeline;
use super::upload::UploadedScene;
use crate::error::Result;
use crate::sets::ShaderSet;
use crate::util::interval::RatioInterval;
use crate::vk::context::{Context, PipelineKind};
use serde::Serialize;
use std::sync::Arc;
use twinray_shared::random::SplitMix64;

/// Placements `compare` and `bench` time over unless told otherwise: three pairs of orders.
pub const DEFAULT_PLACEMENTS: u32 = 6;

/// The order of each round of `sets` sets: the rows of a Williams design, cycled (see
/// [`design`]). A set's time depends on where it comes in a round and on which set was built
/// and released just before it (docs/measuring.md); over a whole number of the design's rows every set comes at every
/// position, and after every other set, equally often, so the label order cannot favour one.
/// Rounds are numbered from `first`, so that a child process that starts at a later round
/// (`--processes`) starts at another row.
pub fn orders(sets: usize, first: u32, placements: u32) -> Vec<Vec<usize>> {
    let rows = design(sets);
    (0..placements.max(1) as usize).map(|p| rows[(first as usize + p) % rows.len()].clone()).collect()
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

/// The place of set `set` (of `sets` timed together) in round `round`: every round and set a
/// place of its own, so that no set, a null control's copy included, is ever timed at the
/// place of another, and a set's interval over its rounds is an interval over places.
pub fn place(round: u32, set: usize, sets: usize) -> u64 {
    u64::from(round) * sets.max(1) as u64 + set as u64
}

/// The most spacer pipelines a place makes before the set it times.
pub const MAX_SPACERS: usize = 7;

/// Which of `kinds` timed sets each spacer of place `place` copies: 1 to [`MAX_SPACERS`]
/// spacers, each of a kind drawn with a seed fixed per place, so that a command repeats its
/// places exactly and the pipelines made before a timed one are of every kind timed (spacers
/// of one kind alone miss regimes other kinds make). Never none: a set made first on a fresh
/// device times in a regime of its own (docs/measuring.md, *Where the timing rules come
/// from*).
pub fn spacer_sets(place: u64, kinds: usize) -> Vec<usize> {
    let mut rng = SplitMix64(SEED ^ place.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    let count = 1 + (rng.next_u64() % MAX_SPACERS as u64) as usize;
    (0..count).map(|_| (rng.next_u64() % kinds.max(1) as u64) as usize).collect()
}

/// The seed of the spacers' draws: fixed, so that a command repeats its places exactly.
const SEED: u64 = 0x7417_2a79_5eed_0026;

/// Pipelines made only to be kept while a place's set is built and timed, so that its code
/// lands further on: copies of the timed sets drawn by [`spacer_sets`], salted (numbered from
/// 1000, so that no timed set shares their code) unless `salted` is false.
pub(super) struct Spacers {
    _pipelines: Vec<ScenePipeline>,
    _libraries: Libraries,
}

impl Spacers {
    pub fn new(
        ctx: &Arc<Context>,
        scene: &UploadedScene,
        sets: &[(ShaderSet, PipelineKind)],
        salted: bool,
    ) -> Result<Spacers> {
        let libraries = Libraries::default();
        let plan = &scene.data.plan;
        let pipelines = sets
            .iter()
            .enumerate()
            .map(|(k, (set, kind))| {
                let linking = (*kind == PipelineKind::Libraries).then_some(&libraries);
                let copy = if salted { set.copy(1000 + k as u32) } else { set.clone() };
                ScenePipeline::new(ctx, &copy, plan, (plan.render_raygen(), LayoutDraw::Sbt), linking)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Spacers { _pipelines: pipelines, _libraries: libraries })
    }
}

/// A GPU idle longer than this since its last warmed trace warms up for `MIN_WARM_MS` again,
/// not `PLACE_WARM_MS`: the GPU's clocks come down while a place is made slowly, and a device
/// made right after another's timed traces finds them up (docs/measuring.md, *Where the timing
/// rules come from*).
pub const LONG_GAP_MS: f64 = 500.0;

/// When each device of this process last ended a warmed trace (name, time): the GPU's clocks are
/// the physical device's, so a fresh logical device made right after another's timing finds
/// them up.
static LAST_WARM: std::sync::Mutex<Vec<(String, std::time::Instant)>> = std::sync::Mutex::new(Vec::new());

/// Records that `ctx`'s GPU has just ended traces that were warmed up: its clocks are up.
pub fn note_warm(ctx: &Context) {
    note_warm_of(&ctx.info.name);
}

/// Milliseconds since `ctx`'s GPU last ended warmed traces (infinite if it has not).
pub fn idle_ms(ctx: &Context) -> f64 {
    idle_ms_of(&ctx.info.name)
}

fn note_warm_of(device: &str) {
    let mut last = LAST_WARM.lock().unwrap_or_else(|e| e.into_inner());
    last.retain(|(name, _)| name != device);
    last.push((device.to_string(), std::time::Instant::now()));
}

fn idle_ms_of(device: &str) -> f64 {
    let last = LAST_WARM.lock().unwrap_or_else(|e| e.into_inner());
    let at = last.iter().find(|(name, _)| name == device);
    at.map_or(f64::INFINITY, |(_, at)| at.elapsed().as_secs_f64() * 1e3)
}

/// The GPU milliseconds of warm-up traces a place takes at least, when any are asked for:
/// `PLACE_WARM_MS` if the GPU ended warmed traces at most [`LONG_GAP_MS`] ago (its clocks are
/// up), else `MIN_WARM_MS`, and always `MIN_WARM_MS` on a CPU device (lavapipe), where places
/// warmed for 20 ms timed in bursts 1.3 to 1.5 times slower: the interval of
/// `tests/timing.rs`'s doubled ray generation reached 0.56 to 0.87 over 8 runs (2 over the
/// test's 0.8), and 0.54 to 0.73 with 1000 ms. Each as its environment variable overrides it.
pub fn warm_floor(ctx: &Context) -> Result<f64> {
    let cpu = ctx.info.cpu_threads.is_some();
    let idle = idle_ms(ctx);
    log::debug!("the GPU idle for {idle:.0} ms since its last warmed trace");
    if idle <= LONG_GAP_MS && !cpu {
        super::prepare::place_warm_ms()
    } else {
        super::prepare::min_warm_ms()
    }
}

/// One set's times by placement.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PlacementTimes {
    /// The median GPU milliseconds of the set's timed traces in each placement.
    pub median_ms: Vec<f64>,
    /// The set's position (0: built and traced first in each round) in each placement.
    pub position: Vec<u32>,
    /// The place each placement timed the set at (`placement::place`: the draw of its
    /// spacers). Empty when timed in child processes (see `first_placement`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub place: Vec<u64>,
    /// Timed in child processes (`render::Isolation`): the round each process started at
    /// (`--first-placement`), whose places it timed. Empty otherwise.
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

    /// How these times spread over their places (processes, when timed in child processes), in
    /// a line after `indent` ending in a newline: "set a at 6 places: 2.312 to 2.451 ms, sd 1.8%";
    /// empty with fewer than two.
    pub fn spread_line(&self, indent: &str, what: &str) -> String {
        let ms: Vec<f64> = self.median_ms.iter().copied().filter(|m| m.is_finite() && *m > 0.0).collect();
        let logs = RatioInterval::of_logs(&ms.iter().map(|m| m.ln()).collect::<Vec<_>>());
        let Some(logs) = logs.filter(|l| l.placements > 1) else { return String::new() };
        let units = if self.first_placement.is_empty() { "places" } else { "processes" };
        let (low, high) = ms.iter().fold((f64::INFINITY, 0.0f64), |(l, h), &m| (l.min(m), h.max(m)));
        format!("{indent}{what} at {} {units}: {low:.3} to {high:.3} ms, sd {:.1}%\n", ms.len(), 100.0 * logs.log_sd)
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
    fn a_gpu_is_idle_since_its_own_last_warmed_trace() {
        // Names of no real device, so that a render elsewhere in the test binary cannot
        // interfere; the GPU's clocks are the physical device's, so another device's warmed
        // trace says nothing about this one.
        assert_eq!(super::idle_ms_of("test GPU a"), f64::INFINITY);
        super::note_warm_of("test GPU a");
        let idle = super::idle_ms_of("test GPU a");
        assert!((0.0..super::LONG_GAP_MS).contains(&idle), "{idle}");
        assert_eq!(super::idle_ms_of("test GPU b"), f64::INFINITY);
    }

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
        assert_eq!(orders(3, 0, 0).len(), 1, "at least one placement");
        assert_eq!(orders(2, 0, 6).len(), 6);
        assert_eq!(orders(3, 2, 1)[0], super::design(3)[2], "numbered from the first round");
        assert_eq!(orders(3, 0, 6), super::design(3), "six placements of three sets: the whole design");
    }

    #[test]
    fn every_round_and_set_has_a_place_of_its_own_and_a_draw_of_spacers() {
        let mut seen = std::collections::HashSet::new();
        for round in 0..50 {
            for set in 0..3 {
                assert!(seen.insert(super::place(round, set, 3)), "round {round}, set {set}");
            }
        }
        let draws: Vec<Vec<usize>> = (0..200).map(|p| super::spacer_sets(p, 3)).collect();
        assert!(draws.iter().all(|d| d.len() <= super::MAX_SPACERS && d.iter().all(|&k| k < 3)));
        // Never none: a set made first on a fresh device times in a regime of its own.
        assert!(draws.iter().all(|d| !d.is_empty()), "every place makes a spacer");
        for count in 1..=super::MAX_SPACERS {
            let n = draws.iter().filter(|d| d.len() == count).count();
            assert!((12..45).contains(&n), "{n} of 200 places make {count} spacers");
        }
        for kind in 0..3 {
            assert!(draws.iter().flatten().any(|&k| k == kind), "spacers of every kind timed");
        }
        assert_eq!(super::spacer_sets(7, 3), super::spacer_sets(7, 3), "a place repeats its draw");
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

    #[test]
    fn the_spread_over_places_in_a_line() {
        let times = super::PlacementTimes { median_ms: vec![2.0, 2.0 * 1.02f64.powi(2)], ..Default::default() };
        let line = times.spread_line("  ", "set a");
        assert!(line.starts_with("  set a at 2 places: 2.000 to 2.081 ms, sd 2.8%"), "{line}");
        let children = super::PlacementTimes { first_placement: vec![0, 2], ..times };
        assert!(children.spread_line("", "b").starts_with("b at 2 processes"));
        let one = super::PlacementTimes { median_ms: vec![2.0], ..Default::default() };
        assert_eq!(one.spread_line("  ", "set a"), "");
    }
}
