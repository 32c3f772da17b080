//! The bench's plots, each as PNG and SVG: error against samples per pixel (log-log, with
//! N^-0.5 and N^-0.75 guide lines), error against GPU time, the Rust/GLSL time ratio per
//! scene, and each set's time at each of its places (a strip plot). PNG text uses an embedded font, so no system font library is needed.

use super::samplers::SamplerRow;
use super::tables::SceneRatio;
use super::{BenchReport, BenchRow};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use twinray_host::error::{Error, Result};

const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSansMono.ttf");
const SIZE: (u32, u32) = (900, 600);

/// One plotted line: its label and points.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// Error against samples per pixel, one series per scene and set.
pub fn error_by_spp(report: &BenchReport) -> Vec<Series> {
    series(&report.rows, set_label, |r| Some((f64::from(r.spp), r.rmse)))
}

/// Error against median GPU time, one series per scene and set.
pub fn error_by_time(report: &BenchReport) -> Vec<Series> {
    series(&report.rows, set_label, |r| r.gpu_ms.map(|s| (s.median, r.rmse)))
}

/// Error against shadow samples per light, one series per scene and sampler.
pub fn sampler_by_count(report: &BenchReport) -> Vec<Series> {
    series(&report.samplers, sampler_label, |r| Some((f64::from(r.shadow_spp), r.rmse)))
}

/// Error against median GPU time, one series per scene and sampler: the comparison at equal time.
pub fn sampler_by_time(report: &BenchReport) -> Vec<Series> {
    series(&report.samplers, sampler_label, |r| r.gpu_ms.map(|s| (s.median, r.rmse)))
}

fn set_label(r: &BenchRow) -> String {
    format!("{} {}", r.scene, r.set)
}

fn sampler_label(r: &SamplerRow) -> String {
    format!("{} {}", r.scene, r.sampler)
}

fn series<T>(items: &[T], label: impl Fn(&T) -> String, point: impl Fn(&T) -> Option<(f64, f64)>) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for r in items {
        let Some(p) = point(r).filter(|p| p.0 > 0.0 && p.1 > 0.0) else { continue };
        let label = label(r);
        match out.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push(p),
            None => out.push(Series { label, points: vec![p] }),
        }
    }
    out
}

/// Smallest p99 error plotted: a case whose hits all match the reference exactly sits here.
pub const ERROR_FLOOR: f64 = 1e-9;

/// GPU time per million rays against p99 relative t error of each probe case, robust and
/// naive, as two series.
pub fn variant_points(report: &BenchReport) -> Vec<Series> {
    ["robust", "naive"]
        .iter()
        .map(|&formula| Series {
            label: formula.to_string(),
            points: report
                .variants
                .iter()
                .filter(|r| r.formula == formula)
                .filter_map(|r| {
                    Some((r.report.gpu_ms_per_million_rays?, r.report.relative_t_error.p99.max(ERROR_FLOOR)))
                })
                .collect(),
        })
        .collect()
}

/// Least-squares slope of log y against log x: the measured convergence rate.
pub fn log_slope(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (mx, my) = (logs.iter().map(|p| p.0).sum::<f64>() / n, logs.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    (logs.len() >= 2 && sxx > 0.0).then(|| logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>() / sxx)
}

/// Writes error-spp, error-time and ratio plots (PNG and SVG) into `dir`.
pub fn write(report: &BenchReport, ratios: &[SceneRatio], dir: &Path) -> Result<()> {
    // Registering twice is harmless; it fails only on a bad font, which is a build error.
    let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    std::fs::create_dir_all(dir).map_err(|source| Error::Io { what: "creating", path: dir.into(), source })?;
    let by_spp = error_by_spp(report);
    let by_time = error_by_time(report);
    let error_plot = |name: &str, x_label: &str, data: &[Series], guides: bool| -> Result<()> {
        let png = dir.join(format!("{name}.png"));
        let svg = dir.join(format!("{name}.svg"));
        draw_png(&png, |area| draw_error(area, x_label, data, guides))?;
        draw_error(SVGBackend::new(&svg, SIZE).into_drawing_area(), x_label, data, guides).map_err(plot_error)
    };
    error_plot("error-spp", "samples per pixel", &by_spp, true)?;
    error_plot("error-time", "GPU ms (median)", &by_time, false)?;
    if !report.variants.is_empty() {
        let points = variant_points(report);
        let (png, svg) = (dir.join("variants.png"), dir.join("variants.svg"));
        draw_png(&png, |area| draw_scatter(area, &points))?;
        draw_scatter(SVGBackend::new(&svg, SIZE).into_drawing_area(), &points).map_err(plot_error)?;
    }
    if !report.samplers.is_empty() {
        error_plot("sampler-spp", "shadow samples per light", &sampler_by_count(report), true)?;
        error_plot("sampler-time", "GPU ms (median)", &sampler_by_time(report), false)?;
    }
    let (png, svg) = (dir.join("places.png"), dir.join("places.svg"));
    let cells =
        report.rows.iter().map(|r| (format!("{} {}", r.scene, r.spp), r.set.as_str(), &r.placements.median_ms[..]));
    let strips = place_strips(cells);
    draw_png(&png, |area| draw_places(area, &strips))?;
    draw_places(SVGBackend::new(&svg, SIZE).into_drawing_area(), &strips).map_err(plot_error)?;
    let (png, svg) = (dir.join("ratio.png"), dir.join("ratio.svg"));
    draw_png(&png, |area| draw_ratios(area, ratios))?;
    draw_ratios(SVGBackend::new(&svg, SIZE).into_drawing_area(), ratios).map_err(plot_error)
}

/// One strip of the places plot: a scene and sample count, and each set's time at each of its
/// places (or processes) over the first set's geometric mean there.
pub struct Strip {
    pub cell: String,
    pub sets: Vec<(String, Vec<f64>)>,
}

/// The strips of `rows` (each a cell, "scene spp", a set and its place times), one per cell,
/// in the order measured.
pub fn place_strips<'a>(rows: impl IntoIterator<Item = (String, &'a str, &'a [f64])>) -> Vec<Strip> {
    let mut strips: Vec<Strip> = Vec::new();
    for (cell, set, ms) in rows {
        if strips.last().is_none_or(|s| s.cell != cell) {
            strips.push(Strip { cell, sets: Vec::new() });
        }
        if let Some(strip) = strips.last_mut() {
            strip.sets.push((set.to_string(), ms.to_vec()));
        }
    }
    for strip in &mut strips {
        let logs: Vec<f64> = strip.sets.first().map_or(Vec::new(), |s| s.1.iter().map(|m| m.ln()).collect());
        let mean = (logs.iter().sum::<f64>() / logs.len().max(1) as f64).exp();
        for (_, ms) in &mut strip.sets {
            ms.iter_mut().for_each(|m| *m /= mean);
        }
    }
    strips
}

fn draw_places<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, strips: &[Strip]) -> Drawn
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let all = strips.iter().flat_map(|s| s.sets.iter().flat_map(|(_, ms)| ms.iter().copied()));
    let (lo, hi) = all.filter(|v| v.is_finite()).fold((0.99f64, 1.01f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let n = strips.len().max(1) as f64;
    let pad = 0.1 * (hi - lo);
    let mut chart = framed(&root).build_cartesian_2d(-0.5..n - 0.5, lo - pad..hi + pad)?;
    let names: Vec<String> = strips.iter().map(|s| s.cell.clone()).collect();
    chart
        .configure_mesh()
        .x_labels(strips.len().max(1))
        .x_label_formatter(&|x| names.get(x.round() as usize).cloned().unwrap_or_default())
        .light_line_style(WHITE)
        .x_desc("scene and samples per pixel")
        .y_desc("GPU time at each place over the first set's mean")
        .draw()?;
    let labels: Vec<&str> =
        strips.iter().flat_map(|s| s.sets.iter().map(|(set, _)| set.as_str())).fold(Vec::new(), |mut v, set| {
            if !v.contains(&set) {
                v.push(set);
            }
            v
        });
    for (i, &label) in labels.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        // Each set in a band of its own within the strip, its places spread across the band.
        let band = 0.8 / labels.len() as f64;
        let x0 = -0.4 + band * i as f64;
        let points = strips.iter().enumerate().flat_map(|(k, strip)| {
            let ms = strip.sets.iter().find(|(set, _)| set == label).map_or(&[][..], |(_, ms)| &ms[..]);
            let step = band / (ms.len() + 1) as f64;
            ms.iter()
                .enumerate()
                .map(move |(j, &m)| Circle::new((k as f64 + x0 + step * (j + 1) as f64, m), 2, colour.filled()))
        });
        chart
            .draw_series(points)?
            .label(label.to_string())
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    root.present()?;
    Ok(())
}

/// A line plot of `data` as `{name}.png` and `{name}.svg` in `dir`: linear x, log y.
pub fn write_lines(dir: &Path, name: &str, (x_label, y_label): (&str, &str), data: &[Series]) -> Result<()> {
    let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    let (png, svg) = (dir.join(format!("{name}.png")), dir.join(format!("{name}.svg")));
    draw_png(&png, |area| draw_lines(area, x_label, y_label, data))?;
    draw_lines(SVGBackend::new(&svg, SIZE).into_drawing_area(), x_label, y_label, data).map_err(plot_error)
}

fn draw_lines<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, x_label: &str, y_label: &str, data: &[Series]) -> Drawn
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let ((_, _), (y0, y1)) = bounds(data);
    let x1 = data.iter().flat_map(|s| s.points.iter().map(|p| p.0)).fold(1.0, f64::max);
    let mut chart = framed(&root).build_cartesian_2d(0.0..x1, (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .light_line_style(WHITE)
        .y_label_formatter(&|v| tick(*v))
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()?;
    for (i, s) in data.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(s.points.clone(), colour.stroke_width(2)))?
            .label(s.label.clone())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Draws a plot into a buffer and writes it as PNG with the host's own encoder (sRGB-tagged,
/// atomic): plotters' encoder would build a second `image` crate, an older one, in every build.
fn draw_png(path: &Path, draw: impl FnOnce(DrawingArea<BitMapBackend<'_>, Shift>) -> Drawn) -> Result<()> {
    let mut rgb = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    draw(BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area()).map_err(plot_error)?;
    let rgba: Vec<u8> = rgb.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect();
    twinray_host::util::output::write_png(path, SIZE.0, SIZE.1, &rgba)
}

fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Input(format!("drawing a plot: {e}"))
}

type Drawn = std::result::Result<(), Box<dyn std::error::Error>>;

fn bounds(data: &[Series]) -> ((f64, f64), (f64, f64)) {
    let all = data.iter().flat_map(|s| s.points.iter());
    let (mut x, mut y) = ((f64::MAX, f64::MIN), (f64::MAX, f64::MIN));
    for &(px, py) in all {
        x = (x.0.min(px), x.1.max(px));
        y = (y.0.min(py), y.1.max(py));
    }
    if x.0 > x.1 {
        return ((1.0, 10.0), (1e-3, 1.0));
    }
    ((x.0 / 1.5, x.1 * 1.5), (y.0 / 2.0, y.1 * 2.0))
}

/// The margins and label areas every plot uses.
fn framed<'a, 'b, DB: DrawingBackend>(root: &'a DrawingArea<DB, Shift>) -> ChartBuilder<'a, 'b, DB> {
    let mut builder = ChartBuilder::on(root);
    builder.margin(20).x_label_area_size(45).y_label_area_size(70);
    builder
}

fn draw_error<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, x_label: &str, data: &[Series], guides: bool) -> Drawn
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let ((x0, x1), (y0, y1)) = bounds(data);
    let mut chart = framed(&root).build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .light_line_style(WHITE)
        .x_labels(8)
        .y_labels(8)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .x_desc(x_label)
        .y_desc("RMSE against the reference")
        .draw()?;
    for (i, s) in data.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(s.points.clone(), colour.stroke_width(2)).point_size(3))?
            .label(s.label.clone())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour.stroke_width(2)));
    }
    if guides {
        // Guide lines through the first series' first point: N^-0.5 (independent samples)
        // and N^-0.75 (stratified samples near edges, Mitchell 1996).
        if let Some(&(gx, gy)) = data.first().and_then(|s| s.points.first()) {
            for (slope, label) in [(-0.5, "N^-0.5"), (-0.75, "N^-0.75")] {
                let line = [(x0, gy * (x0 / gx).powf(slope)), (x1, gy * (x1 / gx).powf(slope))];
                let style = BLACK.mix(0.4).stroke_width(1);
                chart
                    .draw_series(LineSeries::new(line, style))?
                    .label(label)
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], style));
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

fn draw_scatter<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, data: &[Series]) -> Drawn
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let ((x0, x1), (y0, y1)) = bounds(data);
    let mut chart = framed(&root).build_cartesian_2d(x0..x1, (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .light_line_style(WHITE)
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_desc("GPU ms per million rays (probe cases)")
        .y_desc("p99 relative t error")
        .draw()?;
    for (i, s) in data.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        chart
            .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, colour.filled())))?
            .label(s.label.clone())
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    root.present()?;
    Ok(())
}

/// A log-axis tick: whole numbers plainly, small ones with three significant digits.
fn tick(v: f64) -> String {
    if v >= 10.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.3}").trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

fn draw_ratios<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, ratios: &[SceneRatio]) -> Drawn
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let scenes: Vec<&str> = ratios.iter().fold(Vec::new(), |mut v, r| {
        if !v.contains(&r.0.as_str()) {
            v.push(r.0.as_str());
        }
        v
    });
    let (lo, hi) =
        ratios.iter().fold((0.9f64, 1.1f64), |(lo, hi), r| (lo.min(r.2.low - 0.02), hi.max(r.2.high + 0.02)));
    let n = scenes.len().max(1) as f64;
    let mut chart = ChartBuilder::on(&root)
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(60)
        .build_cartesian_2d(-0.5..n - 0.5, lo..hi)?;
    let names = scenes.clone();
    chart
        .configure_mesh()
        .x_labels(scenes.len().max(1))
        .x_label_formatter(&|x| names.get(x.round() as usize).map_or(String::new(), |s| s.to_string()))
        .light_line_style(WHITE)
        .y_desc("Rust / GLSL GPU time with its 95% interval over placements; lines at 1.00 and 1.05")
        .draw()?;
    for (level, colour) in [(1.0, BLACK.mix(0.5)), (1.05, RED.mix(0.5))] {
        chart.draw_series(LineSeries::new([(-0.5, level), (n - 0.5, level)], colour.stroke_width(1)))?;
    }
    let mut counts: Vec<u32> = ratios.iter().map(|r| r.1).collect();
    counts.sort_unstable();
    counts.dedup();
    for (i, &spp) in counts.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        // Each sample count a little to the side, so that the intervals do not overlap.
        let dx = 0.12 * (i as f64 - (counts.len() as f64 - 1.0) / 2.0);
        let at = |scene: &String| scenes.iter().position(|s| s == scene).map(|x| x as f64 + dx);
        let bars = ratios.iter().filter(|r| r.1 == spp).filter_map(|(scene, _, r)| {
            Some(PathElement::new([(at(scene)?, r.low), (at(scene)?, r.high)], colour.stroke_width(2)))
        });
        chart.draw_series(bars)?;
        let points = ratios
            .iter()
            .filter(|r| r.1 == spp)
            .filter_map(|(scene, _, r)| Some(Circle::new((at(scene)?, r.ratio), 5, colour.filled())));
        chart
            .draw_series(points)?
            .label(format!("{spp} spp"))
            .legend(move |(x, y)| Circle::new((x + 8, y), 5, colour.filled()));
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_strip_per_cell_each_set_over_the_first_sets_mean() {
        let rows: [(String, &str, &[f64]); 3] =
            [("a 1".into(), "glsl", &[1.0, 4.0]), ("a 1".into(), "rust", &[2.0, 2.0]), ("b 1".into(), "glsl", &[3.0])];
        let strips = super::place_strips(rows);
        assert_eq!(strips.iter().map(|s| s.cell.as_str()).collect::<Vec<_>>(), ["a 1", "b 1"]);
        let near = |a: &[f64], b: &[f64]| a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
        assert!(near(&strips[0].sets[0].1, &[0.5, 2.0]), "over the geometric mean 2: {:?}", strips[0].sets);
        assert!(near(&strips[0].sets[1].1, &[1.0, 1.0]), "{:?}", strips[0].sets);
        assert!(near(&strips[1].sets[0].1, &[1.0]), "{:?}", strips[1].sets);
    }

    #[test]
    fn slopes_of_power_laws() {
        let points: Vec<(f64, f64)> = [1.0, 4.0, 16.0, 64.0].iter().map(|&n: &f64| (n, 0.3 * n.powf(-0.75))).collect();
        assert!((super::log_slope(&points).unwrap() + 0.75).abs() < 1e-12);
        assert_eq!(super::log_slope(&points[..1]), None);
    }
}
