//! The animation bench's report: per-frame rows (CSV, JSON), the summary table (Markdown,
//! CSV), plots of AS and trace time per frame, and an index.html with all of it.

use super::measure::{AnimateReport, FrameRow, ModeSummary};
use crate::bench::plots::{write_lines, Series};
use std::fmt::Write;
use std::path::Path;
use twinray_host::error::{Error, Result};
use twinray_host::util::interval::RatioInterval;

fn ms(v: Option<f64>) -> String {
    v.map_or("n/a".into(), |v| format!("{v:.3}"))
}

/// "1.031 (1.012 to 1.050)": the ratio and its 95% interval over placements.
fn ratio(v: Option<RatioInterval>) -> String {
    v.map_or("n/a".into(), |v| {
        if v.has_interval() {
            format!("{:.3} ({:.3} to {:.3})", v.ratio, v.low, v.high)
        } else {
            format!("{:.3}", v.ratio)
        }
    })
}

/// The summary table, in Markdown.
pub fn table(report: &AnimateReport) -> String {
    let mut s = String::from(
        "| instances | TLAS mode | build ms | update ms | AS ms per frame | trace ms, first frame | trace ms, last frame | trace / rebuilt, last frame (95% CI) | trace / rebuilt, median (95% CI) |\n|---:|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for m in &report.summaries {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            m.instances,
            m.mode,
            ms(m.build_ms),
            ms(m.update_ms),
            ms(m.as_ms_per_frame),
            ms(m.trace_ms_first),
            ms(m.trace_ms_last),
            ratio(m.trace_vs_rebuild_last),
            ratio(m.trace_vs_rebuild_median)
        );
    }
    s
}

fn summary_csv(summaries: &[ModeSummary]) -> String {
    let mut s = String::from("instances,mode,build_ms,update_ms,as_ms_per_frame,trace_ms_first,trace_ms_last,trace_vs_rebuild_last,last_ci_low,last_ci_high,trace_vs_rebuild_median,median_ci_low,median_ci_high\n");
    let f = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
    let r = |v: Option<RatioInterval>| v.map_or(",,".into(), |v| format!("{},{},{}", v.ratio, v.low, v.high));
    for m in summaries {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{}",
            m.instances,
            m.mode,
            f(m.build_ms),
            f(m.update_ms),
            f(m.as_ms_per_frame),
            f(m.trace_ms_first),
            f(m.trace_ms_last),
            r(m.trace_vs_rebuild_last),
            r(m.trace_vs_rebuild_median)
        );
    }
    s
}

fn rows_csv(report: &AnimateReport) -> String {
    let mut s = String::from("instances,mode,placement,frame,as_work,as_ms,trace_ms,rays\n");
    let f = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
    for r in &report.rows {
        let work =
            serde_json::to_value(r.as_work).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default();
        let (i, p) = (r.instances, r.placement);
        let _ = writeln!(s, "{i},{},{p},{},{work},{},{},{}", r.mode, r.frame, f(r.as_ms), f(r.trace_ms), r.rays);
    }
    s
}

/// One series per instance count and mode of `value` against the frame, of the first placement.
fn series(report: &AnimateReport, value: impl Fn(&FrameRow) -> Option<f64>) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for r in report.rows.iter().filter(|r| r.placement == 0) {
        let Some(v) = value(r).filter(|v| *v > 0.0) else { continue };
        let label = format!("{} inst, {}", r.instances, r.mode);
        match out.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push((f64::from(r.frame), v)),
            None => out.push(Series { label, points: vec![(f64::from(r.frame), v)] }),
        }
    }
    out
}

fn save(dir: &Path, name: &str, text: &str) -> Result<()> {
    let path = dir.join(name);
    std::fs::write(&path, text).map_err(|source| Error::Io { what: "writing", path, source })
}

/// Writes results.json, frames.csv, summary.csv, summary.md, plots/ and index.html into `dir`.
pub fn write(report: &AnimateReport, command: &str, dir: &Path) -> Result<()> {
    let plots = dir.join("plots");
    std::fs::create_dir_all(&plots).map_err(|source| Error::Io { what: "creating", path: plots.clone(), source })?;
    let json = serde_json::to_string_pretty(report).map_err(|e| Error::Input(format!("writing JSON: {e}")))?;
    save(dir, "results.json", &json)?;
    save(dir, "frames.csv", &rows_csv(report))?;
    save(dir, "summary.csv", &summary_csv(&report.summaries))?;
    save(dir, "summary.md", &table(report))?;
    write_lines(&plots, "as-ms", ("frame", "TLAS GPU ms (build or update)"), &series(report, |r| r.as_ms))?;
    write_lines(&plots, "trace-ms", ("frame", "trace GPU ms (median)"), &series(report, |r| r.trace_ms))?;
    save(dir, "index.html", &page(report, command))
}

fn page(report: &AnimateReport, command: &str) -> String {
    let threads = report.cpu_threads.map_or(String::new(), |t| format!(", {t} threads"));
    let mut s = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>twinray animate-bench</title><style>\n\
         body{{font-family:sans-serif;margin:2em;max-width:1400px}}table{{border-collapse:collapse}}\n\
         td,th{{border:1px solid #ccc;padding:3px 8px;text-align:right}}th{{background:#eee}}img{{width:49%}}</style></head><body>\n\
         <h1>twinray animate-bench</h1>\n<p>Device: <b>{}</b>{threads}. Scene <b>{}</b> at {}x{}, set {}, {} frames per \
         instance count and TLAS mode, rendered {} times (placements: each mode's pipeline made afresh, in an order \
         of its own); per frame, the TLAS work and the median of {} timed traces (after warm-up before the first \
         frame), each between timestamp queries. Ratios carry their 95% interval over placements.</p>\n<p>Command: <code>{}</code></p>\n<table>\n",
        esc(&report.device),
        esc(&report.scene),
        report.width,
        report.height,
        esc(&report.set),
        report.frames,
        report.placements,
        report.runs,
        esc(command)
    );
    for (i, line) in table(report).lines().enumerate().filter(|(i, _)| *i != 1) {
        let cell = if i == 0 { "th" } else { "td" };
        let cells: Vec<String> =
            line.trim_matches('|').split('|').map(|c| format!("<{cell}>{}</{cell}>", esc(c.trim()))).collect();
        let _ = writeln!(s, "<tr>{}</tr>", cells.concat());
    }
    s += "</table>\n<p><i>trace / rebuilt</i>: trace time with the mode's TLAS over the trace time at the same frame \
          with a TLAS rebuilt every frame for fast trace (above 1: the TLAS traces slower).</p>\n\
          <p><img src=\"plots/as-ms.svg\"><img src=\"plots/trace-ms.svg\"></p>\n\
          <p>Every frame: <a href=\"frames.csv\">frames.csv</a>, <a href=\"results.json\">results.json</a>.</p></body></html>\n";
    s
}

fn esc(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
