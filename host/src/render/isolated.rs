//! Timing each set alone (`twinray bench`, `compare` and `bisect` with `--processes K`), in
//! child processes or on fresh devices of this process (`--alone-in`).
//!
//! Where a device's rounds start fixes the times of all its places (a regime; docs/measuring.md,
//! *A regime is where a device starts*), so one process's places do not sample what other
//! starts would give. With isolation each set is timed in `processes` fresh processes or
//! devices of its own, in rounds ordered by the rows of a Williams design, as in one process
//! (`placement::design`); a ratio's interval is taken over the rounds, the processes of a round
//! being one paired observation. Every process starts at rounds of its own
//! ([`Isolation::first_placement`]), a set's and its salted copy's alike, so that no two time
//! the same places.

use super::placement::Retimed;
use super::{render_sets, PlacementTimes, RenderOptions, RenderOutput};
use crate::error::Result;
use crate::scene::Scene;
use crate::sets::ShaderSet;
use crate::vk::context::Context;
use std::sync::Arc;

/// Times one set alone: the median GPU ms of each placement of scene number `scene` (in the
/// bench's list) rendered with `set` at `spp`, in a fresh process whose placements start at
/// the last argument's (`RenderOptions::first_placement`).
pub type TimeAlone = dyn Fn(usize, u32, &ShaderSet, u32) -> Result<Vec<f64>> + Send + Sync;

/// What `--processes` times each set alone in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum AloneIn {
    /// A child `twinray bench` process of that set only.
    #[default]
    Processes,
    /// A fresh Vulkan device in the bench's own process, the set's scene uploaded to it afresh.
    Devices,
}

impl AloneIn {
    /// "processes" or "devices".
    pub fn plural(self) -> &'static str {
        match self {
            AloneIn::Processes => "processes",
            AloneIn::Devices => "devices",
        }
    }

    /// "a process" or "a device".
    pub fn one(self) -> &'static str {
        match self {
            AloneIn::Processes => "a process",
            AloneIn::Devices => "a device",
        }
    }
}

/// How the bench times sets in processes of their own.
#[derive(Clone)]
pub struct Isolation {
    /// Processes per set.
    pub processes: u32,
    /// Placements each process makes.
    pub placements: u32,
    /// Where the first process starts (`--first-placement`): a second run starts past the
    /// first's places, so that it times others.
    pub first: u32,
    /// Whether each "process" is a child process or a fresh device in this one.
    pub alone_in: AloneIn,
    pub time_alone: Arc<TimeAlone>,
}

impl std::fmt::Debug for Isolation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Isolation {{ processes: {}, placements: {} }}", self.processes, self.placements)
    }
}

impl Isolation {
    /// The round the process of set `set` (of `sets`) in round `round` starts at
    /// (`--first-placement`): past every place of the processes before it, so that no two
    /// processes, a set's and its salted copy's included, time the same places.
    pub fn first_placement(&self, round: u32, set: usize, sets: usize) -> u32 {
        self.first + (round * sets.max(1) as u32 + set as u32) * self.placements.max(1)
    }

    /// Replaces the times of `outputs` (one per set of `sets`) with each set's times alone:
    /// per round one geometric mean of a process's placements, and every placement's median.
    /// A process that ran [`RETIME_ABOVE`] times slower than its set's median round is timed
    /// again, at the same place, and the faster of the two kept (see `placement::Retimed`).
    pub fn retime(&self, scene: usize, spp: u32, sets: &[ShaderSet], outputs: &mut [RenderOutput]) -> Result<()> {
        let n = sets.len();
        let firsts: Vec<Vec<u32>> =
            (0..n).map(|i| (0..self.processes).map(|r| self.first_placement(r, i, n)).collect()).collect();
        // A salted copy alone is its original alone, at places of its own: the salt only parts
        // code that shares a process.
        let time = |i: usize, round: usize| (self.time_alone)(scene, spp, &sets[i].original(), firsts[i][round]);
        let mut rounds = vec![Vec::new(); sets.len()];
        let mut positions = vec![Vec::new(); sets.len()];
        // The rows of a Williams design, as in one process: with three sets, forwards and
        // backwards alone would keep the second set in the middle of every round.
        let design = super::placement::design(n);
        if self.processes > 1 && !(self.processes as usize).is_multiple_of(design.len()) {
            log::warn!(
                "{} {} per set for {n} sets: the orders balance every set's position only over a multiple of {}",
                self.processes,
                self.alone_in.plural(),
                design.len()
            );
        }
        for round in 0..self.processes as usize {
            for (position, &i) in design[round % design.len()].iter().enumerate() {
                rounds[i].push(time(i, round)?);
                positions[i].push(position as u32);
            }
        }
        for (i, out) in outputs.iter_mut().enumerate() {
            let retimed = retime_slow(&mut rounds[i], |round| time(i, round))?;
            out.placements = PlacementTimes {
                median_ms: rounds[i].iter().map(|ms| geometric_mean(ms)).collect(),
                position: std::mem::take(&mut positions[i]),
                place: Vec::new(),
                first_placement: firsts[i].clone(),
                retimed,
            };
            out.gpu_ms = rounds[i].concat();
        }
        Ok(())
    }
}

/// A round whose process ran this many times slower than its set's median round is timed
/// again: far past what where the code lands can do (a few percent), a whole process whose GPU
/// clocks did not come up. The warm-up (`prepare::MIN_WARM_MS`) prevents most; this catches
/// what else may slow a whole process (docs/measuring.md, *Where the timing rules come from*).
pub const RETIME_ABOVE: f64 = 1.10;

/// Times again, with `again(round)`, every round of `rounds` (each a process's placement
/// medians) whose geometric mean is over [`RETIME_ABOVE`] times the median round's, keeping
/// the faster process. A slow place times slow again and stays; a process slowed by
/// something else does not, and goes.
fn retime_slow(rounds: &mut [Vec<f64>], mut again: impl FnMut(usize) -> Result<Vec<f64>>) -> Result<Vec<Retimed>> {
    let means: Vec<f64> = rounds.iter().map(|ms| geometric_mean(ms)).collect();
    let Some(median) = crate::util::stats::median(&means) else { return Ok(Vec::new()) };
    let mut retimed = Vec::new();
    for (round, &first_ms) in means.iter().enumerate() {
        if first_ms > median * RETIME_ABOVE {
            let ms = again(round)?;
            let again_ms = geometric_mean(&ms);
            if again_ms < first_ms {
                rounds[round] = ms;
            }
            retimed.push(Retimed { round: round as u32, first_ms, again_ms });
        }
    }
    Ok(retimed)
}

/// Renders `scene` with `sets` and times them: here, over `opts`'s placements, or with
/// `isolation` each set alone in processes of its own (the renders here then give only the
/// images, one untimed trace each), at the scene's own sample count.
pub fn render_timed(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[ShaderSet],
    opts: &RenderOptions,
    isolation: Option<&Isolation>,
) -> Result<Vec<RenderOutput>> {
    let Some(isolation) = isolation else { return render_sets(ctx, scene, sets, opts) };
    let mut outputs = render_sets(ctx, scene, sets, &RenderOptions { warmup: 0, runs: 1, placements: 1, ..*opts })?;
    let side = scene.file.image.samples;
    isolation.retime(0, side * side, sets, &mut outputs)?;
    Ok(outputs)
}

fn geometric_mean(values: &[f64]) -> f64 {
    let logs: Vec<f64> = values.iter().filter(|v| v.is_finite() && **v > 0.0).map(|v| v.ln()).collect();
    if logs.is_empty() {
        return f64::NAN;
    }
    (logs.iter().sum::<f64>() / logs.len() as f64).exp()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_geometric_mean_skips_what_is_not_a_time() {
        assert!((super::geometric_mean(&[1.0, 4.0, f64::NAN, 0.0]) - 2.0).abs() < 1e-12);
        assert!(super::geometric_mean(&[]).is_nan());
    }

    #[test]
    fn a_slow_process_is_timed_again_and_the_faster_kept() {
        let mut rounds = vec![vec![1.0, 1.0], vec![1.04, 1.04], vec![1.7, 1.7], vec![0.96, 0.96]];
        let mut asked = Vec::new();
        let retimed = super::retime_slow(&mut rounds, |r| {
            asked.push(r);
            Ok(vec![1.01, 1.01])
        })
        .unwrap();
        assert_eq!(asked, [2]);
        assert_eq!(rounds[2], [1.01, 1.01]);
        assert_eq!(retimed.len(), 1);
        assert_eq!(retimed[0].round, 2);
        assert!((retimed[0].first_ms - 1.7).abs() < 1e-9 && (retimed[0].again_ms - 1.01).abs() < 1e-9);
    }

    #[test]
    fn a_slow_place_stays_slow_and_a_spread_within_places_is_left_alone() {
        // The same time again: the place is slow, not the process.
        let mut rounds = vec![vec![1.0], vec![1.0], vec![1.3]];
        let retimed = super::retime_slow(&mut rounds, |_| Ok(vec![1.31])).unwrap();
        assert_eq!(rounds[2], [1.3]);
        assert_eq!(retimed.len(), 1);
        // 9% above the median: a place, not a slow process; nothing is timed again.
        let mut rounds = vec![vec![1.0], vec![1.09], vec![0.95]];
        let retimed = super::retime_slow(&mut rounds, |_| panic!("timed again")).unwrap();
        assert!(retimed.is_empty());
    }
}
