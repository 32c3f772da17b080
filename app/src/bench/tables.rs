//! The bench's numbers as files: results.json (the whole report) and results.csv (one line
//! per scene, set and sample count), and the Rust/GLSL time ratios they imply.

use super::BenchReport;
use std::path::Path;
use twinray_host::error::{Error, Result};
use twinray_host::util::interval::RatioInterval;

/// Rust over GLSL GPU time per scene and sample count, with its interval over placements.
pub type SceneRatio = (String, u32, RatioInterval);

/// Rust over GLSL GPU time per scene and sample count, where both plain sets ran together.
pub fn ratios(report: &BenchReport) -> Vec<SceneRatio> {
    let mut out = Vec::new();
    for r in &report.ratios {
        match (r.a.as_str(), r.b.as_str()) {
            ("rust", "glsl") => out.push((r.scene.clone(), r.spp, r.interval)),
            ("glsl", "rust") => out.push((r.scene.clone(), r.spp, r.interval.inverse())),
            _ => {}
        }
    }
    out
}

/// The columns of `ratios.csv`.
pub const RATIO_CSV_HEADER: &str = "scene,spp,a,b,ratio,ci_low,ci_high,placements,null_control,verdict";

/// `ratios.csv`: one row per scene, sample count and pair of sets.
pub fn ratio_csv(report: &BenchReport) -> String {
    let mut s = format!("{RATIO_CSV_HEADER}\n");
    for r in &report.ratios {
        let i = &r.interval;
        s += &format!(
            "\"{}\",{},\"{}\",\"{}\",{},{},{},{},{},\"{}\"\n",
            r.scene, r.spp, r.a, r.b, i.ratio, i.low, i.high, i.placements, r.null_control, r.verdict
        );
    }
    s
}

/// The columns of `results.csv`.
pub const CSV_HEADER: &str = "scene,set,spp,width,height,gpu_ms_median,gpu_ms_q1,gpu_ms_q3,runs,primary_rays,shadow_rays,mrays_per_s,rmse,psnr,flip,hit_mismatches,raygen_stack_bytes";

/// `results.csv`: one row per scene, set and sample count.
pub fn csv(report: &BenchReport) -> String {
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
    let mut s = format!("{CSV_HEADER}\n");
    for r in &report.rows {
        let spread = r.gpu_ms;
        s += &format!(
            "\"{}\",\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            r.scene,
            r.set,
            r.spp,
            r.width,
            r.height,
            opt(spread.map(|s| s.median)),
            opt(spread.map(|s| s.q1)),
            opt(spread.map(|s| s.q3)),
            spread.map_or(0, |s| s.samples),
            r.rays.primary,
            r.rays.shadow,
            opt(r.mrays_per_s),
            r.rmse,
            if r.psnr.is_finite() { format!("{}", r.psnr) } else { "inf".into() },
            r.flip,
            r.hit_mismatches.map_or(String::new(), |m| m.to_string()),
            r.raygen_stack_bytes,
        );
    }
    s
}

/// The columns of `samplers.csv`.
pub const SAMPLER_CSV_HEADER: &str = "scene,sampler,shadow_spp,gpu_ms_median,gpu_ms_q1,gpu_ms_q3,shadow_rays,rmse,flip";

/// `samplers.csv`: one row per scene, sampler and shadow sample count.
pub fn sampler_csv(report: &BenchReport) -> String {
    let mut s = format!("{SAMPLER_CSV_HEADER}\n");
    for r in &report.samplers {
        let t = |f: fn(&twinray_host::util::stats::Spread) -> f64| {
            r.gpu_ms.as_ref().map_or(String::new(), |s| format!("{}", f(s)))
        };
        s += &format!(
            "\"{}\",{},{},{},{},{},{},{},{}\n",
            r.scene,
            r.sampler,
            r.shadow_spp,
            t(|s| s.median),
            t(|s| s.q1),
            t(|s| s.q3),
            r.rays.shadow,
            r.rmse,
            r.flip
        );
    }
    s
}

/// The columns of `variants.csv`.
pub const VARIANT_CSV_HEADER: &str =
    "case,variant,formula,rays,decided,false_hits,false_misses,relative_t_p99,condition_multiple_p99,gpu_ms_per_million_rays";

/// `variants.csv`: robust against naive intersection per probe case.
pub fn variant_csv(report: &BenchReport) -> String {
    let mut s = format!("{VARIANT_CSV_HEADER}\n");
    for row in &report.variants {
        let r = &row.report;
        let ms = r.gpu_ms_per_million_rays.map_or(String::new(), |v| format!("{v}"));
        s += &format!(
            "\"{}\",\"{}\",{},{},{},{},{},{},{},{ms}\n",
            r.case,
            row.variant,
            row.formula,
            r.rays,
            r.decided,
            r.false_hits,
            r.false_misses,
            r.relative_t_error.p99,
            r.condition_multiple.p99
        );
    }
    s
}

/// Writes results.json, results.csv, ratios.csv, samplers.csv and variants.csv into `dir`.
pub fn write(report: &BenchReport, dir: &Path) -> Result<()> {
    let json = serde_json::to_string_pretty(report).map_err(|e| Error::Input(format!("results.json: {e}")))?;
    let files = [
        ("results.json", json),
        ("results.csv", csv(report)),
        ("ratios.csv", ratio_csv(report)),
        ("samplers.csv", sampler_csv(report)),
        ("variants.csv", variant_csv(report)),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|source| Error::Io { what: "writing", path, source })?;
    }
    Ok(())
}
