//! `twinray bench`: for each scene, shader set and sample count, GPU time (median and
//! interquartile range), rays per second, and error against a converged reference (RMSE,
//! PSNR, mean FLIP), with hit mismatches against the first set; then tables, plots and an
//! HTML page in one folder.

pub mod animation;
pub mod html;
pub mod linking;
pub mod metrics;
pub mod pipelines;
pub mod plots;
pub mod samplers;
pub mod stages;
pub mod tables;

pub use samplers::side_of;

use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use twinray_host::error::{Error, Result};
use twinray_host::probe::stability::Skipped;
use twinray_host::reference::image::{reference, ReferenceImage};
pub use twinray_host::render::isolated::{AloneIn, Isolation, TimeAlone};
use twinray_host::render::{render_sets, PlacementTimes, RayCounts, RenderOptions, RenderOutput};
use twinray_host::scene::Scene;
use twinray_host::sets::ShaderSet;
use twinray_host::util::interval::RatioInterval;
use twinray_host::util::output::file_safe;
use twinray_host::util::stats::Spread;
use twinray_host::vk::context::Context;

/// What to measure.
#[derive(Clone, Debug)]
pub struct BenchConfig {
    pub scenes: Vec<Scene>,
    pub sets: Vec<ShaderSet>,
    /// Samples per pixel, each a square up to 256.
    pub spp: Vec<u32>,
    /// Image size override; each scene's own when `None`.
    pub size: Option<(u32, u32)>,
    pub warmup: u32,
    /// Timed traces per placement.
    pub runs: u32,
    /// Placements per measurement (see `render::placement`).
    pub placements: u32,
    /// Whose spacers the first placement makes (`RenderOptions::first_placement`).
    pub first_placement: u32,
    /// Whether a salted copy of the first set is timed too: the null control.
    pub null: bool,
    pub reference_spp: u32,
    pub reference_set: ShaderSet,
    pub cache: PathBuf,
    pub out: PathBuf,
    /// Shadow samples per light for the sampler study of soft-shadow scenes (none: no study).
    pub shadow_spp: Vec<u32>,
    /// Probe cases whose robust and naive intersection variants are timed against their
    /// accuracy (none: no such study), each timed over at least `timing_rays` rays.
    pub probes: Option<PathBuf>,
    pub timing_rays: usize,
    /// Which renders are written as images (with their FLIP maps); references always are.
    pub images: Images,
    /// Each set timed alone in processes of its own, the in-process times replaced; `None`:
    /// every set timed in this process.
    pub isolation: Option<Isolation>,
}

/// Which renders `twinray bench` keeps as PNG files.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Images {
    /// Every scene, set and sample count.
    All,
    /// Only the largest sample count (a committed report stays small).
    Last,
    /// None.
    None,
}

/// One measurement: a scene rendered by one set at one sample count.
#[derive(Clone, Debug, Serialize)]
pub struct BenchRow {
    pub scene: String,
    pub set: String,
    pub spp: u32,
    pub width: u32,
    pub height: u32,
    /// The median and quartiles of every timed trace, all placements pooled: how traces
    /// spread, not the uncertainty of a ratio (see `BenchReport::ratios`).
    pub gpu_ms: Option<Spread>,
    /// Each placement's median and the set's position in its order.
    pub placements: PlacementTimes,
    pub rays: RayCounts,
    pub mrays_per_s: Option<f64>,
    pub rmse: f64,
    pub psnr: f64,
    pub flip: f64,
    /// Pixels whose first primary ray hit another primitive than the first set's did, less
    /// those where either is right (null for the first set).
    pub hit_mismatches: Option<u64>,
    /// Those where either is right, as `compare` sets them apart: on an edge inside a mesh, or
    /// at a cutout's alpha cutoff (`compare::edges`).
    pub hit_mismatches_set_apart: Option<u64>,
    /// Stack bytes the set's ray generation stage needs, as the driver reports it.
    pub raygen_stack_bytes: u64,
    /// The rendered image and its error map, relative to the output folder (none when
    /// `images` left them out).
    pub image: Option<String>,
    pub error_map: Option<String>,
}

/// Everything a bench produced.
#[derive(Clone, Debug, Serialize)]
pub struct BenchReport {
    pub device: String,
    pub cpu_threads: Option<u32>,
    pub runs: u32,
    pub warmup: u32,
    pub placements: u32,
    pub first_placement: u32,
    pub reference_spp: u32,
    pub reference_set: String,
    /// Per scene, the reference image relative to the output folder.
    pub references: Vec<(String, String)>,
    pub rows: Vec<BenchRow>,
    /// Every pair of sets measured together, earlier set over later, with its interval.
    pub ratios: Vec<BenchRatio>,
    /// The shadow-sampler study, with the first set.
    pub samplers: Vec<samplers::SamplerRow>,
    /// The probe cases with robust and naive intersection variants, with the first set.
    pub variants: Vec<twinray_host::probe::stability::StabilityRow>,
    /// Size of every module of both sets, as the binary embeds them.
    pub spirv: Vec<ModuleSize>,
    /// Scenes and probe cases not run: a module they need declares what the device lacks.
    pub skipped: Vec<Skipped>,
}

/// The GPU time of set `a` over set `b` for one scene and sample count, over the placements
/// they were timed in together.
#[derive(Clone, Debug, Serialize)]
pub struct BenchRatio {
    pub scene: String,
    pub spp: u32,
    pub a: String,
    pub b: String,
    pub interval: RatioInterval,
    /// The interval in words: "rust slower by 3.1% (95% CI 1.2% to 5.0%)".
    pub verdict: String,
    /// Whether `b` is a salted copy of `a`: the null control, whose interval should hold 1.
    pub null_control: bool,
}

impl BenchConfig {
    /// The sets each measurement times: the asked-for ones, a repeat made a salted copy, and
    /// with `null` a copy of the first set after them.
    pub fn timed_sets(&self) -> Vec<ShaderSet> {
        let mut sets = self.sets.clone();
        if self.null {
            sets.extend(self.sets.first().cloned());
        }
        ShaderSet::distinct(&sets)
    }
}

/// A module's SPIR-V in each language: bytes and instructions.
#[derive(Clone, Debug, Serialize)]
pub struct ModuleSize {
    pub module: &'static str,
    pub rust_bytes: usize,
    pub glsl_bytes: usize,
    pub rust_instructions: usize,
    pub glsl_instructions: usize,
}

/// The sizes of every module of both sets.
pub fn spirv_sizes() -> Result<Vec<ModuleSize>> {
    use twinray_host::sets::{Language, MODULES};
    let size = |language, spec| -> Result<(usize, usize)> {
        let module = ShaderSet::uniform(language).resolve(spec)?;
        let info = twinray_shared::spirv_info::parse(&module.spirv).map_err(Error::Input)?;
        Ok((module.spirv.len(), info.instruction_count))
    };
    MODULES
        .iter()
        .map(|spec| {
            let (rust, glsl) = (size(Language::Rust, spec)?, size(Language::Glsl, spec)?);
            Ok(ModuleSize {
                module: spec.name,
                rust_bytes: rust.0,
                glsl_bytes: glsl.0,
                rust_instructions: rust.1,
                glsl_instructions: glsl.1,
            })
        })
        .collect()
}

/// Runs the bench, writing images into `config.out/images`; `progress` is told after each step.
pub fn run(ctx: &Arc<Context>, config: &BenchConfig, progress: &dyn Fn(&str)) -> Result<BenchReport> {
    let images = config.out.join("images");
    std::fs::create_dir_all(&images).map_err(|source| Error::Io { what: "creating", path: images.clone(), source })?;
    let mut report = BenchReport {
        device: ctx.info.name.clone(),
        cpu_threads: ctx.info.cpu_threads,
        runs: config.runs,
        warmup: config.warmup,
        placements: config.placements,
        first_placement: config.first_placement,
        reference_spp: config.reference_spp,
        reference_set: config.reference_set.to_string(),
        references: Vec::new(),
        rows: Vec::new(),
        ratios: Vec::new(),
        samplers: Vec::new(),
        variants: Vec::new(),
        spirv: spirv_sizes()?,
        skipped: Vec::new(),
    };
    for (index, scene) in config.scenes.iter().enumerate() {
        // A scene a set's module cannot run on this device is skipped, with what it had added.
        let kept = (report.references.len(), report.rows.len(), report.ratios.len(), report.samplers.len());
        match bench_scene(ctx, config, (index, scene), &mut report, progress) {
            Ok(()) => {}
            Err(e) if e.device_lacks() => {
                report.references.truncate(kept.0);
                report.rows.truncate(kept.1);
                report.ratios.truncate(kept.2);
                report.samplers.truncate(kept.3);
                let skip = Skipped { name: scene.name().to_string(), why: e.to_string() };
                progress(&skip.line());
                report.skipped.push(skip);
            }
            Err(e) => return Err(e),
        }
    }
    if let Some(dir) = &config.probes {
        progress("probe cases: robust and naive intersection variants");
        let files = twinray_host::probe::stability::case_files(dir)?;
        let formulas = [twinray_host::scene::shape::Formula::Robust, twinray_host::scene::shape::Formula::Naive];
        let timing = twinray_host::probe::stability::Timing {
            warmup: config.warmup,
            runs: config.runs,
            rays: config.timing_rays,
        };
        let suite = twinray_host::probe::stability::run(ctx, &files, &config.sets[..1], &formulas, timing, |skip| {
            progress(&skip.line());
        })?;
        report.skipped.extend(suite.skipped);
        let rows = suite.rows;
        // Only cases where the naive formula differs make a comparison.
        let paired = |r: &&twinray_host::probe::stability::StabilityRow| {
            rows.iter().any(|o| o.formula == "naive" && o.report.case == r.report.case)
        };
        report.variants = rows.iter().filter(paired).cloned().collect();
    }
    Ok(report)
}

/// One scene of the bench: its reference, every set at every sample count, the sampler study.
fn bench_scene(
    ctx: &Arc<Context>,
    config: &BenchConfig,
    (index, scene): (usize, &Scene),
    report: &mut BenchReport,
    progress: &dyn Fn(&str),
) -> Result<()> {
    let size = config.size.unwrap_or((scene.file.image.width, scene.file.image.height));
    progress(&format!("{}: reference at {} spp", scene.name(), config.reference_spp));
    let truth = reference(ctx, scene, &config.reference_set, size, config.reference_spp, &config.cache)?;
    let reference_png = format!("images/{}-reference.png", file_safe(scene.name()));
    twinray_host::util::output::write_png(
        &config.out.join(&reference_png),
        size.0,
        size.1,
        &twinray_host::render::to_picture(&truth.linear),
    )?;
    report.references.push((scene.name().to_string(), reference_png));
    let sets = config.timed_sets();
    for &spp in &config.spp {
        progress(&format!("{}: {} sets at {spp} spp", scene.name(), sets.len()));
        let mut outputs = measure(ctx, scene, size, spp, &sets, config)?;
        if let Some(isolation) = &config.isolation {
            progress(&format!("{}: each set alone at {spp} spp, {} processes each", scene.name(), isolation.processes));
            isolation.retime(index, spp, &sets, &mut outputs)?;
        }
        let keep = match config.images {
            Images::All => true,
            Images::Last => config.spp.iter().max() == Some(&spp),
            Images::None => false,
        };
        report.ratios.extend(ratios(scene.name(), spp, &sets, &outputs));
        for (set, out) in sets.iter().zip(&outputs) {
            out.written.require(&set.to_string(), "pixels", &format!("{} at {spp} spp", scene.name()))?;
            let first = outputs.first().filter(|f| !std::ptr::eq(*f, out));
            let row = row(scene, set, spp, out, &truth, first, keep.then_some(config.out.as_path()))?;
            report.rows.push(row);
        }
    }
    if scene.has_soft_shadows() && !config.shadow_spp.is_empty() {
        let study = samplers::Study {
            set: &config.sets[0],
            size,
            counts: &config.shadow_spp,
            reference_spp: config.reference_spp,
            cache: &config.cache,
            warmup: config.warmup,
            runs: config.runs,
        };
        report.samplers.extend(samplers::study(ctx, scene, &study, progress)?);
    }
    Ok(())
}

/// Progress steps `run` reports for `config`.
pub fn steps(config: &BenchConfig) -> usize {
    let soft = config.scenes.iter().filter(|s| s.has_soft_shadows()).count();
    let study = if config.shadow_spp.is_empty() { 0 } else { soft * (1 + 2 * config.shadow_spp.len()) };
    let per_spp = 1 + usize::from(config.isolation.is_some());
    config.scenes.len() * (1 + per_spp * config.spp.len()) + study + usize::from(config.probes.is_some())
}

/// Every set's render of `scene` at `spp`, timed interleaved in every placement.
fn measure(
    ctx: &Arc<Context>,
    scene: &Scene,
    (width, height): (u32, u32),
    spp: u32,
    sets: &[ShaderSet],
    config: &BenchConfig,
) -> Result<Vec<RenderOutput>> {
    let mut scene = scene.clone();
    scene.file.image.samples = side_of(spp)?;
    // Timed alone elsewhere: here only the images (and ray counts) are needed.
    let (warmup, runs, placements) =
        if config.isolation.is_some() { (0, 1, 1) } else { (config.warmup, config.runs, config.placements) };
    let first_placement = config.first_placement;
    render_sets(ctx, &scene, sets, &RenderOptions { width, height, warmup, runs, placements, first_placement })
}

/// Every pair of `sets`, earlier over later, with the interval of their time ratio.
fn ratios(scene: &str, spp: u32, sets: &[ShaderSet], outputs: &[RenderOutput]) -> Vec<BenchRatio> {
    let mut out = Vec::new();
    for (i, (a, a_out)) in sets.iter().zip(outputs).enumerate() {
        for (b, b_out) in sets.iter().zip(outputs).skip(i + 1) {
            if let Some(interval) = a_out.ratio_to(b_out) {
                out.push(BenchRatio {
                    scene: scene.to_string(),
                    spp,
                    a: a.to_string(),
                    b: b.to_string(),
                    verdict: interval.verdict(&a.to_string()),
                    interval,
                    null_control: a.original() == b.original(),
                });
            }
        }
    }
    out
}

fn row(
    scene: &Scene,
    set: &ShaderSet,
    spp: u32,
    out: &RenderOutput,
    truth: &ReferenceImage,
    first: Option<&RenderOutput>,
    images: Option<&Path>,
) -> Result<BenchRow> {
    let errors = metrics::errors(&out.linear, &truth.linear, (out.width, out.height));
    let stem = format!("images/{}-{}-{spp}spp", file_safe(scene.name()), file_safe(&set.to_string()));
    let (mut image, mut error_map) = (None, None);
    if let Some(dir) = images {
        let (png, flip) = (format!("{stem}.png"), format!("{stem}-flip.png"));
        twinray_host::util::output::write_png(&dir.join(&png), out.width, out.height, &out.picture())?;
        twinray_host::util::output::write_png(&dir.join(&flip), out.width, out.height, &errors.flip_map_rgba)?;
        (image, error_map) = (Some(png), Some(flip));
    }
    let diff = first.map(|f| twinray_host::compare::scene_diff(scene, f, out));
    let hit_mismatches = diff.as_ref().map(|d| d.hit_mismatches);
    let hit_mismatches_set_apart = diff.as_ref().map(|d| d.internal_edges + d.alpha_edges);
    Ok(BenchRow {
        scene: scene.name().to_string(),
        set: set.to_string(),
        spp,
        width: out.width,
        height: out.height,
        gpu_ms: out.spread(),
        placements: out.placements.clone(),
        rays: out.rays,
        mrays_per_s: out.mrays_per_s(),
        rmse: errors.rmse,
        psnr: errors.psnr,
        flip: errors.flip,
        hit_mismatches,
        hit_mismatches_set_apart,
        raygen_stack_bytes: out.raygen_stack_bytes,
        image,
        error_map,
    })
}
