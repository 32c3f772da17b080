//! What a place changes (`twinray places`): each set timed over many places with one thing
//! moved at a time, the pipeline's code, its SBT or the scene's buffers, and with nothing
//! moved, so that the spread each leaves can be read apart (docs/measuring.md, *Places*).
//!
//! Every place makes the set's pipeline, SBT and descriptors afresh and releases them after.
//! `none` repeats one place: what is left is the timing's own noise and the clocks' drift.
//! `code` makes the place's spacer pipelines first (`placement::spacer_sets`), which moves
//! where the driver puts the set's code and nothing else twinray allocates. `sbt` allocates a
//! pad of a drawn size in the SBT's memory before the SBT, which moves the SBT alone (its
//! address is recorded). `buffers` uploads the scene and its outputs afresh after pads of drawn
//! sizes in both memories they use, which moves every buffer, image and acceleration structure.
//! `layout` hands the driver the pipeline's groups and stages in an order drawn for the place
//! (`super::layout`), which moves where each stage's code lies within the pipeline.

use super::layout::LayoutDraw;
use super::placement;
use super::prepare::{min_warm_ms, place_warm_ms};
use super::sets::{Placed, SetRender, SharedOutputs};
use super::tracing;
use super::upload::{upload_shared, UploadedScene};
use super::RenderOptions;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::sets::ShaderSet;
use crate::util::interval::RatioInterval;
use crate::util::{activity, progress, stats};
use crate::vk::buffer::Buffer;
use crate::vk::context::{Context, PipelineKind};
use ash::vk;
use gpu_allocator::MemoryLocation;
use serde::Serialize;
use std::sync::Arc;
use twinray_shared::random::SplitMix64;

/// What a study moves from place to place.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Move {
    /// Nothing: the same place every time.
    None,
    /// The pipeline's code, by spacer pipelines made before it.
    Code,
    /// The pipeline's code, by spacers that are unsalted copies of the timed sets, which a
    /// driver could make from its cache, or share code with.
    Reused,
    /// The SBT, by a pad allocated before it.
    Sbt,
    /// The scene's buffers, acceleration structures and output image, by pads before them.
    Buffers,
    /// The order in which the pipeline's groups and stages are handed to the driver, drawn for
    /// the place.
    Layout,
}

/// One set timed at one place.
#[derive(Clone, Debug, Serialize)]
pub struct PlaceTime {
    #[serde(rename = "move")]
    pub moved: Move,
    pub set: String,
    pub place: u32,
    /// The median GPU ms of the place's timed traces.
    pub median_ms: f64,
    /// Each warm-up trace's GPU ms, in order: whether the clocks were up after the CPU's work.
    pub warm_ms: Vec<f64>,
    /// Wall ms of making the place's spacers, pipeline, SBT and descriptors (not the pads, nor
    /// the upload of `buffers`).
    pub make_ms: f64,
    /// Whether the making took over `placement::LONG_GAP_MS`, so that the place first warmed
    /// up for `MIN_WARM_MS` (untimed) before its recorded warm-up traces.
    pub long_gap: bool,
    pub spacers: usize,
    /// Bytes of the pad allocated before what was moved (0 for `none` and `code`).
    pub pad_bytes: u64,
    /// The SBT's device address.
    pub sbt_address: u64,
}

/// `sets` timed over `places` places for each move of `moves`, the sets alternating in order
/// from place to place, after one warm-up of at least `MIN_WARM_MS`; `opts.runs` timed traces
/// per place after `place_warm_ms()` of warm-up traces, themselves timed and recorded.
pub fn study(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[ShaderSet],
    moves: &[Move],
    places: u32,
    opts: &RenderOptions,
) -> Result<Vec<PlaceTime>> {
    super::sets::check_device_limits(ctx, opts)?;
    let size = (opts.width, opts.height);
    let made: Vec<(ShaderSet, PipelineKind)> = sets.iter().map(|s| (s.clone(), ctx.pipeline_kind())).collect();
    let fixed = (upload_shared(ctx, scene, None, size)?, SharedOutputs::new(ctx, opts)?);
    let warm = warm_traces(ctx, &fixed, &made[0], opts)?;
    let timed = RenderOptions { warmup: 0, runs: warm + opts.runs.max(1), ..*opts };
    let mut out = Vec::new();
    let total = (moves.len() * places as usize * sets.len()) as u64;
    for &moved in moves {
        for place in 0..places {
            let order: Vec<usize> =
                if place % 2 == 0 { (0..sets.len()).collect() } else { (0..sets.len()).rev().collect() };
            for i in order {
                let _doing = activity::doing(format!("{moved:?}: {} at place {place}", sets[i]));
                let at = At { moved, place, set: i };
                out.push(time_at(ctx, scene, (&fixed, &made), at, (&timed, warm as usize))?);
                progress::report("places", out.len() as u64, total);
            }
        }
    }
    ctx.check_validation()?;
    Ok(out)
}

/// Warm-up traces per place: as many as `place_warm_ms()` takes, counted from one trace after
/// the first warm-up of the study (at least `MIN_WARM_MS`), which brings the clocks up.
fn warm_traces(
    ctx: &Arc<Context>,
    (scene, outputs): &(UploadedScene, SharedOutputs),
    set: &(ShaderSet, PipelineKind),
    opts: &RenderOptions,
) -> Result<u32> {
    let size = (opts.width, opts.height);
    let render = SetRender::each(ctx, scene, outputs, std::slice::from_ref(set), (opts, LayoutDraw::Sbt))?.remove(0);
    render.trace_output(ctx, outputs, size)?;
    let trace = render.timed_trace_after(ctx, size, (1, opts.runs.max(1)), min_warm_ms()?)?;
    tracing::submit(ctx, &render.prepared.one_shot, &[trace], |_, _| {}, |_, _| {})?;
    let ms = stats::median(&render.times()?).unwrap_or(1.0);
    Ok(((place_warm_ms()? / ms.max(1e-6)).ceil() as u32).clamp(2, 500))
}

/// Which move, place and set.
#[derive(Clone, Copy)]
struct At {
    moved: Move,
    place: u32,
    set: usize,
}

/// One set at one place of one move.
fn time_at(
    ctx: &Arc<Context>,
    scene: &Scene,
    (fixed, sets): (&(UploadedScene, SharedOutputs), &[(ShaderSet, PipelineKind)]),
    at: At,
    (opts, warm): (&RenderOptions, usize),
) -> Result<PlaceTime> {
    let id = placement::place(at.place, at.set, sets.len());
    let mut rng = SplitMix64(0x9ad5_eed0_0053 ^ id.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    let pad_bytes = match at.moved {
        Move::None | Move::Code | Move::Reused | Move::Layout => 0,
        Move::Sbt => 256 * (1 + rng.next_u64() % 4096),
        Move::Buffers => 256 * (1 + rng.next_u64() % 65536),
    };
    let spacer_sets: Vec<_> = match at.moved {
        Move::Code | Move::Reused => placement::spacer_sets(id, sets.len()).iter().map(|&k| sets[k].clone()).collect(),
        _ => Vec::new(),
    };
    let pad = |location| -> Result<Option<Buffer>> {
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
        (pad_bytes > 0).then(|| Buffer::new(ctx, "place pad", pad_bytes, usage, location)).transpose()
    };
    // A fresh upload behind pads moves every buffer; the others keep the study's.
    let moved_scene = match at.moved {
        Move::Buffers => {
            let pads = (pad(MemoryLocation::GpuOnly)?, pad(MemoryLocation::CpuToGpu)?);
            Some((upload_shared(ctx, scene, None, (opts.width, opts.height))?, SharedOutputs::new(ctx, opts)?, pads))
        }
        _ => None,
    };
    let (uploaded, outputs) = moved_scene.as_ref().map_or((&fixed.0, &fixed.1), |(u, o, _)| (u, o));
    // Spacers allocate no buffer: a pad made before them lands right before the SBT.
    let _sbt_pad = if at.moved == Move::Sbt { pad(MemoryLocation::CpuToGpu)? } else { None };
    let salted = at.moved != Move::Reused;
    let layout = if at.moved == Move::Layout { LayoutDraw::Place(id) } else { LayoutDraw::Sbt };
    let placed = Placed::new(ctx, (uploaded, outputs), &sets[at.set], (&spacer_sets, salted, layout), opts)?;
    let (render, make_ms) = (&placed.render, placed.made_ms);
    let size = (opts.width, opts.height);
    // After a long gap the clocks may have fallen: warm up as at the start (untimed).
    if make_ms > placement::LONG_GAP_MS {
        let long = render.timed_trace_after(ctx, size, (1, 1), min_warm_ms()?)?;
        tracing::submit(ctx, &render.prepared.one_shot, &[long], |_, _| {}, |_, _| {})?;
    }
    let trace = render.timed_trace_after(ctx, size, (0, opts.runs), 0.0)?;
    tracing::submit(ctx, &render.prepared.one_shot, &[trace], |_, _| {}, |_, _| {})?;
    let times = render.times()?;
    let (warm_ms, timed) = times.split_at(warm.min(times.len()));
    let median_ms = stats::median(timed).ok_or_else(|| Error::Unsupported(format!("{} cannot time", ctx.info.name)))?;
    Ok(PlaceTime {
        moved: at.moved,
        set: sets[at.set].0.to_string(),
        place: at.place,
        median_ms,
        warm_ms: warm_ms.to_vec(),
        make_ms,
        long_gap: make_ms > placement::LONG_GAP_MS,
        spacers: spacer_sets.len(),
        pad_bytes,
        sbt_address: render.prepared.sbt.as_ref().map_or(0, |s| s.raygen.device_address),
    })
}

/// Per move and set: how its places spread.
#[derive(Clone, Debug, Serialize)]
pub struct Spread {
    #[serde(rename = "move")]
    pub moved: Move,
    pub set: String,
    pub places: usize,
    /// The geometric mean of the place medians, and their standard deviation as a fraction
    /// (of the logs).
    pub mean_ms: f64,
    pub sd: f64,
    pub min_ms: f64,
    pub max_ms: f64,
    /// The median over places of the first warm-up trace over the place's timed median: well
    /// above 1 when the clocks fell while the CPU made the place.
    pub first_warm: f64,
    pub make_ms: f64,
    /// This set's time over the first set's, paired by place, with its interval.
    pub to_first: Option<RatioInterval>,
}

/// The spread of every move and set of `times`.
pub fn spreads(times: &[PlaceTime]) -> Vec<Spread> {
    let mut keys: Vec<(Move, &str)> = Vec::new();
    for t in times {
        if !keys.contains(&(t.moved, &t.set)) {
            keys.push((t.moved, &t.set));
        }
    }
    let of = |moved: Move, set: &str| -> Vec<&PlaceTime> {
        let mut v: Vec<&PlaceTime> = times.iter().filter(|t| t.moved == moved && t.set == set).collect();
        v.sort_by_key(|t| t.place);
        v
    };
    keys.iter()
        .map(|&(moved, set)| {
            let these = of(moved, set);
            let first_set = keys.iter().find(|k| k.0 == moved).map_or(set, |k| k.1);
            let first = of(moved, first_set);
            let ms: Vec<f64> = these.iter().map(|t| t.median_ms).collect();
            let logs = RatioInterval::of_logs(&ms.iter().map(|m| m.ln()).collect::<Vec<_>>());
            let warm: Vec<f64> = these.iter().filter_map(|t| t.warm_ms.first().map(|w| w / t.median_ms)).collect();
            let make: Vec<f64> = these.iter().map(|t| t.make_ms).collect();
            Spread {
                moved,
                set: set.to_string(),
                places: ms.len(),
                mean_ms: logs.map_or(f64::NAN, |l| l.ratio),
                sd: logs.map_or(f64::NAN, |l| l.log_sd),
                min_ms: ms.iter().copied().fold(f64::INFINITY, f64::min),
                max_ms: ms.iter().copied().fold(0.0, f64::max),
                first_warm: stats::median(&warm).unwrap_or(f64::NAN),
                make_ms: stats::median(&make).unwrap_or(f64::NAN),
                to_first: (first_set != set)
                    .then(|| RatioInterval::paired(&ms, &first.iter().map(|t| t.median_ms).collect::<Vec<_>>()))
                    .flatten(),
            }
        })
        .collect()
}
