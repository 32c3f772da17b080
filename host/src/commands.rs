//! The bodies of `twinray info`, `render` and `compare`: every input is checked before any
//! GPU work, and files are written only once everything has succeeded.

use crate::{BenchArgs, CompareArgs, FrameArgs, GlobalArgs, ProbeArgs, ReferenceArgs, RenderArgs, StabilityArgs};
use anyhow::{Context as _, Result};
use std::process::ExitCode;
use std::sync::Arc;
use twinray::compare::hit_count;
use twinray::output::{check_png_target, write_png};
use twinray::render::check_size;
use twinray::report::compare_sets;
use twinray::scene::file::Formula;
use twinray::{Context, ContextOptions, Error, RenderOptions, Scene, Validation};

fn context(global: &GlobalArgs) -> Result<Arc<Context>> {
    let options = ContextOptions {
        validation: if global.validate { Validation::Required } else { Validation::Off },
        device_filter: global.device.clone(),
    };
    Context::new(&options).context("setting up Vulkan")
}

/// (warm-up, timed) traces when not given: `render` wants an image quickly, `compare` a
/// GPU-time ratio that is a median over several traces.
const RENDER_TRACES: (u32, u32) = (0, 1);
const COMPARE_TRACES: (u32, u32) = (2, 10);

/// Size from the flags, or the scene's, checked against twinray's limits; trace counts from the
/// flags or `(warmup, runs)`.
fn render_options(scene: &Scene, frame: &FrameArgs, (warmup, runs): (u32, u32)) -> Result<RenderOptions, Error> {
    let width = frame.width.unwrap_or(scene.file.image.width);
    let height = frame.height.unwrap_or(scene.file.image.height);
    check_size(width, height).map_err(Error::Input)?;
    Ok(RenderOptions { width, height, warmup: frame.warmup.unwrap_or(warmup), runs: frame.runs.unwrap_or(runs) })
}

pub fn info(global: &GlobalArgs, json: bool) -> Result<ExitCode> {
    let ctx = context(global)?;
    let i = &ctx.info;
    if json {
        println!("{}", serde_json::to_string_pretty(i)?);
    } else {
        println!("device      {} ({})", i.name, i.device_type);
        println!("driver      {} {}", i.driver_name, i.driver_info);
        println!("vulkan      {}", i.api_version);
        println!(
            "sbt         handle size {}, handle alignment {}, base alignment {}",
            i.shader_group_handle_size, i.shader_group_handle_alignment, i.shader_group_base_alignment
        );
        println!("recursion   max depth {}", i.max_ray_recursion_depth);
        println!(
            "dispatch    max {} invocations, image side {}",
            i.max_ray_dispatch_invocation_count, i.max_image_dimension_2d
        );
        let timing = if i.timestamp_valid_bits > 0 {
            format!("{} ns per tick, {} valid bits", i.timestamp_period_ns, i.timestamp_valid_bits)
        } else {
            "not available on this queue".into()
        };
        println!("timestamps  {timing}");
        if let Some(threads) = i.cpu_threads {
            println!("threads     {threads} (a CPU device: LP_NUM_THREADS, else the CPU count)");
        }
    }
    Ok(ExitCode::SUCCESS)
}

pub fn scenes(json: bool) -> Result<ExitCode> {
    let mut rows = Vec::new();
    for (name, _) in twinray::scene::BUILTIN {
        let scene = Scene::load(Some(name))?;
        let data = scene.build();
        let groups: Vec<_> = data.plan.hit_groups.iter().map(|g| g.name()).collect();
        rows.push(serde_json::json!({
            "name": name,
            "description": scene.file.description,
            "width": scene.file.image.width,
            "height": scene.file.image.height,
            "samples": scene.file.image.samples,
            "objects": scene.file.objects.len(),
            "lights": scene.file.lights.len(),
            "hit_groups": groups,
            "shadows": data.plan.shadows,
        }));
    }
    let kinds = twinray::scene::file::KINDS;
    if json {
        let kinds: serde_json::Map<_, _> =
            kinds.iter().map(|(what, list)| (what.to_string(), serde_json::json!(list))).collect();
        println!("{}", serde_json::json!({ "scenes": rows, "kinds": kinds }));
        return Ok(ExitCode::SUCCESS);
    }
    println!("{:<10} {:>9} {:>7} {:>7}  {:<28} description", "scene", "size", "objects", "shadows", "hit groups");
    for r in &rows {
        println!(
            "{:<10} {:>9} {:>7} {:>7}  {:<28} {}",
            r["name"].as_str().unwrap_or_default(),
            format!("{}x{}", r["width"], r["height"]),
            r["objects"],
            if r["shadows"] == true { "yes" } else { "no" },
            r["hit_groups"]
                .as_array()
                .map(|g| g.iter().filter_map(|v| v.as_str()).collect::<Vec<_>>().join(","))
                .unwrap_or_default(),
            r["description"].as_str().unwrap_or_default(),
        );
    }
    println!();
    for (what, list) in kinds {
        println!("{what:<10} {}", list.join(", "));
    }
    println!("\nEvery field of a scene file: docs/scene-format.md");
    Ok(ExitCode::SUCCESS)
}

pub fn render(global: &GlobalArgs, args: RenderArgs) -> Result<ExitCode> {
    let scene = Scene::load(args.scene.as_deref())?;
    let opts = render_options(&scene, &args.frame, RENDER_TRACES)?;
    check_png_target(&args.out)?;
    let ctx = context(global)?;
    let out = twinray::render(&ctx, &scene, &args.shaders, &opts)?;
    write_png(&args.out, out.width, out.height, &out.rgba)?;
    let median = out.median_ms();
    if args.frame.json {
        let value = serde_json::json!({
            "scene": scene.name(),
            "device": ctx.info.name,
            "set": args.shaders.to_string(),
            "width": out.width,
            "height": out.height,
            "out": args.out,
            "gpu_ms": median,
            "gpu_ms_spread": out.spread(),
            "gpu_ms_runs": out.gpu_ms,
            "warmup_traces": out.warmup_traces,
            "rays": out.rays,
            "mrays_per_s": out.mrays_per_s(),
            "cpu_threads": ctx.info.cpu_threads,
            "hit_pixels": hit_count(&out),
        });
        println!("{value}");
    } else {
        let ms = out.spread().map_or("n/a".into(), |s| {
            let rate = out.mrays_per_s().map_or(String::new(), |r| format!(", {r:.1} Mrays/s"));
            format!("{:.3} ms (median of {}, IQR {:.3}){rate}", s.median, s.samples, s.iqr())
        });
        println!("{} {}x{} with {} on {}: GPU {ms}", scene.name(), out.width, out.height, args.shaders, ctx.info.name);
        println!("wrote {}", args.out.display());
    }
    Ok(ExitCode::SUCCESS)
}

pub fn compare(global: &GlobalArgs, args: CompareArgs) -> Result<ExitCode> {
    let scene = Scene::load(args.scene.as_deref())?;
    let opts = render_options(&scene, &args.frame, COMPARE_TRACES)?;
    if args.out_dir.exists() && !args.out_dir.is_dir() {
        return Err(Error::Input(format!("--out-dir {}: exists and is not a directory", args.out_dir.display())).into());
    }
    let ctx = context(global)?;
    let comparison = compare_sets(&ctx, &scene, &args.a, &args.b, &opts)?;
    comparison.write_images(&args.out_dir)?;
    let report = &comparison.report;
    if args.frame.json {
        println!("{}", serde_json::to_string(report)?);
    } else {
        print!("{}", report.summary());
        println!("  wrote a.png, b.png, diff.png in {}", args.out_dir.display());
        println!("  diff.png: {}", twinray::compare::DIFF_LEGEND);
    }
    Ok(if report.pass { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

pub fn probe(global: &GlobalArgs, args: ProbeArgs) -> Result<ExitCode> {
    let mut case = twinray::probe_case::ProbeCase::load(&args.case)?;
    if let Some(formula) = args.formula.as_deref() {
        let formula = if formula == "naive" { Formula::Naive } else { Formula::Robust };
        case.set_formula(formula);
    }
    let ctx = context(global)?;
    let out = twinray::probe::probe(&ctx, &case.scene, &args.shaders, &case.rays, args.warmup, args.runs)?;
    let median = twinray::stats::median(&out.gpu_ms);
    let label = match args.formula.as_deref() {
        Some(formula) => format!("{} ({formula})", args.shaders),
        None => args.shaders.to_string(),
    };
    let report = twinray::probe_report::evaluate(&case, &out.results, &label, &ctx.info.name, median);
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print!("{}", report.summary());
    }
    Ok(ExitCode::SUCCESS)
}

pub fn stability(global: &GlobalArgs, args: StabilityArgs) -> Result<ExitCode> {
    let files = twinray::stability::case_files(&args.dir)?;
    let sets = args.sets.split(';').map(str::parse).collect::<Result<Vec<twinray::ShaderSet>, _>>()?;
    let ctx = context(global)?;
    let formulas = [Formula::Robust, Formula::Naive];
    let timing = twinray::stability::Timing { warmup: args.warmup, runs: args.runs, rays: args.timing_rays };
    let rows = twinray::stability::run(&ctx, &files, &sets, &formulas, timing)?;
    if args.json {
        println!("{}", serde_json::to_string(&rows)?);
    } else {
        print!("{}", twinray::stability::table(&rows));
    }
    let missed = rows.iter().filter(|r| !r.failures.is_empty()).count();
    Ok(if missed == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

pub fn reference(global: &GlobalArgs, args: ReferenceArgs) -> Result<ExitCode> {
    let scene = Scene::load(args.scene.as_deref())?;
    let size = (args.width.unwrap_or(scene.file.image.width), args.height.unwrap_or(scene.file.image.height));
    check_size(size.0, size.1).map_err(Error::Input)?;
    twinray::reference_image::frames(args.spp)?;
    if let Some(out) = &args.out {
        check_png_target(out)?;
    }
    let cache = args.cache.unwrap_or_else(twinray::reference_image::default_cache);
    let ctx = context(global)?;
    let start = std::time::Instant::now();
    let r = twinray::reference_image::reference(&ctx, &scene, &args.shaders, size, args.spp, &cache)?;
    if let Some(out) = &args.out {
        write_png(out, r.width, r.height, &twinray::render::to_rgba8(&r.linear))?;
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
    twinray::reference_image::frames(args.reference_spp)?;
    if args.runs < 10 {
        return Err(Error::Input(format!("--runs must be at least 10 (got {})", args.runs)).into());
    }
    if let (Some(w), Some(h)) = (args.width, args.height) {
        check_size(w, h).map_err(Error::Input)?;
    }
    let sets = twinray::shader_set::parse_sets(&args.sets)?;
    if args.probes.as_os_str() != "none" && !args.probes.is_dir() {
        let message = format!("--probes {}: no such folder (give --probes DIR, or none)", args.probes.display());
        return Err(Error::Input(message).into());
    }
    let config = bench::BenchConfig {
        scenes,
        sets,
        spp,
        size: args.width.zip(args.height),
        warmup: args.warmup,
        runs: args.runs,
        reference_spp: args.reference_spp,
        reference_set: args.reference_set,
        cache: args.cache.unwrap_or_else(twinray::reference_image::default_cache),
        out: args.out.clone(),
        shadow_spp,
        probes: Some(args.probes.clone()).filter(|p| p.as_os_str() != "none"),
        timing_rays: args.timing_rays,
        images: args.images,
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
    for (scene, spp, ratio) in &ratios {
        println!("{scene:<12} {spp:>4} spp  rust/glsl {ratio:.3}");
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
