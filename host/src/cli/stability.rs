//! `twinray stability`: the hard-case suite, every case of a folder per set and formula.

use crate::args::{GlobalArgs, MAX_RUNS, MAX_TIMING_RAYS, MAX_WARMUP};
use crate::session::context;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray::scene::shape::Formula;

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

#[derive(Args)]
pub struct StabilityArgs {
    /// Folder of probe cases.
    #[arg(long, default_value = "probes/stability")]
    pub dir: PathBuf,
    /// Shader sets, comma-separated with ';' between sets, e.g. "rust;glsl".
    #[arg(long, default_value = "rust;glsl")]
    pub sets: String,
    /// Timed passes per case, set and formula.
    #[arg(long, default_value_t = 5, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_RUNS)))]
    pub runs: u32,
    /// Untimed passes before the timed ones.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_WARMUP)))]
    pub warmup: u32,
    /// Time each case over its rays repeated up to at least this many (0: the case's rays).
    #[arg(long, default_value_t = 262_144, value_parser = clap::value_parser!(u64).range(0..=MAX_TIMING_RAYS))]
    pub timing_rays: u64,
    /// Print one JSON array of rows.
    #[arg(long)]
    pub json: bool,
}
