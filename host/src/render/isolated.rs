//! Timing each set alone, in processes of its own (`twinray bench` and `compare` with
//! `--processes K`).
//!
//! On the H100 a process that builds pipelines of several sets settles into a regime chosen
//! by the set list: one set runs at its speed alone and another 4-7% slower, the same in
//! every placement of the process, so no interval over placements can see it, and a label
//! order or a `--null` decided Rust/GLSL (1.116 or 0.991 on swarm at 16 spp). Each set alone
//! in a fresh process timed within 0.1% from one process to the next
//! (`bench/reports/inspect-h100/`). So with isolation each set is timed in `processes`
//! processes of its own, in rounds that alternate the sets' order; a ratio's interval is taken
//! over the rounds, the two processes of a round being one paired observation.
//!
//! Each round's processes start at a later placement than the round before
//! ([`Isolation::first_placement`]), so the rounds time the sets at different places and the
//! interval over them holds where the code lands.
//! When every process started at placement 0, every process timed the same places: three
//! sessions on three H100s with 2 placements per process (0 spacers each) agreed to 0.1%
//! (median), while one with 4 (0 and 1 spacers) put some cells 1-2% away, outside intervals
//! of +-0.1% (`bench/reports/issue40-third/`).

use super::{render_sets, PlacementTimes, RenderOptions, RenderOutput};
use crate::error::Result;
use crate::scene::Scene;
use crate::shaders::ShaderSet;
use crate::vk::context::Context;
use std::sync::Arc;

/// Times one set alone: the median GPU ms of each placement of scene number `scene` (in the
/// bench's list) rendered with `set` at `spp`, in a fresh process whose placements start at
/// the last argument's (`RenderOptions::first_placement`).
pub type TimeAlone = dyn Fn(usize, u32, &ShaderSet, u32) -> Result<Vec<f64>> + Send + Sync;

/// How the bench times sets in processes of their own.
#[derive(Clone)]
pub struct Isolation {
    /// Processes per set.
    pub processes: u32,
    /// Placements each process makes.
    pub placements: u32,
    pub time_alone: Arc<TimeAlone>,
}

impl std::fmt::Debug for Isolation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Isolation {{ processes: {}, placements: {} }}", self.processes, self.placements)
    }
}

impl Isolation {
    /// Where round `round`'s processes start (`placement::round_start`).
    pub fn first_placement(&self, round: u32) -> u32 {
        super::placement::round_start(round, self.placements)
    }

    /// Replaces the times of `outputs` (one per set of `sets`) with each set's times alone:
    /// per round one geometric mean of a process's placements, and every placement's median.
    pub fn retime(&self, scene: usize, spp: u32, sets: &[ShaderSet], outputs: &mut [RenderOutput]) -> Result<()> {
        let mut means = vec![Vec::new(); sets.len()];
        let mut positions = vec![Vec::new(); sets.len()];
        let mut all = vec![Vec::new(); sets.len()];
        let firsts: Vec<u32> = (0..self.processes).map(|r| self.first_placement(r)).collect();
        for round in 0..self.processes {
            let order: Vec<usize> =
                if round % 2 == 0 { (0..sets.len()).collect() } else { (0..sets.len()).rev().collect() };
            for (position, &i) in order.iter().enumerate() {
                // A salted copy alone is its original alone: the salt only parts code that
                // shares a process.
                let ms = (self.time_alone)(scene, spp, &sets[i].original(), firsts[round as usize])?;
                means[i].push(geometric_mean(&ms));
                positions[i].push(position as u32);
                all[i].extend(ms);
            }
        }
        for (i, out) in outputs.iter_mut().enumerate() {
            out.placements = PlacementTimes {
                median_ms: std::mem::take(&mut means[i]),
                position: std::mem::take(&mut positions[i]),
                first_placement: firsts.clone(),
            };
            out.gpu_ms = std::mem::take(&mut all[i]);
        }
        Ok(())
    }
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
}
