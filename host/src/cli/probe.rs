//! `twinray probe` and `twinray stability`.

use crate::args::{GlobalArgs, ProbeArgs, StabilityArgs};
use crate::session::context;
use anyhow::Result;
use std::process::ExitCode;
use twinray::scene::shape::Formula;

pub fn probe(global: &GlobalArgs, args: ProbeArgs) -> Result<ExitCode> {
    let mut case = twinray::probe::case::ProbeCase::load(&args.case)?;
    if let Some(formula) = args.formula.as_deref() {
        let formula = if formula == "naive" { Formula::Naive } else { Formula::Robust };
        case.set_formula(formula);
    }
    if let Some(path) = &args.rays_out {
        twinray::util::output::check_file_target(path).map_err(|e| twinray::Error::Input(format!("--rays-out {e}")))?;
    }
    let ctx = context(global)?;
    let out = twinray::probe::probe(&ctx, &case.scene, &args.shaders, &case.rays, args.warmup, args.runs)?;
    let median = twinray::util::stats::median(&out.gpu_ms);
    let label = match args.formula.as_deref() {
        Some(formula) => format!("{} ({formula})", args.shaders),
        None => args.shaders.to_string(),
    };
    let report = twinray::probe::report::evaluate(&case, out.records(), &label, &ctx.info.name, median);
    if let Some(path) = &args.rays_out {
        let mut csv = Vec::new();
        twinray::probe::report::write_rays_csv(&mut csv, &case, &[(&label, &out.results)])?;
        twinray::util::output::write_atomically(path, &csv)?;
    }
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print!("{}", report.summary());
    }
    Ok(if report.pass { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

pub fn stability(global: &GlobalArgs, args: StabilityArgs) -> Result<ExitCode> {
    let files = twinray::probe::stability::case_files(&args.dir)?;
    let sets = args.sets.split(';').map(str::parse).collect::<Result<Vec<twinray::ShaderSet>, _>>()?;
    let ctx = context(global)?;
    let formulas = [Formula::Robust, Formula::Naive];
    let timing =
        twinray::probe::stability::Timing { warmup: args.warmup, runs: args.runs, rays: args.timing_rays as usize };
    // Each skip is said as it happens, on stderr, so JSON on stdout stays the rows.
    let skip = |s: &twinray::probe::stability::Skipped| eprintln!("{}", s.line());
    let suite = twinray::probe::stability::run(&ctx, &files, &sets, &formulas, timing, skip)?;
    let rows = &suite.rows;
    if args.json {
        println!("{}", serde_json::to_string(rows)?);
    } else {
        print!("{}", twinray::probe::stability::table(rows));
    }
    if !suite.skipped.is_empty() {
        let names: Vec<&str> = suite.skipped.iter().map(|s| s.name.as_str()).collect();
        let line = format!(
            "skipped {} of {} cases, which need what {} lacks: {}",
            names.len(),
            files.len(),
            ctx.info.name,
            names.join(", ")
        );
        if args.json {
            eprintln!("{line}")
        } else {
            println!("{line}")
        }
    }
    let missed = rows.iter().filter(|r| !r.failures.is_empty()).count();
    Ok(if missed == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}
