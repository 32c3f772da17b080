//! Placements: each an independent making of every set's pipeline, SBT and descriptors over a
//! fresh upload of the scene, in an order of its own, then the sets' timed traces interleaved.
//!
//! On the H100 a set's time moved by up to 5% with where the command put it (issue 26), by
//! more than its traces vary inside one render. Where the driver places a pipeline's code is
//! outside twinray's control; what twinray controls is that no set is favoured by its place:
//! orders come in pairs, a shuffled order and its reverse, so every set's mean position over a
//! pair is the middle, and each placement gives each set one median. A ratio's uncertainty is
//! then the spread of those medians' ratios over placements (`util::interval`).

use crate::util::interval::RatioInterval;
use serde::Serialize;

/// Placements `compare` and `bench` time over unless told otherwise: three pairs of orders.
pub const DEFAULT_PLACEMENTS: u32 = 6;

/// The seed of the shuffles: fixed, so that a command repeats its orders exactly; the orders
/// owe nothing to the sets' names or places in the command.
const SEED: u64 = 0x7417_2a79_5eed_0026;

/// The order of each placement of `sets` sets: pairs of a shuffled order and its reverse (the
/// last one alone when `placements` is odd).
pub fn orders(sets: usize, placements: u32) -> Vec<Vec<usize>> {
    let mut rng = SplitMix(SEED);
    let mut out = Vec::with_capacity(placements as usize);
    while out.len() < placements.max(1) as usize {
        let mut order: Vec<usize> = (0..sets).collect();
        // Fisher-Yates.
        for i in (1..sets).rev() {
            order.swap(i, (rng.next() % (i as u64 + 1)) as usize);
        }
        out.push(order.clone());
        order.reverse();
        out.push(order);
    }
    out.truncate(placements.max(1) as usize);
    out
}

/// SplitMix64: a small, well-mixed generator, enough to shuffle orders.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
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
