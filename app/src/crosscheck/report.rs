//! The cross-check's report: the table (summary.md) and index.html with each scene's
//! twinray and Mitsuba images and their difference side by side.

use super::SceneCheck;
use crate::bench::html::escape;
use std::fmt::Write;

/// The columns of the report's table.
const HEADERS: [&str; 10] = [
    "scene",
    "size",
    "twinray spp",
    "Mitsuba spp",
    "relative RMSE",
    "RMSE",
    "Mitsuba noise",
    "max abs",
    "masked",
    "coverage mismatches",
];

/// One scene's row of the table.
fn cells(c: &SceneCheck) -> [String; 10] {
    let f = &c.figures;
    [
        c.scene.clone(),
        format!("{}x{}", c.width, c.height),
        c.twinray_spp.to_string(),
        c.mitsuba_spp.to_string(),
        format!("{:.4}", f.relative_rmse),
        format!("{:.5}", f.rmse),
        format!("{:.5}", f.mitsuba_noise),
        format!("{:.4}", f.max_abs_diff),
        f.masked.to_string(),
        f.coverage_mismatches.to_string(),
    ]
}

/// The report's table in Markdown: one row per scene.
pub fn table(checks: &[SceneCheck]) -> String {
    let mut s = format!("| {} |\n|---|---|{}\n", HEADERS.join(" | "), "---:|".repeat(HEADERS.len() - 2));
    for c in checks {
        s += &format!("| {} |\n", cells(c).join(" | "));
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
    let row = |tag: &str, cells: &[String]| {
        let cells: String = cells.iter().map(|c| format!("<{tag}>{}</{tag}>", escape(c))).collect();
        format!("<tr>{cells}</tr>\n")
    };
    s += "<table>";
    s += &row("th", &HEADERS.map(String::from));
    for c in checks {
        s += &row("td", &cells(c));
    }
    s += "</table>\n";
    for c in checks {
        let dir = escape(&twinray_host::util::output::file_safe(&c.scene));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crosscheck::compare::Figures;

    fn check(scene: &str) -> SceneCheck {
        let figures = Figures {
            pixels: 12,
            masked: 1,
            rmse: 0.001,
            mean: 0.5,
            relative_rmse: 0.002,
            max_abs_diff: 0.01,
            mitsuba_noise: 0.0005,
            coverage_mismatches: 0,
            mean_coverage_diff: 0.0,
        };
        SceneCheck {
            scene: scene.into(),
            width: 4,
            height: 3,
            twinray_spp: 16,
            mitsuba_spp: 32,
            figures,
            notes: vec!["cone shapes are drawn in Mitsuba as fine meshes".into()],
        }
    }

    /// One Markdown row per scene under the header, and in the HTML each scene's three
    /// images and notes, with names escaped.
    #[test]
    fn table_and_page_show_every_scene() {
        let checks = [check("a"), check("b<c")];
        let table = table(&checks);
        assert_eq!(table.lines().count(), 4, "{table}");
        assert!(table.lines().nth(2).unwrap().starts_with("| a | 4x3 | 16 | 32 | 0.0020 |"), "{table}");
        let page = html(&checks, "twinray crosscheck a");
        for image in ["a/twinray.png", "a/mitsuba.png", "a/diff.png"] {
            assert!(page.contains(image), "{image}");
        }
        assert!(page.contains("b&lt;c") && !page.contains("b<c"));
        assert!(page.contains("fine meshes"));
    }
}
