//! index.html: the bench at a glance, readable from the folder without a server: how it was
//! run, the plots, the Rust/GLSL ratios, the convergence slopes, every measurement, and per
//! scene the reference beside each set's images and FLIP error maps.

use super::plots::{error_by_spp, log_slope, sampler_by_count, Series};
use super::tables::SceneRatio;
use super::{BenchReport, BenchRow};
use std::fmt::Write;
use std::path::Path;
use twinray_host::error::{Error, Result};

/// `text` safe inside HTML text and attribute values.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Writes `index.html`: the tables, plots and images of the report, with the command that made it.
pub fn write(report: &BenchReport, ratios: &[SceneRatio], command: &str, dir: &Path) -> Result<()> {
    let html = page(report, ratios, command);
    let path = dir.join("index.html");
    std::fs::write(&path, html).map_err(|source| Error::Io { what: "writing", path, source })
}

fn page(report: &BenchReport, ratios: &[SceneRatio], command: &str) -> String {
    let mut s = String::from(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>twinray bench</title><style>\n\
         body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse;margin:1em 0}\n\
         td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#eee}td.l{text-align:left}\n\
         img{image-rendering:pixelated;max-width:100%}figure{display:inline-block;margin:4px;text-align:center}\n\
         figcaption{font-size:small}.plots img{width:32%}</style></head><body>\n<h1>twinray bench</h1>\n",
    );
    let threads = report.cpu_threads.map_or(String::new(), |t| format!(", {t} threads"));
    let _ = write!(
        s,
        "<p>Device: <b>{}</b>{threads}. GPU time (timestamp queries): {} placements, each making every set's \
         pipeline afresh in an order of its own, each of {} timed traces per set after {} untimed ones; the median \
         and interquartile range of all traces pooled, and each ratio's 95% interval over placements. Reference: {} samples per pixel rendered by {}. Errors are on display \
         values (radiance clamped to [0, 1]).</p>\n<p>Command: <code>{}</code></p>\n",
        escape(&report.device),
        report.placements,
        report.runs,
        report.warmup,
        report.reference_spp,
        escape(&report.reference_set),
        escape(command),
    );
    s += "<h2>Plots</h2>\n<div class=\"plots\"><img src=\"plots/error-spp.svg\" alt=\"error against samples per pixel\">\
          <img src=\"plots/error-time.svg\" alt=\"error against GPU time\"><img src=\"plots/ratio.svg\" alt=\"Rust/GLSL time\">\
          <img src=\"plots/places.svg\" alt=\"each set's time at each place\"></div>\n";
    s += &ratio_table(ratios);
    s += &pairs_table(report);
    s += "<h2>Convergence</h2>\n<p>Least-squares slope of log RMSE against log samples per pixel (N<sup>-0.5</sup>: \
          independent samples; N<sup>-0.75</sup>: stratified samples near edges).</p>\n";
    s += &slope_table(&error_by_spp(report));
    s += &samplers_section(report);
    s += &variants_section(report);
    s += &spirv_table(report);
    s += &rows_table(&report.rows);
    for (scene, reference) in &report.references {
        s += &gallery(report, scene, reference);
    }
    s += "</body></html>\n";
    s
}

fn ratio_table(ratios: &[SceneRatio]) -> String {
    let mut s = String::from(
        "<h2>Rust / GLSL GPU time</h2>\n<p>The geometric mean of the ratios of each placement's medians, with its 95% \
         interval over placements (a t interval on their logs); red where the interval lies wholly above 1.05.</p>\n\
         <table><tr><th>scene</th><th>spp</th><th>ratio</th><th>95% interval</th><th>placements</th><th>verdict</th></tr>\n",
    );
    for (scene, spp, r) in ratios {
        let flag = if r.low > 1.05 { " style=\"color:#b00\"" } else { "" };
        let _ = writeln!(
            s,
            "<tr><td class=\"l\">{}</td><td>{spp}</td><td{flag}>{:.3}</td><td>{:.3} to {:.3}</td><td>{}</td><td class=\"l\">{}</td></tr>",
            escape(scene),
            r.ratio,
            r.low,
            r.high,
            r.placements,
            escape(&r.verdict("rust"))
        );
    }
    s + "</table>\n"
}

/// Every pair of sets measured together, the null controls first.
fn pairs_table(report: &BenchReport) -> String {
    let mut s = String::from(
        "<h2>Every pair of sets</h2>\n<p>Each earlier set's time over each later one's; a null control times a \
         salted copy of a set (the same code, built apart) and its interval should hold 1.</p>\n<table><tr>\
         <th>scene</th><th>spp</th><th>a / b</th><th>ratio</th><th>95% interval</th><th>verdict</th></tr>\n",
    );
    let mut pairs: Vec<_> = report.ratios.iter().collect();
    pairs.sort_by_key(|r| !r.null_control);
    for r in pairs {
        let null = if r.null_control { " (null control)" } else { "" };
        let _ = writeln!(
            s,
            "<tr><td class=\"l\">{}</td><td>{}</td><td class=\"l\">{} / {}{null}</td><td>{:.3}</td><td>{:.3} to {:.3}</td><td class=\"l\">{}</td></tr>",
            escape(&r.scene),
            r.spp,
            escape(&r.a),
            escape(&r.b),
            r.interval.ratio,
            r.interval.low,
            r.interval.high,
            escape(&r.verdict)
        );
    }
    s + "</table>\n"
}

fn slope_table(all: &[Series]) -> String {
    let mut s = String::from("<table><tr><th>series</th><th>slope</th></tr>\n");
    for series in all {
        let slope = log_slope(&series.points).map_or("n/a".into(), |v| format!("{v:.3}"));
        let _ = writeln!(s, "<tr><td class=\"l\">{}</td><td>{slope}</td></tr>", escape(&series.label));
    }
    s + "</table>\n"
}

fn samplers_section(report: &BenchReport) -> String {
    if report.samplers.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "<h2>Shadow samplers</h2>\n<p>Soft-shadow scenes, one primary sample at each pixel's centre, N x N shadow \
         samples per rect light: stratified jittered against independent random, against a reference that converges \
         the shadows at pixel centres. Equal counts are equal rays; the time plot compares them at equal time.</p>\n\
         <div class=\"plots\"><img src=\"plots/sampler-spp.svg\" alt=\"error against shadow samples\">\
         <img src=\"plots/sampler-time.svg\" alt=\"error against time\"></div>\n",
    );
    s += &slope_table(&sampler_by_count(report));
    s += "<table><tr><th>scene</th><th>sampler</th><th>shadow samples</th><th>GPU ms</th><th>RMSE</th><th>mean FLIP</th></tr>\n";
    for r in &report.samplers {
        let ms = r.gpu_ms.map_or("n/a".into(), |t| format!("{:.4}", t.median));
        let _ = writeln!(
            s,
            "<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td>{ms}</td><td>{:.5}</td><td>{:.4}</td></tr>",
            escape(&r.scene),
            r.sampler,
            r.shadow_spp,
            r.rmse,
            r.flip
        );
    }
    s + "</table>\n"
}

fn variants_section(report: &BenchReport) -> String {
    if report.variants.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "<h2>Intersection variants</h2>\n<p>Probe cases (the hard-case suite) traced with the robust and the naive \
         formulas in the same run: GPU time per million rays against p99 relative t error and wrong answers on decided \
         rays. Cases with no t error (surface rays, judged by what they see) sit at 1e-9.</p>\n<div class=\"plots\"><img src=\"plots/variants.svg\" alt=\"time against error\"></div>\n\
         <table><tr><th>case</th><th>variant</th><th>robust ms/Mray</th><th>naive ms/Mray</th><th>robust/naive</th>\
         <th>robust t p99</th><th>naive t p99</th><th>robust, naive condition multiple p99</th><th>naive wrong</th></tr>\n",
    );
    for robust in report.variants.iter().filter(|r| r.formula == "robust") {
        let Some(naive) = report.variants.iter().find(|n| n.formula == "naive" && n.report.case == robust.report.case)
        else {
            continue;
        };
        let (a, b) = (robust.report.gpu_ms_per_million_rays, naive.report.gpu_ms_per_million_rays);
        let ms = |v: Option<f64>| v.map_or("n/a".into(), |v| format!("{v:.4}"));
        let ratio = a.zip(b).map_or("n/a".into(), |(a, b)| format!("{:.3}", a / b));
        let _ = writeln!(
            s,
            "<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td>{}</td><td>{ratio}</td><td>{:.2e}</td><td>{:.2e}</td><td>{:.2}, {:.2}</td><td>{}</td></tr>",
            escape(&robust.report.case),
            escape(&robust.variant),
            ms(a),
            ms(b),
            robust.report.relative_t_error.p99,
            naive.report.relative_t_error.p99,
            robust.report.condition_multiple.p99,
            naive.report.condition_multiple.p99,
            naive.report.false_hits + naive.report.false_misses + naive.report.wrong_object,
        );
    }
    s + "</table>\n"
}

fn spirv_table(report: &BenchReport) -> String {
    let mut s = String::from(
        "<h2>SPIR-V per stage</h2>\n<table><tr><th>module</th><th>Rust bytes</th><th>GLSL bytes</th>\
         <th>Rust instructions</th><th>GLSL instructions</th></tr>\n",
    );
    for m in &report.spirv {
        let _ = writeln!(
            s,
            "<tr><td class=\"l\">{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            m.module, m.rust_bytes, m.glsl_bytes, m.rust_instructions, m.glsl_instructions
        );
    }
    s + "</table>\n"
}

fn rows_table(rows: &[BenchRow]) -> String {
    let mut s = String::from(
        "<h2>Measurements</h2>\n<table><tr><th>scene</th><th>set</th><th>spp</th><th>GPU ms</th><th>IQR of traces</th>\
         <th>Mrays/s</th><th>primary rays (the scene's)</th><th>shadow rays (raygen's count)</th><th>RMSE</th><th>PSNR dB</th><th>mean FLIP</th><th>hit mismatches</th><th>raygen stack B</th></tr>\n",
    );
    for r in rows {
        let (ms, iqr) =
            r.gpu_ms.map_or(("n/a".into(), String::new()), |t| (format!("{:.4}", t.median), format!("{:.4}", t.iqr())));
        let _ = writeln!(
            s,
            "<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td>{ms}</td><td>{iqr}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td>{:.5}</td><td>{}</td><td>{:.4}</td><td>{}</td><td>{}</td></tr>",
            escape(&r.scene),
            escape(&r.set),
            r.spp,
            r.mrays_per_s.map_or("n/a".into(), |v| format!("{v:.1}")),
            r.rays.primary,
            r.rays.shadow,
            r.rmse,
            if r.psnr.is_finite() { format!("{:.2}", r.psnr) } else { "inf".into() },
            r.flip,
            r.hit_mismatches.map_or("-".into(), |m| match r.hit_mismatches_set_apart {
                Some(apart) if apart > 0 => format!("{m} (+{apart} either right)"),
                _ => m.to_string(),
            }),
            r.raygen_stack_bytes,
        );
    }
    s + "</table>\n"
}

fn gallery(report: &BenchReport, scene: &str, reference: &str) -> String {
    let mut s = format!(
        "<h2>{0}</h2>\n<figure><img src=\"{1}\" alt=\"reference\"><figcaption>reference, {2} spp</figcaption></figure><br>\n",
        escape(scene),
        escape(reference),
        report.reference_spp
    );
    for r in report.rows.iter().filter(|r| r.scene == scene) {
        let (Some(image), Some(error_map)) = (&r.image, &r.error_map) else { continue };
        let _ = writeln!(
            s,
            "<figure><img src=\"{0}\" alt=\"image\"><img src=\"{1}\" alt=\"FLIP error map\">\
             <figcaption>{2}, {3} spp: RMSE {4:.4}, FLIP {5:.4}</figcaption></figure>",
            escape(image),
            escape(error_map),
            escape(&r.set),
            r.spp,
            r.rmse,
            r.flip
        );
    }
    s
}
