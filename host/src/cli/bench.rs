//! `twinray reference` and `twinray bench`.

use crate::args::{BenchArgs, GlobalArgs, ReferenceArgs};
use crate::session::context;
use anyhow::Result;
use std::process::ExitCode;
use twinray::scene::check_size;
use twinray::util::output::{check_image_target, write_image};
use twinray::{Error, Scene};

pub fn reference(global: &GlobalArgs, args: ReferenceArgs) -> Result<ExitCode> {
    let scene = Scene::load(args.scene.as_deref())?;
    let size = (args.width.unwrap_or(scene.file.image.width), args.height.unwrap_or(scene.file.image.height));
    check_size(size.0, size.1).map_err(Error::Input)?;
    twinray::reference::image::frames(args.spp)?;
    if let Some(out) = &args.out {
        check_image_target(out)?;
    }
    let cache = args.cache.unwrap_or_else(twinray::reference::image::default_cache);
    let ctx = context(global)?;
    let start = std::time::Instant::now();
    let r = twinray::reference::image::reference(&ctx, &scene, &args.shaders, size, args.spp, &cache)?;
    if let Some(out) = &args.out {
        write_image(out, (r.width, r.height), &r.linear, &twinray::render::to_picture(&r.linear))?;
    }
    if args.json {
        let value = serde_json::json!({
            "scene": scene.name(),
            "set": args.shaders.to_string(),
            "width": r.width,
            "height": r.height,
            "spp": r.spp,
            "path": r.path,
            "cached": r.cached,
            "seconds": start.elapsed().as_secs_f64(),
        });
        println!("{value}");
    } else {
        let how = if r.cached { "read from the cache" } else { "rendered" };
        println!(
            "{} {}x{} at {} spp with {}: {how}, {}",
            scene.name(),
            r.width,
            r.height,
            r.spp,
            args.shaders,
            r.path.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}

pub fn bench(global: &GlobalArgs, args: BenchArgs) -> Result<ExitCode> {
    use twinray::bench;
    let names = if args.scenes.is_empty() {
        twinray::scene::BUILTIN.iter().map(|(name, _)| name.to_string()).collect()
    } else {
        args.scenes.clone()
    };
    let scenes = names.iter().map(|n| Scene::load(Some(n))).collect::<Result<Vec<_>, _>>()?;
    let (spp, shadow_spp) = (sample_counts("--spp", &args.spp)?, sample_counts("--shadow-spp", &args.shadow_spp)?);
    if spp.is_empty() {
        return Err(Error::Input("--spp needs at least one sample count".into()).into());
    }
    twinray::reference::image::frames(args.reference_spp)?;
    if args.runs < 10 {
        return Err(Error::Input(format!("--runs must be at least 10 (got {})", args.runs)).into());
    }
    if let (Some(w), Some(h)) = (args.width, args.height) {
        check_size(w, h).map_err(Error::Input)?;
    }
    let sets = twinray::shaders::parse_sets(&args.sets)?;
    if args.probes.as_os_str() != "none" && !args.probes.is_dir() {
        let message = format!("--probes {}: no such folder (give --probes DIR, or none)", args.probes.display());
        return Err(Error::Input(message).into());
    }
    let cache = args.cache.clone().unwrap_or_else(twinray::reference::image::default_cache);
    let isolation = (args.processes > 0).then(|| bench::Isolation {
        processes: args.processes,
        placements: args.placements,
        first: args.first_placement,
        alone_in: args.alone.alone_in,
        time_alone: crate::alone::time_alone(
            global,
            crate::alone::ChildSettings::of_bench(&args, cache.clone()),
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
        reference_set: args.reference_set,
        cache,
        out: args.out.clone(),
        shadow_spp,
        probes: Some(args.probes.clone()).filter(|p| p.as_os_str() != "none"),
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
