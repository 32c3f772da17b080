//! `twinray probe`: a probe case's rays traced with one set, judged against the f64 reference.

use crate::args::{GlobalArgs, MAX_RUNS, MAX_WARMUP};
use crate::session::context;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::scene::shape::Formula;
use twinray_host::sets::SetSpec;

pub fn probe(global: &GlobalArgs, args: ProbeArgs) -> Result<ExitCode> {
    if let Some(path) = &args.rays_out {
        twinray_host::util::output::check_file_target(path)
            .map_err(|e| twinray_host::Error::Input(format!("--rays-out {e}")))?;
    }
    // The set first: a case's scene may name the kinds of the crate it was built from.
    let shaders = global.load("--shaders", &args.shaders)?;
    let own = twinray_host::ShaderSet::own_kinds(&[&shaders]);
    let mut case = twinray_host::probe::builtin::open(&args.case, &own)?;
    if let Some(formula) = args.formula.as_deref() {
        let formula = if formula == "naive" { Formula::Naive } else { Formula::Robust };
        case.set_formula(formula);
    }
    let ctx = context(global)?;
    let out = twinray_host::probe::probe(&ctx, &case.scene, &shaders, &case.rays, args.warmup, args.runs)?;
    let median = twinray_host::util::stats::median(&out.gpu_ms);
    let label = match args.formula.as_deref() {
        Some(formula) => format!("{} ({formula})", shaders),
        None => shaders.to_string(),
    };
    let report = twinray_host::probe::report::evaluate(&case, out.records(), &label, &ctx.info.name, median);
    if let Some(path) = &args.rays_out {
        let mut csv = Vec::new();
        twinray_host::probe::report::write_rays_csv(&mut csv, &case, &[(&label, &out.results)])?;
        twinray_host::util::output::write_atomically(path, &csv)?;
    }
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print!("{}", report.summary());
    }
    Ok(if report.pass { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

#[derive(Args)]
pub struct ProbeArgs {
    /// Probe case file (TOML; see docs/probe-format.md), or a built-in case by its name
    /// (`far-sphere`, `probes/far-sphere.toml`, `stability/sphere-far-1e5`).
    pub case: PathBuf,
    /// Shader set: rust, glsl, or a mix such as rust,intersection=glsl.
    #[arg(long, default_value = "rust")]
    pub shaders: SetSpec,
    /// Intersection formula for every shape that has both: robust, or naive (the textbook
    /// forms kept on purpose) [default: as the scene says].
    #[arg(long, value_parser = ["robust", "naive"])]
    pub formula: Option<String>,
    /// Timed passes over all the rays; the median is reported.
    #[arg(long, default_value_t = 10, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_RUNS)))]
    pub runs: u32,
    /// Untimed passes before the timed ones.
    #[arg(long, default_value_t = 2, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_WARMUP)))]
    pub warmup: u32,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Write one CSV row per ray to FILE: origin, direction, t range, the reference's hit, t,
    /// object and ambiguity, the set's hit, t, object and normal, and the verdict.
    #[arg(long, value_name = "FILE")]
    pub rays_out: Option<PathBuf>,
}
