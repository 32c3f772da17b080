//! What `twinray bisect` runs sets on: a scene's image, or a probe case's rays.

use crate::compare::diff::verdict;
use crate::compare::edges::scene_diff;
use crate::error::Result;
use crate::probe::case::ProbeCase;
use crate::probe::run::{count_written, probe, ProbeResult};
use crate::render::isolated::{render_timed, AloneIn, Isolation};
use crate::render::pipeline::plan_modules;
use crate::render::placement::orders;
use crate::render::{RenderOptions, RenderOutput, Written};
use crate::scene::Scene;
use crate::sets::ShaderSet;
use crate::util::stats::median;
use crate::vk::context::Context;
use serde::Serialize;
use std::sync::Arc;
use twinray_shared::bindings::NO_HIT;

/// How two runs of one subject differ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Gap {
    /// RMS difference: of the images' RGB in [0, 1], or of probe rays' relative t where both
    /// runs hit.
    pub rmse: f64,
    /// Pixels over the scene's pixel threshold, or probe rays whose t differs by more than
    /// [`PROBE_T_TOLERANCE`] relative.
    pub over: u64,
    /// Pixels whose primary rays hit different primitives (less those where either is right:
    /// `compare::edges`), or probe rays that hit another object or only in one run.
    pub mismatches: u64,
    /// Within the scene's parity tolerance (as `compare` judges it); for probe rays, no
    /// mismatches and no t over the tolerance.
    pub within_tolerance: bool,
}

impl Gap {
    pub fn is_zero(&self) -> bool {
        self.rmse == 0.0 && self.over == 0 && self.mismatches == 0
    }
}

/// What one run of a set gave: its output (compared through [`Subject::gap`]) and GPU times,
/// the median of each placement (placement p of every set of one `Subject::run` together).
pub struct Run<T> {
    pub data: T,
    pub placement_ms: Vec<f64>,
    pub raygen_stack_bytes: u64,
    /// What the set left unwritten of its output, or wrote non-finite.
    pub written: Written,
}

/// Relative difference of t beyond which two probe results count as differing.
pub const PROBE_T_TOLERANCE: f64 = 1e-4;

/// Something to run shader sets on and compare their outputs.
pub trait Subject {
    type Data;
    /// The scene or case, for the report.
    fn name(&self) -> String;
    fn device(&self) -> String;
    /// What one item of its output is called: "pixels", "rays".
    fn items(&self) -> &'static str;
    /// The catalog modules its pipeline uses.
    fn modules(&self) -> Vec<&'static str>;
    /// One run per set, in order.
    fn run(&mut self, sets: &[ShaderSet]) -> Result<Vec<Run<Self::Data>>>;
    /// Processes (or devices) each set is timed alone in (0: all in this one).
    fn processes(&self) -> (u32, AloneIn) {
        (0, AloneIn::Processes)
    }
    fn gap(&self, a: &Self::Data, b: &Self::Data) -> Gap;
}

/// A scene's image, rendered as `compare` renders it (every set over one upload, traces
/// interleaved), built and timed in one order and then in reverse rather than in every
/// rotation: a bisect renders up to 16 sets.
pub struct ImageSubject<'a> {
    pub ctx: &'a Arc<Context>,
    pub scene: &'a Scene,
    pub opts: RenderOptions,
    /// Each set timed alone in processes of its own (`bisect --processes`).
    pub isolation: Option<Isolation>,
}

impl Subject for ImageSubject<'_> {
    type Data = RenderOutput;

    fn name(&self) -> String {
        format!("{} {}x{}", self.scene.name(), self.opts.width, self.opts.height)
    }

    fn items(&self) -> &'static str {
        "pixels"
    }

    fn device(&self) -> String {
        self.ctx.info.name.clone()
    }

    fn modules(&self) -> Vec<&'static str> {
        let plan = self.scene.build().plan;
        plan_modules(&plan, plan.render_raygen())
    }

    fn run(&mut self, sets: &[ShaderSet]) -> Result<Vec<Run<RenderOutput>>> {
        let outputs = render_timed(self.ctx, self.scene, sets, &self.opts, self.isolation.as_ref())?;
        Ok(outputs
            .into_iter()
            .map(|o| Run {
                placement_ms: o.placements.median_ms.clone(),
                raygen_stack_bytes: o.raygen_stack_bytes,
                written: o.written,
                data: o,
            })
            .collect())
    }

    fn processes(&self) -> (u32, AloneIn) {
        self.isolation.as_ref().map_or((0, AloneIn::Processes), |i| (i.processes, i.alone_in))
    }

    fn gap(&self, a: &RenderOutput, b: &RenderOutput) -> Gap {
        let parity = &self.scene.file.parity;
        let d = scene_diff(self.scene, a, b);
        let pixels = u64::from(a.width) * u64::from(a.height);
        Gap {
            rmse: d.color.rmse,
            over: d.color.pixels_over_threshold,
            mismatches: d.hit_mismatches,
            within_tolerance: verdict(&d, parity, pixels).is_empty(),
        }
    }
}

/// A probe case's rays, each set probed in turn (not interleaved: a probe is one dispatch),
/// in each placement's order.
pub struct ProbeSubject<'a> {
    pub ctx: &'a Arc<Context>,
    pub case: &'a ProbeCase,
    pub warmup: u32,
    pub runs: u32,
    pub placements: u32,
}

impl Subject for ProbeSubject<'_> {
    type Data = Vec<ProbeResult>;

    fn name(&self) -> String {
        format!("probe case {} ({} rays)", self.case.file.name, self.case.rays.len())
    }

    fn items(&self) -> &'static str {
        "rays"
    }

    fn device(&self) -> String {
        self.ctx.info.name.clone()
    }

    fn modules(&self) -> Vec<&'static str> {
        plan_modules(&self.case.scene.build().plan, crate::probe::run::probe_module(&self.case.scene))
    }

    fn run(&mut self, sets: &[ShaderSet]) -> Result<Vec<Run<Vec<ProbeResult>>>> {
        let mut runs: Vec<Option<Run<Vec<ProbeResult>>>> = sets.iter().map(|_| None).collect();
        for order in orders(sets.len(), 0, self.placements) {
            for i in order {
                let out = probe(self.ctx, &self.case.scene, &sets[i], &self.case.rays, self.warmup, self.runs)?;
                let ms = median(&out.gpu_ms);
                match &mut runs[i] {
                    Some(run) => run.placement_ms.extend(ms),
                    slot => {
                        let written = count_written(&out.results);
                        let raygen_stack_bytes = out.raygen_stack_bytes;
                        *slot = Some(Run {
                            data: out.results,
                            placement_ms: ms.into_iter().collect(),
                            raygen_stack_bytes,
                            written,
                        });
                    }
                }
            }
        }
        runs.into_iter()
            .map(|r| r.ok_or_else(|| crate::error::Error::Unsupported("a probe placement left a set out".into())))
            .collect()
    }

    fn gap(&self, a: &Vec<ProbeResult>, b: &Vec<ProbeResult>) -> Gap {
        probe_gap(a, b)
    }
}

/// Rays that hit another object (or hit in one run only), rays whose t differs by more than
/// [`PROBE_T_TOLERANCE`], and the RMS relative difference of t where both hit.
pub fn probe_gap(a: &[ProbeResult], b: &[ProbeResult]) -> Gap {
    let (mut sum, mut over, mut mismatches) = (0.0f64, 0u64, 0u64);
    for (x, y) in a.iter().zip(b) {
        let (hit_x, hit_y) = (x.ids.w != NO_HIT, y.ids.w != NO_HIT);
        if hit_x != hit_y || (hit_x && x.ids.x != y.ids.x) {
            mismatches += 1;
        } else if hit_x {
            let (tx, ty) = (f64::from(x.normal_t.w), f64::from(y.normal_t.w));
            let relative = (tx - ty).abs() / tx.abs().max(ty.abs()).max(f64::MIN_POSITIVE);
            sum += relative * relative;
            over += u64::from(relative > PROBE_T_TOLERANCE);
        }
    }
    Gap { rmse: (sum / a.len().max(1) as f64).sqrt(), over, mismatches, within_tolerance: over == 0 && mismatches == 0 }
}
