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
//! `spacers` pipelines that it keeps, moving the code of what follows. Orders come in pairs,
//! a shuffled order and its reverse, so that a drift of the GPU's clocks over a placement
//! reaches every set alike. A ratio's uncertainty is the spread of the placements' ratios
//! (`util::interval`): how much a set's time owes to where its code landed, and to drift.
//!
//! A render of several placements first renders one more whose times it drops: on the H100 the
//! first placement of a process ran 5% slower than the rest (sphere at 16 spp: 2.47 and 2.37
//! ms against 2.33), and the first after a second of idle GPU (the bench writing images) up to
//! 3x (7.2 ms), though each set had its 200 ms of warm-up traces: the GPU's clocks take longer
//! than that to settle.

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

/// The seed of the shuffles: fixed, so that a command repeats its orders exactly; the orders
/// owe nothing to the sets' names or places in the command.
const SEED: u64 = 0x7417_2a79_5eed_0026;

/// The order of each placement of `sets` sets: pairs of a shuffled order and its reverse (the
/// last one alone when `placements` is odd).
pub fn orders(sets: usize, placements: u32) -> Vec<Vec<usize>> {
    let mut rng = SplitMix64(SEED);
    let mut out = Vec::with_capacity(placements as usize);
    while out.len() < placements.max(1) as usize {
        let mut order: Vec<usize> = (0..sets).collect();
        // Fisher-Yates.
        for i in (1..sets).rev() {
            order.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
        }
        out.push(order.clone());
        order.reverse();
        out.push(order);
    }
    out.truncate(placements.max(1) as usize);
    out
}

/// Spacer pipelines placement `p` makes first: 0, 0, 1, 1, 2, 2, 3, 3, 0, ... (each pair of
/// orders at one place).
pub fn spacers(p: usize) -> u32 {
    ((p / 2) % 4) as u32
}

/// Pipelines made only to be kept while a placement's sets are built and timed, so that their
/// code lands further on: salted copies of the built-in GLSL set (`ShaderSet::copy`, numbered
/// from 1000 so that no timed set shares their code), the same whatever sets are timed, so
/// that `--a X --b Y` and `--a Y --b X` sample the same places.
pub(super) struct Spacers {
    _pipelines: Vec<ScenePipeline>,
    _libraries: Libraries,
}

impl Spacers {
    pub fn new(ctx: &Arc<Context>, scene: &UploadedScene, count: u32) -> Result<Spacers> {
        let set = ShaderSet::uniform(crate::shaders::Language::Glsl);
        let libraries = Libraries::default();
        let linking = (ctx.pipeline_kind() == PipelineKind::Libraries).then_some(&libraries);
        let plan = &scene.data.plan;
        let pipelines = (0..count)
            .map(|k| ScenePipeline::new(ctx, &set.copy(1000 + k), plan, plan.render_raygen(), linking))
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
}

impl PlacementTimes {
    /// The ratio of these times to `other`'s, placement by placement, with its interval.
    pub fn ratio_to(&self, other: &PlacementTimes) -> Option<RatioInterval> {
        RatioInterval::paired(&self.median_ms, &other.median_ms)
    }
}

#[cfg(test)]
mod tests {
    use super::orders;

    #[test]
    fn orders_come_in_pairs_that_centre_every_set() {
        for sets in 1..=7 {
            let all = orders(sets, 6);
            assert_eq!(all.len(), 6);
            for pair in all.chunks(2) {
                let mut sorted = pair[0].clone();
                sorted.sort();
                assert_eq!(sorted, (0..sets).collect::<Vec<_>>(), "a permutation");
                assert_eq!(pair[1], pair[0].iter().rev().copied().collect::<Vec<_>>());
            }
        }
        assert_eq!(orders(3, 0).len(), 1, "at least one placement");
        assert_eq!(orders(3, 5), orders(3, 5), "the same orders every time");
        let firsts: std::collections::BTreeSet<usize> = orders(4, 40).iter().map(|o| o[0]).collect();
        assert_eq!(firsts.len(), 4, "every set comes first in some placement");
    }
}
