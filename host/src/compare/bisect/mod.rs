//! `twinray bisect`: which stage makes two shader sets differ. It runs A, B and, for every
//! stage whose modules differ between them, A with that stage taken from B and B with it taken
//! from A; where no single stage explains a difference, every pair of stages the same way; and
//! where a stage of several modules (the intersection stage: one per shape) explains one,
//! each of its modules alone.
//!
//! A swap's *share* of a difference is how much of it the swap carries, in each direction:
//! for images, `1 - left² / whole²` of the RMSE (left: what still differs from the other set
//! after the swap) and `1 - left / whole` of the hit mismatches; for time, the fraction of
//! `t(B) - t(A)` the swap moves. A swap *explains* the image difference when both directions
//! carry at least [`IMAGE_EXPLAINED`] of every part of it that is not zero, and the time
//! difference when both carry at least [`TIME_EXPLAINED_EACH`] and together on average
//! [`TIME_EXPLAINED`]: time adds up from every stage less exactly than images do.

mod report;
mod subject;

pub use subject::{Gap, ImageSubject, ProbeSubject, Run, Subject, PROBE_T_TOLERANCE};

use crate::error::Result;
use crate::render::isolated::AloneIn;
use crate::sets::{ShaderSet, Stage, MODULES};
use crate::util::interval::RatioInterval;
use crate::util::stats::median;
use serde::Serialize;

/// Share of an image difference a swap must carry in both directions to explain it.
pub const IMAGE_EXPLAINED: f64 = 0.9;
/// Share of a time difference a swap must carry on average over both directions...
pub const TIME_EXPLAINED: f64 = 0.75;
/// ...and in each.
pub const TIME_EXPLAINED_EACH: f64 = 0.5;
/// A time difference counts when its 95% interval over placements excludes 1 and it is at
/// least this fraction of A's time: a smaller one, though resolved, is left unbisected.
pub const MIN_TIME_DIFFERENCE: f64 = 0.02;

/// Stages or modules swapped together.
#[derive(Clone, Debug, PartialEq)]
pub struct Unit {
    pub name: String,
    pub modules: Vec<&'static str>,
}

/// One swap, both ways.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub unit: String,
    /// The modules it swaps (those of the subject's pipeline that differ between A and B).
    pub modules: Vec<&'static str>,
    /// A with the unit from B, and B with it from A.
    pub a_with: String,
    pub b_with: String,
    /// What still differs: A-with against B, and B-with against A.
    pub left_forward: Gap,
    pub left_reverse: Gap,
    /// Shares of the image difference, [A to B, B to A]; null where that part is zero.
    pub rmse_share: Option<[f64; 2]>,
    pub mismatch_share: Option<[f64; 2]>,
    /// Median GPU ms of A-with and B-with, their ratios against A and B (with intervals over
    /// placements), and their shares of the time difference (null when it is not judged or not
    /// resolved).
    pub gpu_ms: [Option<f64>; 2],
    pub ratio_forward: Option<RatioInterval>,
    pub ratio_reverse: Option<RatioInterval>,
    pub time_share: Option<[f64; 2]>,
    pub explains_image: bool,
    pub explains_time: bool,
}

/// Whether there was a difference and what explains it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Finding {
    /// "none", "significant", "within noise", "under 2%" or "not judged (...)".
    pub difference: String,
    /// The units (stages, pairs "a+b", or modules "stage: module") that explain it.
    pub explained_by: Vec<String>,
    pub pinned: bool,
}

/// `twinray bisect`'s result; `--json` prints it.
#[derive(Clone, Debug, Serialize)]
pub struct BisectReport {
    pub subject: String,
    pub device: String,
    pub set_a: String,
    pub set_b: String,
    pub whole: Gap,
    /// Median GPU ms of A and B: the median of their placements' medians.
    pub gpu_ms_a: Option<f64>,
    pub gpu_ms_b: Option<f64>,
    /// t(B) / t(A), with its 95% interval over placements (or rounds of processes), and that
    /// in words.
    pub ratio: Option<RatioInterval>,
    /// Processes each set was timed alone in (`--processes`); 0: all in this one.
    pub processes: u32,
    /// What those were: child processes or fresh devices in this one (`--alone-in`).
    pub alone_in: AloneIn,
    pub time_verdict: String,
    pub raygen_stack_bytes_a: u64,
    pub raygen_stack_bytes_b: u64,
    /// The subject's modules that are the same code in both sets.
    pub same_modules: Vec<&'static str>,
    pub stages: Vec<Row>,
    pub pairs: Vec<Row>,
    pub modules: Vec<Row>,
    pub image: Finding,
    pub time: Finding,
    /// Both findings pinned: exit code 0 (when A and B wrote every output).
    pub pinned: bool,
    /// What A or B left unwritten of its output, or wrote non-finite: each fails the command.
    pub failures: Vec<String>,
}

/// Per stage, the modules of `used` that differ between `a` and `b`.
pub fn stage_units(a: &ShaderSet, b: &ShaderSet, used: &[&'static str]) -> Vec<Unit> {
    Stage::ALL
        .iter()
        .filter_map(|stage| {
            let modules: Vec<&'static str> = MODULES
                .iter()
                .filter(|m| m.stage == *stage && used.contains(&m.name) && !a.same_module(b, m.name))
                .map(|m| m.name)
                .collect();
            (!modules.is_empty()).then(|| Unit { name: stage.name().to_string(), modules })
        })
        .collect()
}

/// Every pair of `units`, as one unit each.
fn pairs(units: &[Unit]) -> Vec<Unit> {
    let mut out = Vec::new();
    for (i, x) in units.iter().enumerate() {
        for y in &units[i + 1..] {
            let modules = x.modules.iter().chain(&y.modules).copied().collect();
            out.push(Unit { name: format!("{}+{}", x.name, y.name), modules });
        }
    }
    out
}

/// A and B's figures that every row is measured against.
struct Base {
    whole: Gap,
    ms: [Option<f64>; 2],
    /// B's time over A's.
    interval: Option<RatioInterval>,
    time_judged: Result<(), String>,
}

impl Base {
    fn new<T>(subject: &dyn Subject<Data = T>, a: &Run<T>, b: &Run<T>) -> Base {
        let interval = RatioInterval::paired(&b.placement_ms, &a.placement_ms);
        let time_judged = match interval {
            None => Err("not judged (the device cannot time)".into()),
            Some(i) if !i.has_interval() => Err("not judged (one placement: give --placements 2 or more)".into()),
            Some(i) if !i.resolved() => Err("within noise".into()),
            Some(i) if (i.ratio - 1.0).abs() < MIN_TIME_DIFFERENCE => Err("under 2%".into()),
            Some(_) => Ok(()),
        };
        let ms = [median(&a.placement_ms), median(&b.placement_ms)];
        Base { whole: subject.gap(&a.data, &b.data), ms, interval, time_judged }
    }

    fn row<T>(&self, subject: &dyn Subject<Data = T>, unit: &Unit, sets: [String; 2], runs: [&Run<T>; 4]) -> Row {
        let [a, b, a_with, b_with] = runs;
        let (left_forward, left_reverse) = (subject.gap(&a_with.data, &b.data), subject.gap(&b_with.data, &a.data));
        let share = |whole: f64, left: [f64; 2]| (whole > 0.0).then(|| left.map(|l| 1.0 - l / whole));
        let rmse_share = share(self.whole.rmse.powi(2), [left_forward.rmse.powi(2), left_reverse.rmse.powi(2)]);
        let mismatch_share =
            share(self.whole.mismatches as f64, [left_forward.mismatches as f64, left_reverse.mismatches as f64]);
        let gpu_ms = [a_with, b_with].map(|r| median(&r.placement_ms));
        let [ta, tb] = self.ms;
        let time_share = match (self.time_judged.is_ok(), ta, tb, gpu_ms) {
            (true, Some(ta), Some(tb), [Some(fa), Some(fb)]) => Some([(fa - ta) / (tb - ta), (tb - fb) / (tb - ta)]),
            _ => None,
        };
        let enough = |s: Option<[f64; 2]>| s.is_none_or(|[f, r]| f >= IMAGE_EXPLAINED && r >= IMAGE_EXPLAINED);
        let explains_image = !self.whole.is_zero() && enough(rmse_share) && enough(mismatch_share) && {
            // A difference only in pixels over the threshold (no RMSE, no hits) cannot be.
            rmse_share.is_some() || mismatch_share.is_some()
        };
        let explains_time =
            time_share.is_some_and(|[f, r]| f.min(r) >= TIME_EXPLAINED_EACH && (f + r) / 2.0 >= TIME_EXPLAINED);
        let [a_with_name, b_with_name] = sets;
        Row {
            unit: unit.name.clone(),
            modules: unit.modules.clone(),
            a_with: a_with_name,
            b_with: b_with_name,
            left_forward,
            left_reverse,
            rmse_share,
            mismatch_share,
            gpu_ms,
            ratio_forward: RatioInterval::paired(&a_with.placement_ms, &a.placement_ms),
            ratio_reverse: RatioInterval::paired(&b_with.placement_ms, &b.placement_ms),
            time_share,
            explains_image,
            explains_time,
        }
    }
}

/// Runs A, B and each unit's two swaps in one go (so their times are measured together) and
/// returns the rows, with A's and B's figures from the same run.
fn swaps<T>(
    subject: &mut dyn Subject<Data = T>,
    a: &ShaderSet,
    b: &ShaderSet,
    units: &[Unit],
) -> Result<(Base, Vec<Row>, [Run<T>; 2])> {
    let mut sets = vec![a.clone(), b.clone()];
    for unit in units {
        sets.push(a.with_modules_from(b, &unit.modules));
        sets.push(b.with_modules_from(a, &unit.modules));
    }
    let mut runs = subject.run(&sets)?.into_iter();
    let (Some(run_a), Some(run_b)) = (runs.next(), runs.next()) else {
        return Err(crate::error::Error::Unsupported("a bisect run returned fewer runs than sets".into()));
    };
    let base = Base::new(subject, &run_a, &run_b);
    let rest: Vec<Run<T>> = runs.collect();
    let rows = units
        .iter()
        .zip(rest.chunks_exact(2))
        .zip(sets[2..].chunks_exact(2))
        .map(|((unit, r), s)| {
            base.row(subject, unit, [s[0].to_string(), s[1].to_string()], [&run_a, &run_b, &r[0], &r[1]])
        })
        .collect();
    Ok((base, rows, [run_a, run_b]))
}

/// Bisects the difference between `a` and `b` on `subject`.
pub fn bisect<T>(subject: &mut dyn Subject<Data = T>, a: &ShaderSet, b: &ShaderSet) -> Result<BisectReport> {
    let used = subject.modules();
    let units = stage_units(a, b, &used);
    let (base, stages, [run_a, run_b]) = swaps(subject, a, b, &units)?;
    let single_image = stages.iter().any(|r| r.explains_image);
    let single_time = stages.iter().any(|r| r.explains_time);
    let image_open = image_difference(&base.whole).is_ok() && !single_image;
    let time_open = base.time_judged.is_ok() && !single_time;
    let pairs = if (image_open || time_open) && units.len() >= 3 {
        swaps(subject, a, b, &pairs(&units))?.1
    } else {
        Vec::new()
    };
    let mut drill = Vec::new();
    for row in stages.iter().filter(|r| (r.explains_image || r.explains_time) && r.modules.len() > 1) {
        let units: Vec<Unit> =
            row.modules.iter().map(|m| Unit { name: format!("{}: {m}", row.unit), modules: vec![m] }).collect();
        drill.extend(swaps(subject, a, b, &units)?.1);
    }
    let image = finding(image_difference(&base.whole), [&stages, &pairs, &drill], |r| r.explains_image);
    let time =
        finding(base.time_judged.clone().map(|()| "significant"), [&stages, &pairs, &drill], |r| r.explains_time);
    let [gpu_ms_a, gpu_ms_b] = base.ms;
    let mut failures = run_a.written.problems(&format!("A ({a})"), subject.items());
    failures.extend(run_b.written.problems(&format!("B ({b})"), subject.items()));
    Ok(BisectReport {
        failures,
        subject: subject.name(),
        device: subject.device(),
        set_a: a.to_string(),
        set_b: b.to_string(),
        whole: base.whole,
        gpu_ms_a,
        gpu_ms_b,
        ratio: base.interval,
        processes: subject.processes().0,
        alone_in: subject.processes().1,
        time_verdict: base.interval.map_or("the device cannot time".into(), |i| i.verdict("B")),
        raygen_stack_bytes_a: run_a.raygen_stack_bytes,
        raygen_stack_bytes_b: run_b.raygen_stack_bytes,
        same_modules: used.iter().copied().filter(|m| a.same_module(b, m)).collect(),
        pinned: image.pinned && time.pinned,
        stages,
        pairs,
        modules: drill,
        image,
        time,
    })
}

/// Whether the image difference must be pinned: Ok("present") when it breaks the scene's
/// tolerance; "within tolerance" (bisected, but a few rounding-level pixels that no stage
/// alone carries need not be pinned) or "none" otherwise.
fn image_difference(whole: &Gap) -> std::result::Result<&'static str, String> {
    if whole.is_zero() {
        Err("none".into())
    } else if whole.within_tolerance {
        Err("within tolerance".into())
    } else {
        Ok("present")
    }
}

/// The finding for one kind of difference: `present` is Ok when there is one that must be
/// explained, else why not (and then nothing needs pinning, though what explains it is still
/// named). Explained by the single stages that explain it, else by the pairs; modules that
/// explain it refine a stage.
fn finding(present: std::result::Result<&str, String>, rows: [&[Row]; 3], explains: impl Fn(&Row) -> bool) -> Finding {
    let [stages, pairs, modules] = rows;
    let names = |rows: &[Row]| rows.iter().filter(|r| explains(r)).map(|r| r.unit.clone()).collect::<Vec<_>>();
    let mut explained_by = names(stages);
    if explained_by.is_empty() {
        explained_by = names(pairs);
    }
    let found = !explained_by.is_empty();
    explained_by.extend(names(modules));
    match present {
        Err(why) => Finding { difference: why, explained_by, pinned: true },
        Ok(label) => Finding { difference: label.into(), explained_by, pinned: found },
    }
}

#[cfg(test)]
mod tests;
