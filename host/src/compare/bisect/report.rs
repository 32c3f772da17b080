//! The text `twinray bisect` prints.

use super::{BisectReport, Finding, Gap, Row};
use crate::util::interval::RatioInterval;

fn gap(g: &Gap) -> String {
    format!("rmse {:.3e}, {} over threshold, {} hit mismatches", g.rmse, g.over, g.mismatches)
}

fn pct(share: Option<[f64; 2]>) -> String {
    share.map_or("-".into(), |[f, r]| format!("{:.0}% / {:.0}%", 100.0 * f, 100.0 * r))
}

fn ratio(r: Option<RatioInterval>) -> String {
    r.map_or("-".into(), |r| format!("{:.3}", r.ratio))
}

fn table(title: &str, rows: &[Row]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "\n  {title:<34} {:>15} {:>15} {:>9} {:>9} {:>15}  explains\n",
        "rmse share", "hit share", "A+/A", "B+/B", "time share"
    );
    for r in rows {
        let mut explains = Vec::new();
        if r.explains_image {
            explains.push("image");
        }
        if r.explains_time {
            explains.push("time");
        }
        s += &format!(
            "  {:<34} {:>15} {:>15} {:>9} {:>9} {:>15}  {}\n",
            r.unit,
            pct(r.rmse_share),
            pct(r.mismatch_share),
            ratio(r.ratio_forward),
            ratio(r.ratio_reverse),
            pct(r.time_share),
            if explains.is_empty() { "-".into() } else { explains.join(", ") }
        );
    }
    s
}

fn finding(what: &str, f: &Finding) -> String {
    match (f.difference.as_str(), f.explained_by.as_slice()) {
        ("present" | "significant", []) => format!("  {what}: NOT PINNED: no stage or pair of stages explains it\n"),
        ("present" | "significant", names) => format!("  {what}: explained by {}\n", names.join(", ")),
        (why, []) => format!("  {what}: no difference to pin ({why})\n"),
        (why, names) => format!("  {what}: no difference to pin ({why}); carried by {}\n", names.join(", ")),
    }
}

impl BisectReport {
    /// The table `twinray bisect` prints: A against B, then each swap's shares (A to B / B to
    /// A), and what explains each difference.
    pub fn summary(&self) -> String {
        let ms = |m: Option<f64>| m.map_or("n/a".into(), |m| format!("{m:.3} ms"));
        let over = match (self.ratio.map_or(0, |r| r.placements), self.processes) {
            (n, 0) => format!("{n} placements"),
            (n, _) => format!("{n} rounds, each set alone in {} of its own", self.alone_in.one()),
        };
        let mut s = format!(
            "bisect {} on {}\n  A = {}\n  B = {}\n  A against B: {}\n  GPU A {}, B {}; B/A {} over {over}: {}; raygen stack {} / {} bytes\n",
            self.subject,
            self.device,
            self.set_a,
            self.set_b,
            gap(&self.whole),
            ms(self.gpu_ms_a),
            ms(self.gpu_ms_b),
            ratio(self.ratio),
            self.time_verdict,
            self.raygen_stack_bytes_a,
            self.raygen_stack_bytes_b,
        );
        for failure in &self.failures {
            s += &format!("  FAIL: {failure}\n");
        }
        if !self.same_modules.is_empty() {
            s += &format!("  same code in both: {}\n", self.same_modules.join(", "));
        }
        s += "  shares: A with the unit from B (A+) moved toward B / B with it from A (B+) moved toward A\n";
        s += &table("stage", &self.stages);
        s += &table("pair of stages", &self.pairs);
        s += &table("module", &self.modules);
        s += "\n";
        s += &finding("image", &self.image);
        s += &finding("time", &self.time);
        s += if self.pinned { "  PINNED\n" } else { "  NOT PINNED\n" };
        s
    }
}
