//! The cross-check's report: the table (summary.md) and index.html with each scene's
//! twinray and Mitsuba images and their difference side by side.

use super::SceneCheck;
use crate::bench::html::escape;
use std::fmt::Write;

/// The report's table: one row per scene.
pub fn table(checks: &[SceneCheck]) -> String {
    let mut s = String::from(
        "| scene | size | twinray spp | Mitsuba spp | relative RMSE | RMSE | Mitsuba noise | max abs | masked | coverage mismatches |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for c in checks {
        let f = &c.figures;
        s += &format!(
            "| {} | {}x{} | {} | {} | {:.4} | {:.5} | {:.5} | {:.4} | {} | {} |\n",
            c.scene,
            c.width,
            c.height,
            c.twinray_spp,
            c.mitsuba_spp,
            f.relative_rmse,
            f.rmse,
            f.mitsuba_noise,
            f.max_abs_diff,
            f.masked,
            f.coverage_mismatches
        );
    }
    s
}

/// index.html: how it was run, the table, and per scene the images side by side with the
/// notes on what Mitsuba draws differently. Image paths are relative to the report folder.
pub fn html(checks: &[SceneCheck], command: &str) -> String {
    let mut s = String::from(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>twinray crosscheck</title><style>\n\
         body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse;margin:1em 0}\n\
         td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#eee}td.l{text-align:left}\n\
         img{image-rendering:pixelated;width:32%}</style></head><body>\n<h1>twinray against Mitsuba 3</h1>\n",
    );
    let _ = writeln!(
        s,
        "<p>Linear radiance over the pixels that see no emitter (docs/shading-model.md). Relative RMSE is over \
         Mitsuba's mean; Mitsuba's noise is half the RMS difference of its two halves. In the difference image, \
         full red is a tenth of the mean radiance and blue marks pixels that see an emitter.</p>\n\
         <p>Command: <code>{}</code></p>",
        escape(command)
    );
    s += "<table><tr><th>scene</th><th>size</th><th>relative RMSE</th><th>RMSE</th><th>Mitsuba noise</th>\
          <th>max abs</th><th>masked</th><th>coverage mismatches</th></tr>\n";
    for c in checks {
        let f = &c.figures;
        let _ = writeln!(
            s,
            "<tr><td class=\"l\">{}</td><td>{}x{}</td><td>{:.4}</td><td>{:.5}</td><td>{:.5}</td><td>{:.4}</td>\
             <td>{}</td><td>{}</td></tr>",
            escape(&c.scene),
            c.width,
            c.height,
            f.relative_rmse,
            f.rmse,
            f.mitsuba_noise,
            f.max_abs_diff,
            f.masked,
            f.coverage_mismatches
        );
    }
    s += "</table>\n";
    for c in checks {
        let dir = escape(&crate::util::output::file_safe(&c.scene));
        let _ = writeln!(
            s,
            "<h2>{0}</h2><p>twinray ({1} spp), Mitsuba ({2} spp), difference. {3}</p>\
             <img src=\"{dir}/twinray.png\" alt=\"twinray\"><img src=\"{dir}/mitsuba.png\" alt=\"Mitsuba\">\
             <img src=\"{dir}/diff.png\" alt=\"difference\">",
            escape(&c.scene),
            c.twinray_spp,
            c.mitsuba_spp,
            escape(&c.notes.join("; "))
        );
    }
    s += "</body></html>\n";
    s
}
