//! `twinray render --frames` and `twinray compare --frames`: a moving scene, frame by frame.

use crate::args::CompareArgs;
use crate::args::GlobalArgs;
use crate::args::RenderArgs;
use crate::session::{context, render_options, COMPARE_TRACES, RENDER_TRACES};
use anyhow::Result;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use twinray_host::compare::{compare_frames, diff_image};
use twinray_host::render::{render_frames, FrameRange};
use twinray_host::util::apng::AnimatedPng;
use twinray_host::util::output::{check_png_target, write_png};
use twinray_host::util::stats::median;
use twinray_host::{Error, Scene, ShaderSet};

/// `STEM-NNNN.png` beside `out`.
fn numbered(out: &Path, frame: u32) -> PathBuf {
    let stem = out.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "render".into());
    out.with_file_name(format!("{stem}-{frame:04}.png"))
}

fn fps(scene: &Scene) -> f32 {
    scene.animation.as_ref().map_or(24.0, |a| a.fps)
}

pub fn render(global: &GlobalArgs, args: RenderArgs, range: FrameRange) -> Result<ExitCode> {
    check_png_target(&args.out)?;
    let shaders = global.load("--shaders", &args.shaders)?;
    let scene = Scene::load_with(args.scene.as_deref(), &ShaderSet::own_kinds(&[&shaders]))?;
    let frames = range.of(&scene)?;
    let opts = render_options(&scene, &args.frame, RENDER_TRACES)?;
    let ctx = context(global)?;
    let mode = args.animation.mode();
    let mut movie = AnimatedPng::create(&args.out, (opts.width, opts.height), frames.len() as u32, fps(&scene))?;
    let mut rows = Vec::new();
    let set = shaders.to_string();
    let mut problems = Vec::new();
    render_frames(&ctx, &scene, std::slice::from_ref(&shaders), &opts, frames, mode, |frame| {
        let out = &frame.outputs[0];
        let mut found = out.written.problems(&set, "pixels");
        if !out.no_payload.is_empty() {
            let posed = scene.at_frame(frame.index)?;
            found.extend(twinray_host::explain::no_payload::render_lines(&posed, out, &set));
        }
        problems.extend(found.into_iter().map(|p| format!("frame {}: {p}", frame.index)));
        let png = numbered(&args.out, frame.index);
        let picture = out.picture();
        write_png(&png, out.width, out.height, &picture)?;
        movie.add(&picture)?;
        rows.push(serde_json::json!({
            "frame": frame.index,
            "time": frame.time,
            "as_work": frame.as_work,
            "as_ms": frame.as_ms,
            "trace_ms": out.median_ms(),
            "rays": out.rays,
            "written": out.written,
            "png": png,
        }));
        Ok(())
    })?;
    movie.finish()?;
    if args.frame.json {
        let value = serde_json::json!({
            "scene": scene.name(),
            "device": ctx.info.name,
            "set": shaders.to_string(),
            "width": opts.width,
            "height": opts.height,
            "tlas": mode.name(),
            "out": args.out,
            "frames": rows,
            "pass": problems.is_empty(),
            "failures": problems,
        });
        println!("{value}");
        return Ok(if problems.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE });
    }
    println!(
        "{} {}x{} with {} on {}, TLAS {}: {} frames",
        scene.name(),
        opts.width,
        opts.height,
        shaders,
        ctx.info.name,
        mode.name(),
        rows.len()
    );
    println!("{:>6} {:>8} {:>7} {:>9} {:>10}", "frame", "time s", "AS", "AS ms", "trace ms");
    let ms = |v: &serde_json::Value| v.as_f64().map_or("n/a".into(), |v| format!("{v:.3}"));
    for r in &rows {
        println!(
            "{:>6} {:>8.3} {:>7} {:>9} {:>10}",
            r["frame"].as_u64().unwrap_or(0),
            r["time"].as_f64().unwrap_or(0.0),
            r["as_work"].as_str().unwrap_or("-"),
            ms(&r["as_ms"]),
            ms(&r["trace_ms"])
        );
    }
    let medians = |key: &str| median(&rows.iter().filter_map(|r| r[key].as_f64()).collect::<Vec<_>>());
    let show = |m: Option<f64>| m.map_or("n/a".into(), |m| format!("{m:.3} ms"));
    println!("median AS {}, median trace {}", show(medians("as_ms")), show(medians("trace_ms")));
    for problem in &problems {
        println!("FAIL: {problem}");
    }
    println!("wrote {} (animated) and {}", args.out.display(), numbered(&args.out, 0).display());
    Ok(if problems.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

pub fn compare(global: &GlobalArgs, args: CompareArgs, range: FrameRange) -> Result<ExitCode> {
    if args.out_dir.exists() && !args.out_dir.is_dir() {
        return Err(Error::Input(format!("--out-dir {}: exists and is not a directory", args.out_dir.display())).into());
    }
    let a = global.load("--a", &args.a)?;
    let b = global.load("--b", &args.b)?;
    let scene = Scene::load_with(args.scene.as_deref(), &ShaderSet::own_kinds(&[&a, &b]))?;
    let frames = range.of(&scene)?;
    let opts = render_options(&scene, &args.frame, COMPARE_TRACES)?;
    let ctx = context(global)?;
    std::fs::create_dir_all(&args.out_dir).map_err(|source| Error::Io {
        what: "creating",
        path: args.out_dir.clone(),
        source,
    })?;
    let parity = scene.file.parity;
    let pixels = u64::from(opts.width) * u64::from(opts.height);
    let mut worst: Option<(f64, [Vec<u8>; 3])> = None;
    let sets = (&a, &b);
    let report = compare_frames(&ctx, &scene, sets, &opts, frames, args.animation.mode(), |row, a, b| {
        let diff = diff_image(a, b, &row.diff);
        if !row.pass {
            write_png(&args.out_dir.join(format!("diff-{:04}.png", row.frame)), a.width, a.height, &diff)?;
        }
        let bad = twinray_host::compare::frames::badness(&row.diff, &parity, pixels);
        if worst.as_ref().is_none_or(|w| bad > w.0) {
            worst = Some((bad, [a.picture(), b.picture(), diff]));
        }
        Ok(())
    })?;
    if let Some((_, images)) = &worst {
        for (name, rgba) in ["a.png", "b.png", "diff.png"].into_iter().zip(images) {
            write_png(&args.out_dir.join(name), opts.width, opts.height, rgba)?;
        }
    }
    if args.frame.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print!("{}", report.summary());
        println!("  wrote the worst frame's a.png, b.png, diff.png in {}", args.out_dir.display());
    }
    Ok(if report.pass { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}
