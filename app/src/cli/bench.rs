//! `twinray bench`: speed against error, per scene, set and samples per pixel.

use crate::args::{BenchArgs, GlobalArgs};
use crate::session::context;
use anyhow::Result;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use twinray_host::scene::check_size;
use twinray_host::{Error, Scene};

pub fn bench(global: &GlobalArgs, args: BenchArgs) -> Result<ExitCode> {
    use twinray::bench;
    let names = if args.scenes.is_empty() {
        twinray_host::scene::BUILTIN.iter().map(|(name, _)| name.to_string()).collect()
    } else {
        args.scenes.clone()
    };
    let (spp, shadow_spp) = (sample_counts("--spp", &args.spp)?, sample_counts("--shadow-spp", &args.shadow_spp)?);
    if spp.is_empty() {
        return Err(Error::Input("--spp needs at least one sample count".into()).into());
    }
    twinray_host::reference::image::frames(args.reference_spp)?;
    if args.runs < 10 {
        return Err(Error::Input(format!("--runs must be at least 10 (got {})", args.runs)).into());
    }
    if let (Some(w), Some(h)) = (args.width, args.height) {
        check_size(w, h).map_err(Error::Input)?;
    }
    let sets = global.load_all("--sets", &twinray_host::sets::parse_specs(&args.sets)?)?;
    // The pair's other set by default: the error of a crate against its own twin, not against
    // a built-in set that may not even know the scene's kinds.
    let reference_set = match &args.reference_set {
        Some(spec) => global.load("--reference-set", spec)?,
        None => sets.get(1).or(sets.first()).cloned().ok_or_else(|| Error::Input("--sets names no set".into()))?,
    };
    // The sets first: a scene may name the kinds of the crates they were built from.
    let own = twinray_host::ShaderSet::own_kinds(&sets.iter().chain([&reference_set]).collect::<Vec<_>>());
    let scenes = names.iter().map(|n| Scene::load_with(Some(n), &own)).collect::<Result<Vec<_>, _>>()?;
    let probes = probes(args.probes.as_deref())?;
    let cache = args.cache.clone().unwrap_or_else(twinray_host::reference::image::default_cache);
    let isolation = (args.processes > 0).then(|| bench::Isolation {
        processes: args.processes,
        placements: args.placements,
        first: args.first_placement,
        alone_in: args.alone.alone_in,
        time_alone: crate::timed_alone::time_alone(
            global,
            crate::timed_alone::ChildSettings::of_bench(&args, &reference_set, cache.clone()),
            names.clone(),
            args.alone.alone_in,
        ),
    });
    let config = bench::BenchConfig {
        scenes,
        sets,
        spp,
        size: args.width.zip(args.height),
        warmup: args.warmup,
        runs: args.runs,
        placements: args.placements,
        first_placement: args.first_placement,
        null: args.null,
        reference_spp: args.reference_spp,
        reference_set,
        cache,
        out: args.out.clone(),
        shadow_spp,
        probes,
        timing_rays: args.timing_rays as usize,
        images: args.images,
        isolation,
    };
    let ctx = context(global)?;
    let bar = indicatif::ProgressBar::new(bench::steps(&config) as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} {elapsed_precise} {msg}")
            .map_err(|e| Error::Input(e.to_string()))?,
    );
    let report = bench::run(&ctx, &config, &|step: &str| {
        bar.set_message(step.to_string());
        bar.inc(1);
    })?;
    bar.finish_and_clear();
    let ratios = bench::tables::ratios(&report);
    bench::tables::write(&report, &args.out)?;
    bench::plots::write(&report, &ratios, &args.out.join("plots"))?;
    let command: Vec<String> = std::env::args().collect();
    bench::html::write(&report, &ratios, &command.join(" "), &args.out)?;
    for r in &report.ratios {
        let what = if r.null_control { "null control" } else { "" };
        println!("{:<12} {:>4} spp  {} / {}: {:.3}  {} {what}", r.scene, r.spp, r.a, r.b, r.interval.ratio, r.verdict);
    }
    for row in &report.rows {
        print!("{}", row.placements.retimed_lines("", &format!("{:<12} {:>4} spp  {}", row.scene, row.spp, row.set)));
    }
    for skip in &report.skipped {
        println!("{}", skip.line());
    }
    if !report.skipped.is_empty() {
        println!("skipped {} scenes or probe cases, which need what {} lacks", report.skipped.len(), ctx.info.name);
    }
    println!("wrote {}/index.html, results.json, results.csv, plots/ and images/", args.out.display());
    Ok(ExitCode::SUCCESS)
}

/// A comma-separated list of squares up to 256 ("" or "none": empty).
fn sample_counts(flag: &str, text: &str) -> Result<Vec<u32>, Error> {
    if text.trim().is_empty() || text.trim() == "none" {
        return Ok(Vec::new());
    }
    let parse = |v: &str| v.trim().parse::<u32>().map_err(|_| Error::Input(format!("{flag}: {v:?} is not a number")));
    let counts = text.split(',').map(parse).collect::<Result<Vec<_>, _>>()?;
    for &n in &counts {
        twinray::bench::side_of(n).map_err(|e| Error::Input(format!("{flag}: {e}")))?;
    }
    Ok(counts)
}

/// The probe cases of the robust-against-naive study: the folder given, none for `none`, and
/// by default the checkout's `probes/stability` where the bench runs in one (an installed
/// binary elsewhere skips the study, and says so).
fn probes(given: Option<&Path>) -> Result<Option<PathBuf>> {
    match given {
        Some(dir) if dir.as_os_str() == "none" => Ok(None),
        Some(dir) if dir.is_dir() => Ok(Some(dir.to_path_buf())),
        Some(dir) => {
            let message = format!("--probes {}: no such folder (give --probes DIR, or none)", dir.display());
            Err(Error::Input(message).into())
        }
        None if Path::new(DEFAULT_PROBES).is_dir() => Ok(Some(PathBuf::from(DEFAULT_PROBES))),
        None => {
            eprintln!("bench: no {DEFAULT_PROBES} here, so no probe study (give --probes DIR to run one)");
            Ok(None)
        }
    }
}

/// The hard cases of a checkout, relative to its root.
const DEFAULT_PROBES: &str = "probes/stability";
