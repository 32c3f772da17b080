//! `twinray render` and `twinray compare`.

use crate::args::{CompareArgs, GlobalArgs, RenderArgs};
use crate::session::{
    context, load_still, refuse_viewpoint_with_frames, render_options, COMPARE_TRACES, RENDER_TRACES,
};
use anyhow::Result;
use std::process::ExitCode;
use twinray::compare::hit_count;
use twinray::compare::report::compare_sets;
use twinray::util::output::{check_image_target, write_image};
use twinray::Error;

pub fn render(global: &GlobalArgs, args: RenderArgs) -> Result<ExitCode> {
    if let Some(range) = args.animation.frames {
        refuse_viewpoint_with_frames(&args.viewpoint)?;
        return crate::frames::render(global, args, range);
    }
    let loading = std::time::Instant::now();
    let scene = load_still(args.scene.as_deref(), &args.viewpoint)?;
    let load_ms = loading.elapsed().as_secs_f64() * 1e3;
    let opts = render_options(&scene, &args.frame, RENDER_TRACES)?;
    check_image_target(&args.out)?;
    let ctx = context(global)?;
    let out = twinray::render(&ctx, &scene, &args.shaders, &opts)?;
    write_image(&args.out, (out.width, out.height), &out.linear, &out.picture())?;
    let median = out.median_ms();
    let set = args.shaders.to_string();
    let mut problems = out.written.problems(&set, "pixels");
    problems.extend(twinray::explain::no_payload::render_lines(&scene, &out, &set));
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
            "written": out.written,
            "load_ms": load_ms,
            "acceleration_structures": out.accel,
            "pass": problems.is_empty(),
            "failures": problems,
        });
        println!("{value}");
    } else {
        let ms = out.spread().map_or("n/a".into(), |s| {
            let rate = out.mrays_per_s().map_or(String::new(), |r| format!(", {r:.1} Mrays/s"));
            format!("{:.3} ms (median of {}, IQR {:.3}){rate}", s.median, s.samples, s.iqr())
        });
        println!(
            "{} {}x{} with {set} on {}: GPU {ms} of {}",
            scene.name(),
            out.width,
            out.height,
            ctx.info.name,
            out.rays
        );
        println!("  scene loaded in {load_ms:.0} ms; {}", out.accel);
        for problem in &problems {
            println!("FAIL: {problem} (magenta in {})", args.out.display());
        }
        println!("wrote {}", args.out.display());
    }
    Ok(if problems.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

pub fn compare(global: &GlobalArgs, args: CompareArgs) -> Result<ExitCode> {
    if args.processes > 0 && (args.animation.frames.is_some() || args.viewpoint.given()) {
        let message = "--processes times the scene's own still image: not with --frames, --frame, --eye or --look-at";
        return Err(Error::Input(message.into()).into());
    }
    if let Some(range) = args.animation.frames {
        refuse_viewpoint_with_frames(&args.viewpoint)?;
        return crate::frames::compare(global, args, range);
    }
    let scene = load_still(args.scene.as_deref(), &args.viewpoint)?;
    let opts = render_options(&scene, &args.frame, COMPARE_TRACES)?;
    crate::alone::check_runs(args.processes, opts.runs)?;
    if args.out_dir.exists() && !args.out_dir.is_dir() {
        return Err(Error::Input(format!("--out-dir {}: exists and is not a directory", args.out_dir.display())).into());
    }
    let ctx = context(global)?;
    let scene_arg = args.scene.clone().unwrap_or_else(|| twinray::scene::DEFAULT_SCENE.to_string());
    let (isolation, cache) =
        crate::alone::for_scene(global, scene_arg, &opts, &args.a, (args.processes, args.alone.alone_in));
    let comparison = compare_sets(&ctx, &scene, (&args.a, &args.b), &opts, isolation.as_ref());
    let _ = std::fs::remove_dir_all(cache);
    let comparison = comparison?;
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
