//! The hard-case suite (`twinray stability`): every probe case of a folder, for each shader
//! set and formula, judged against the f64 reference; the robust formulas against each case's
//! targets.

use super::case::ProbeCase;
use super::generate::Generator;
use super::report::{evaluate, ProbeReport};
use super::run::{probe, ProbeOutput};
use crate::error::{Error, Result};
use crate::scene::shape::Formula;
use crate::sets::ShaderSet;
use crate::vk::context::Context;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One row of the suite: a case run with one set and formula.
#[derive(Clone, Debug, serde::Serialize)]
pub struct StabilityRow {
    pub formula: &'static str,
    /// What the formula changes in this case: its hit groups (robust names), or "shadow rays
    /// from" them for surface rays.
    pub variant: String,
    #[serde(flatten)]
    pub report: ProbeReport,
    /// Broken targets (robust rows only); empty when the row meets them.
    pub failures: Vec<String>,
}

/// A case (or scene) a suite did not run, and why: a module it needs declares what the device
/// lacks (`Error::DeviceLacks`). The rest of the suite is judged without it.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Skipped {
    pub name: String,
    pub why: String,
}

impl Skipped {
    /// The one line a suite prints for it.
    pub fn line(&self) -> String {
        format!("skipped {}: {}", self.name, self.why)
    }
}

/// The rows of a suite run, and the cases it skipped.
#[derive(Clone, Debug, Default)]
pub struct Suite {
    pub rows: Vec<StabilityRow>,
    pub skipped: Vec<Skipped>,
}

/// The case files of `dir`, sorted by name; where there is no folder `dir`, the built-in cases
/// of that name (`probes/stability`), each as the path `builtin::open` reads it by.
pub fn case_files(dir: &Path) -> Result<Vec<PathBuf>> {
    // Where no such folder is (an installed twinray), the built-in cases of that name.
    if let Some(cases) = (!dir.exists()).then(|| super::builtin::folder(dir)).flatten() {
        return Ok(cases);
    }
    let entries =
        std::fs::read_dir(dir).map_err(|e| Error::Input(format!("probe case folder {}: {e}", dir.display())))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(Error::Input(format!("{}: no probe cases (*.toml)", dir.display())));
    }
    Ok(files)
}

/// How GPU time is taken: `runs` timed passes after `warmup`, each over the case's rays
/// repeated up to at least `rays` rays (a case's few thousand rays alone take too little
/// time to measure), or over the case's rays alone when `rays` is 0.
#[derive(Clone, Copy, Debug)]
pub struct Timing {
    pub warmup: u32,
    pub runs: u32,
    pub rays: usize,
}

/// Runs every case with every set and formula, in one probe each: accuracy from the first
/// copy of the case's rays, GPU time as `timing` says. A case that needs what the device lacks
/// is skipped (with `skipped(line)` called as it is), and the others run.
pub fn run(
    ctx: &Arc<Context>,
    files: &[PathBuf],
    sets: &[ShaderSet],
    formulas: &[Formula],
    timing: Timing,
    mut skipped: impl FnMut(&Skipped),
) -> Result<Suite> {
    let mut suite = Suite::default();
    for file in files {
        let mut case = super::builtin::open(file, &[])?;
        match run_case(ctx, &mut case, sets, formulas, timing) {
            Ok(rows) => suite.rows.extend(rows),
            Err(e) if e.device_lacks() => {
                let skip = Skipped { name: case.file.name.clone(), why: e.to_string() };
                skipped(&skip);
                suite.skipped.push(skip);
            }
            Err(e) => return Err(e),
        }
    }
    Ok(suite)
}

/// Every set and formula of one case.
fn run_case(
    ctx: &Arc<Context>,
    case: &mut ProbeCase,
    sets: &[ShaderSet],
    formulas: &[Formula],
    timing: Timing,
) -> Result<Vec<StabilityRow>> {
    let mut rows = Vec::new();
    // A case whose shapes have no naive variant and no surface rays runs robust only.
    let has_naive = case.has_naive();
    let variant = variant(case);
    for &formula in formulas.iter().filter(|&&f| f == Formula::Robust || has_naive) {
        case.set_formula(formula);
        for set in sets {
            let (out, gpu_ms) = measure(ctx, case, set, timing)?;
            let report = evaluate(case, out.records(), &set.to_string(), &ctx.info.name, gpu_ms);
            // A set that leaves records unwritten fails with either formula; the textbook
            // formulas are kept to show their wrong answers, which fail a robust row only.
            let wrong = crate::probe::report::wrong_answers(&report);
            let mut failures = report.failures.clone();
            if formula == Formula::Robust {
                failures.extend(self::failures(case, &report));
            } else {
                failures.retain(|f| Some(f) != wrong.as_ref());
            }
            let formula = if formula == Formula::Robust { "robust" } else { "naive" };
            rows.push(StabilityRow { formula, variant: variant.clone(), report, failures });
        }
    }
    Ok(rows)
}

/// See `StabilityRow::variant`.
fn variant(case: &ProbeCase) -> String {
    let groups = case.scene.build().plan.hit_groups;
    let shapes = groups.iter().map(|g| g.name()).collect::<Vec<_>>().join("+");
    let surface = case.file.generators.iter().any(|g| matches!(g, Generator::Surface { .. }));
    if surface {
        format!("shadow rays from {shapes}")
    } else {
        shapes
    }
}

/// One probe of the case's rays repeated as `timing` says: the first copy's results (they are
/// the case's own rays), and the median GPU time of one pass over the case's rays.
fn measure(
    ctx: &Arc<Context>,
    case: &ProbeCase,
    set: &ShaderSet,
    timing: Timing,
) -> Result<(ProbeOutput, Option<f64>)> {
    let n = case.rays.len();
    let copies = timing.rays.div_ceil(n).max(1);
    let rays: Vec<_> = case.rays.iter().copied().cycle().take(n * copies).collect();
    let mut out = probe(ctx, &case.scene, set, &rays, timing.warmup, timing.runs)?;
    out.results.truncate(n);
    for witness in [&mut out.witness, &mut out.driver_witness].into_iter().flatten() {
        witness.truncate(n);
    }
    let ms = crate::util::stats::median(&out.gpu_ms).map(|ms| ms / copies as f64);
    Ok((out, ms))
}

/// The condition multiple (`reference::condition`) a robust row may reach at p99 where its case
/// names none: an error up to 8 times what rounding the problem's inputs to f32 allows. Above
/// it, the formula or the transform lost precision the inputs held.
pub const MAX_CONDITION_MULTIPLE_P99: f64 = 8.0;

/// What a robust report breaks of its case's targets (beyond its wrong answers, which the
/// report's own failures name).
pub fn failures(case: &ProbeCase, r: &ProbeReport) -> Vec<String> {
    let mut failures = Vec::new();
    let targets = case.file.targets;
    if let Some(most) = targets.and_then(|t| t.max_relative_t_p99).filter(|&most| r.relative_t_error.p99 > most) {
        failures.push(format!("relative t p99 {:.2e} > {most:.0e}", r.relative_t_error.p99));
    }
    let most = targets.and_then(|t| t.max_condition_multiple_p99).unwrap_or(MAX_CONDITION_MULTIPLE_P99);
    if r.condition_multiple.p99 > most {
        failures.push(format!("condition multiple p99 {:.2} > {most}", r.condition_multiple.p99));
    }
    if r.decided == 0 {
        failures.push("no ray decided".into());
    }
    failures
}

/// The table `twinray stability` prints, then what robustness costs.
pub fn table(rows: &[StabilityRow]) -> String {
    let mut s = results(rows);
    s += &generators(rows);
    s += &costs(rows);
    s
}

/// GPU time per million rays of the robust formulas over the naive ones, per case and set,
/// both from the same run; then per variant and set, the geometric mean over its cases.
fn costs(rows: &[StabilityRow]) -> String {
    let mut s = format!(
        "\n{:<26} {:<5} {:>14} {:>14} {:>12}\n",
        "cost", "set", "robust ms/Mray", "naive ms/Mray", "robust/naive"
    );
    let mut ratios: Vec<(&str, &str, f64)> = Vec::new();
    for robust in rows.iter().filter(|r| r.formula == "robust") {
        let (case, set) = (&robust.report.case, &robust.report.set);
        let naive = rows.iter().find(|r| r.formula == "naive" && &r.report.case == case && &r.report.set == set);
        let times =
            naive.and_then(|n| Some((robust.report.gpu_ms_per_million_rays?, n.report.gpu_ms_per_million_rays?)));
        if let Some((r, n)) = times {
            s += &format!("{case:<26} {set:<5} {r:>14.4} {n:>14.4} {:>12.3}\n", r / n);
            ratios.push((&robust.variant, set, r / n));
        }
    }
    s += &format!("\n{:<32} {:<5} {:>5} {:>12}\n", "cost per variant", "set", "cases", "robust/naive");
    let mut keys: Vec<(&str, &str)> = ratios.iter().map(|&(v, set, _)| (v, set)).collect();
    keys.sort();
    keys.dedup();
    for (variant, set) in keys {
        let logs: Vec<f64> = ratios.iter().filter(|r| (r.0, r.1) == (variant, set)).map(|r| r.2.ln()).collect();
        let mean = (logs.iter().sum::<f64>() / logs.len() as f64).exp();
        s += &format!("{variant:<32} {set:<5} {:>5} {mean:>12.3}\n", logs.len());
    }
    s
}

/// Per case with generators, set and formula: the rays each generator made and how many hit.
fn generators(rows: &[StabilityRow]) -> String {
    let mut s = format!("\n{:<26} {:<5} {:<7} generators\n", "case", "set", "formula");
    for row in rows.iter().filter(|r| !r.report.generators.is_empty()) {
        let r = &row.report;
        s += &format!("{:<26} {:<5} {:<7} {}\n", r.case, r.set, row.formula, r.generators_made());
    }
    s
}

fn results(rows: &[StabilityRow]) -> String {
    let mut s = format!(
        "{:<26} {:<5} {:<7} {:>5} {:>7} {:>6} {:>6} {:>9} {:>8} {:>10} {:>10} {:>11} {:>8} {:>9} {:>9}  targets\n",
        "case",
        "set",
        "formula",
        "rays",
        "decided",
        "f.hit",
        "f.miss",
        "t p99",
        "cond p99",
        "stage p99",
        "xform p99",
        "driver p99",
        "ulp p99",
        "n p99",
        "ms/Mray"
    );
    // The t error by source (`split`): the stages' own, their transform's, and what the
    // driver's transform would have given.
    let by_source = |r: &ProbeReport| match &r.t_error_by_source {
        Some(split) => (
            format!("{:.2e}", split.stage.p99),
            format!("{:.2e}", split.transform.p99),
            split.driver.as_ref().map_or("n/a".into(), |d| format!("{:.2e}", d.p99)),
        ),
        None => ("n/a".into(), "n/a".into(), "n/a".into()),
    };
    for row in rows {
        let r = &row.report;
        let verdict = if row.formula != "robust" {
            "-".to_string()
        } else if row.failures.is_empty() {
            "met".to_string()
        } else {
            format!("MISSED: {}", row.failures.join("; "))
        };
        let (stage, transform, driver) = by_source(r);
        s += &format!(
            "{:<26} {:<5} {:<7} {:>5} {:>7} {:>6} {:>6} {:>9.2e} {:>8.2} {:>10} {:>10} {:>11} {:>8.1} {:>9.2e} {:>9}  {verdict}\n",
            r.case,
            r.set,
            row.formula,
            r.rays,
            r.decided,
            r.false_hits,
            r.false_misses + r.wrong_object,
            r.relative_t_error.p99,
            r.condition_multiple.p99,
            stage,
            transform,
            driver,
            r.ulp_error_p99,
            r.normal_angle_error_p99,
            r.gpu_ms_per_million_rays.map_or("n/a".into(), |m| format!("{m:.2}")),
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where no such folder is (an installed twinray, here a name no folder of the crate
    /// has), the suite is the built-in hard cases, each of which opens.
    #[test]
    fn without_the_folder_the_suite_is_the_built_in_cases() {
        assert!(!Path::new("stability").exists());
        let files = case_files(Path::new("stability")).unwrap();
        assert!(files.len() >= 24, "{files:?}");
        let case = super::super::builtin::open(&files[0], &[]).unwrap();
        assert!(!case.rays.is_empty());
        let e = case_files(Path::new("no/such/folder")).unwrap_err().to_string();
        assert!(e.contains("probe case folder no/such/folder"), "{e}");
    }
}
