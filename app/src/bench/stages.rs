//! `twinray stage-bench`: what a stage kind or tracing method costs, as GPU time against the
//! image it gives. Each scene renders in variants (made opaque, cutouts without holes, shadows
//! by `traceRay` or by ray queries, materials inline or by callables, hit groups per shape or
//! per material, the pipeline or the compute renderer) with each shader set; every variant's time is set
//! against the first variant's with the same set, and its image against that variant's image.
//! Variants use different uploads, so they are timed in rounds: in each round every variant
//! and set renders once (order rotated from round to round), and each median pools the timed
//! traces of every round.

use super::metrics::rmse;
use serde::Serialize;
use std::sync::Arc;
use twinray_host::compare::scene_diff;
use twinray_host::error::{Error, Result};
use twinray_host::render::{render, RenderOptions, RenderOutput};
use twinray_host::scene::file::{CutoutPattern, MaterialDesc};
use twinray_host::scene::{HitGroups, MaterialShading, Renderer, Scene, ShadowMethod};
use twinray_host::sets::ShaderSet;
use twinray_host::util::interval::RatioInterval;
use twinray_host::util::stats::Spread;
use twinray_host::vk::context::Context;

/// A way to render a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Variant {
    /// The scene as written.
    AsIs,
    /// Every cutout material made diffuse: no any-hit stage anywhere.
    Opaque,
    /// Cutouts keep their any-hit stage, with disc holes too small to hit: the image of
    /// `Opaque`, at the cost of running any-hit for every candidate.
    SolidCutouts,
    /// Shadow rays traced by `traceRay` with the shadow miss stage.
    TraceShadows,
    /// Shadow rays traced inline by ray queries (`VK_KHR_ray_query`).
    QueryShadows,
    /// Materials' colours computed in the closest-hit stages.
    InlineMaterials,
    /// Materials' colours computed by callables chosen through the SBT.
    CallableMaterials,
    /// One hit group per shape kind, its closest-hit stage branching on the material's kind.
    PerShapeHits,
    /// Hit groups per shape kind and material kind, chosen by each instance's SBT offset.
    PerMaterialHits,
    /// Rendered by the ray tracing pipeline.
    Pipeline,
    /// Rendered by the compute renderer, primary and shadow rays traced by ray queries (with
    /// materials inline and no hit groups to choose, as it has no SBT).
    Compute,
}

impl Variant {
    pub const ALL: [Variant; 11] = [
        Variant::AsIs,
        Variant::Opaque,
        Variant::SolidCutouts,
        Variant::TraceShadows,
        Variant::QueryShadows,
        Variant::InlineMaterials,
        Variant::CallableMaterials,
        Variant::PerShapeHits,
        Variant::PerMaterialHits,
        Variant::Pipeline,
        Variant::Compute,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Variant::AsIs => "as-is",
            Variant::Opaque => "opaque",
            Variant::SolidCutouts => "solid-cutouts",
            Variant::TraceShadows => "trace-shadows",
            Variant::QueryShadows => "query-shadows",
            Variant::InlineMaterials => "inline-materials",
            Variant::CallableMaterials => "callable-materials",
            Variant::PerShapeHits => "per-shape-hits",
            Variant::PerMaterialHits => "per-material-hits",
            Variant::Pipeline => "pipeline",
            Variant::Compute => "compute",
        }
    }

    /// Comma-separated variant names.
    pub fn parse_list(text: &str) -> Result<Vec<Variant>> {
        let variants = text
            .split(',')
            .map(str::trim)
            .map(|word| {
                Variant::ALL.into_iter().find(|v| v.name() == word).ok_or_else(|| {
                    let names: Vec<_> = Variant::ALL.iter().map(|v| v.name()).collect();
                    Error::Input(format!("unknown variant {word:?} (expected {})", names.join(", ")))
                })
            })
            .collect::<Result<Vec<_>>>()?;
        if variants.is_empty() {
            return Err(Error::Input("no variants".into()));
        }
        Ok(variants)
    }

    /// `scene` as this variant renders it; `None` where the variant means nothing for it
    /// (cutout variants of a scene without cutouts, shadow methods of one without shadows).
    pub fn apply(self, scene: &Scene) -> Option<Scene> {
        let mut out = scene.clone();
        let cutouts = out.file.materials.values_mut().filter(|m| matches!(m, MaterialDesc::Cutout { .. }));
        let shadows = scene.build().plan.shadows;
        match self {
            Variant::AsIs => {}
            Variant::Opaque | Variant::SolidCutouts => {
                let mut any = false;
                for m in cutouts {
                    any = true;
                    if let MaterialDesc::Cutout { color, pattern, threshold, .. } = m {
                        if self == Variant::Opaque {
                            *m = MaterialDesc::Diffuse { color: *color, texture: None, emission: None };
                        } else {
                            (*pattern, *threshold) = (CutoutPattern::Discs, f32::MIN_POSITIVE);
                        }
                    }
                }
                if !any {
                    return None;
                }
            }
            Variant::TraceShadows if shadows => out.file.shadow_method = ShadowMethod::Trace,
            Variant::QueryShadows if shadows => out.file.shadow_method = ShadowMethod::Query,
            Variant::TraceShadows | Variant::QueryShadows => return None,
            Variant::InlineMaterials => out.file.material_shading = MaterialShading::Inline,
            Variant::CallableMaterials => out.file.material_shading = MaterialShading::Callable,
            Variant::PerShapeHits => out.file.hit_groups = HitGroups::PerShape,
            Variant::PerMaterialHits => out.file.hit_groups = HitGroups::PerMaterial,
            Variant::Pipeline => out.file.renderer = Renderer::Pipeline,
            Variant::Compute => {
                out.file.renderer = Renderer::Compute;
                (out.file.material_shading, out.file.hit_groups) = (MaterialShading::Inline, HitGroups::PerShape);
            }
        }
        Some(out)
    }

    /// What the device must have for it, if it lacks it.
    fn lacking(self, ctx: &Context) -> Option<&'static str> {
        let queries = matches!(self, Variant::QueryShadows | Variant::Compute);
        (queries && !ctx.info.ray_query).then_some("VK_KHR_ray_query")
    }
}

/// One scene, variant and set.
#[derive(Clone, Debug, Serialize)]
pub struct StageRow {
    pub scene: String,
    pub variant: Variant,
    pub set: String,
    pub width: u32,
    pub height: u32,
    /// GPU time of every timed trace of every round pooled: how the traces spread.
    pub gpu_ms: Spread,
    /// The median of each round (each round makes the pipeline afresh: a placement).
    pub round_ms: Vec<f64>,
    /// Its time over the first variant's with the same set, round by round, with the 95%
    /// interval over rounds.
    pub against_first: Option<RatioInterval>,
    /// Its time over the same variant's with the first set, likewise.
    pub against_first_set: Option<RatioInterval>,
    /// RMSE of its image (display values) against the first variant's with the same set.
    pub rmse: f64,
    pub hit_mismatches: u64,
    pub primary_rays: u64,
    pub shadow_rays: u64,
    pub raygen_stack_bytes: u64,
}

/// A variant that could not be measured, and why.
#[derive(Clone, Debug, Serialize)]
pub struct Skipped {
    pub scene: String,
    pub variant: Variant,
    pub why: String,
}

/// Times one variant of scene number `scene` (in the plan's list) with one set, alone in a
/// fresh process, as round number `round` ([`StagePlan::first_round`]): the median GPU ms of
/// its timed traces.
pub type TimeCell = dyn Fn(usize, Variant, &ShaderSet, u32) -> Result<f64>;

/// What to measure: `variants` of `scenes`, each with `sets`, `rounds` times each with
/// `opts.runs` timed traces, at the size `size` gives per scene; with `alone`, each round's
/// time of each variant and set is that of a fresh process (the renders here give only the
/// images).
pub struct StagePlan<'a> {
    pub scenes: &'a [Scene],
    pub variants: &'a [Variant],
    pub sets: &'a [ShaderSet],
    pub rounds: u32,
    /// The number of the first round (0 but in `--alone`'s children): in round `r` each of the
    /// `c` cells (variant and set) is timed once, cell `k` at place `r * c + k` (see
    /// `render::placement::place`).
    pub first_round: u32,
    pub alone: Option<&'a TimeCell>,
}

/// Every measurement of `plan`, reporting each render to `progress`.
pub fn run(
    ctx: &Arc<Context>,
    plan: &StagePlan,
    opts: impl Fn(&Scene) -> RenderOptions,
    mut progress: impl FnMut(&str),
) -> Result<(Vec<StageRow>, Vec<Skipped>)> {
    let (mut rows, mut skipped) = (Vec::new(), Vec::new());
    for (index, scene) in plan.scenes.iter().enumerate() {
        let opts = opts(scene);
        let mut runs: Vec<(Variant, Scene)> = Vec::new();
        for &variant in plan.variants {
            let why = match (variant.apply(scene), variant.lacking(ctx)) {
                (None, _) => "means nothing for this scene".to_string(),
                (Some(_), Some(lacking)) => format!("{} lacks {lacking}", ctx.info.name),
                (Some(s), None) => {
                    runs.push((variant, s));
                    continue;
                }
            };
            skipped.push(Skipped { scene: scene.name().to_string(), variant, why });
        }
        let cells: Vec<(usize, usize)> =
            (0..runs.len()).flat_map(|v| (0..plan.sets.len()).map(move |s| (v, s))).collect();
        let mut times = vec![Vec::new(); cells.len()];
        let mut round_ms = vec![Vec::new(); cells.len()];
        let mut last: Vec<Option<RenderOutput>> = (0..cells.len()).map(|_| None).collect();
        for round in 0..plan.rounds.max(1) as usize {
            let number = plan.first_round + round as u32;
            for k in 0..cells.len() {
                let c = (k + round) % cells.len();
                let opts = RenderOptions { first_placement: number * cells.len() as u32 + c as u32, ..opts };
                let (v, s) = cells[c];
                progress(&format!("{} {} {} (round {})", scene.name(), runs[v].0.name(), plan.sets[s], round + 1));
                let (variant, set) = (runs[v].0, &plan.sets[s]);
                let render_here = |opts: &RenderOptions| -> Result<RenderOutput> {
                    let out = render(ctx, &runs[v].1, set, opts)?;
                    out.written.require(&set.to_string(), "pixels", &format!("{} {}", scene.name(), variant.name()))?;
                    Ok(out)
                };
                let (ms, median) = match plan.alone {
                    Some(alone) => {
                        if last[c].is_none() {
                            last[c] = Some(render_here(&RenderOptions { warmup: 0, runs: 1, placements: 1, ..opts })?);
                        }
                        let ms = alone(index, variant, set, number)?;
                        (vec![ms], ms)
                    }
                    None => {
                        let out = render_here(&opts)?;
                        let timed = (out.gpu_ms.clone(), out.median_ms().unwrap_or(f64::NAN));
                        last[c] = Some(out);
                        timed
                    }
                };
                times[c].extend(ms);
                round_ms[c].push(median);
            }
        }
        rows.extend(rows_of(scene, &runs, plan.sets, &cells, (&times, &round_ms), &last));
    }
    Ok((rows, skipped))
}

fn rows_of(
    scene: &Scene,
    runs: &[(Variant, Scene)],
    sets: &[ShaderSet],
    cells: &[(usize, usize)],
    (times, round_ms): (&[Vec<f64>], &[Vec<f64>]),
    last: &[Option<RenderOutput>],
) -> Vec<StageRow> {
    let against = |c: usize, d: usize| RatioInterval::paired(&round_ms[c], &round_ms[d]);
    let cell = |v: usize, s: usize| cells.iter().position(|&x| x == (v, s)).unwrap_or(0);
    let mut rows = Vec::new();
    for (c, &(v, s)) in cells.iter().enumerate() {
        let Some(out) = &last[c] else { continue };
        let first = cell(0, s);
        let base = last[first].as_ref().unwrap_or(out);
        // Judged in the first variant's scene: where either answer is right there.
        let d = scene_diff(&runs[0].1, out, base);
        rows.push(StageRow {
            scene: scene.name().to_string(),
            variant: runs[v].0,
            set: sets[s].to_string(),
            width: out.width,
            height: out.height,
            gpu_ms: Spread::of(&times[c]).unwrap_or(Spread {
                median: f64::NAN,
                q1: f64::NAN,
                q3: f64::NAN,
                samples: 0,
            }),
            round_ms: round_ms[c].clone(),
            against_first: against(c, first),
            against_first_set: against(c, cell(v, 0)),
            rmse: rmse(&out.linear, &base.linear),
            hit_mismatches: d.hit_mismatches,
            primary_rays: out.rays.primary,
            shadow_rays: out.rays.shadow,
            raygen_stack_bytes: out.raygen_stack_bytes,
        });
    }
    rows
}

/// "1.031 (1.012 to 1.050)", or "n/a".
fn with_interval(r: Option<RatioInterval>) -> String {
    r.map_or("n/a".into(), |r| match r.has_interval() {
        true => format!("{:.3} ({:.3} to {:.3})", r.ratio, r.low, r.high),
        false => format!("{:.3}", r.ratio),
    })
}

/// The rows as a Markdown table, and the skipped variants under it.
pub fn table(rows: &[StageRow], skipped: &[Skipped]) -> String {
    let mut s = String::from(
        "| scene | variant | set | size | GPU ms (median) | IQR of traces | against first variant (95% CI) | against first set (95% CI) | RMSE against first variant | hit mismatches | shadow rays | raygen stack |\n|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        s += &format!(
            "| {} | {} | {} | {}x{} | {:.3} | {:.3} | {} | {} | {:.2e} | {} | {} | {} |\n",
            r.scene,
            r.variant.name(),
            r.set,
            r.width,
            r.height,
            r.gpu_ms.median,
            r.gpu_ms.q3 - r.gpu_ms.q1,
            with_interval(r.against_first),
            with_interval(r.against_first_set),
            r.rmse,
            r.hit_mismatches,
            r.shadow_rays,
            r.raygen_stack_bytes
        );
    }
    for k in skipped {
        s += &format!("\n{} {}: not measured ({})", k.scene, k.variant.name(), k.why);
    }
    if !skipped.is_empty() {
        s.push('\n');
    }
    s
}
