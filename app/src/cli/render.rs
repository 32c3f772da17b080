//! `twinray render`: one scene with one set, to a PNG (a moving scene's frames: `frames`).

use crate::args::{GlobalArgs, RenderArgs};
use crate::session::{context, load_still, refuse_viewpoint_with_frames, render_options, RENDER_TRACES};
use anyhow::Result;
use std::process::ExitCode;
use twinray_host::compare::hit_count;
use twinray_host::util::output::{check_image_target, write_image};

pub fn render(global: &GlobalArgs, args: RenderArgs) -> Result<ExitCode> {
    if let Some(range) = args.animation.frames {
        refuse_viewpoint_with_frames(&args.viewpoint)?;
        return crate::frames::render(global, args, range);
    }
    check_image_target(&args.out)?;
    // The set first: a scene may name the kinds of the crate it was built from.
    let shaders = global.load("--shaders", &args.shaders)?;
    let loading = std::time::Instant::now();
    let scene = load_still(args.scene.as_deref(), &args.viewpoint, &[&shaders])?;
    let load_ms = loading.elapsed().as_secs_f64() * 1e3;
    let opts = render_options(&scene, &args.frame, RENDER_TRACES)?;
    let ctx = context(global)?;
    let name = scene.name().to_string();
    // The scene given up: its meshes are freed once uploaded (a large model's peak memory).
    let out = twinray_host::render_owned(&ctx, scene, &shaders, &opts)?;
    write_image(&args.out, (out.width, out.height), &out.linear, &out.picture())?;
    let median = out.median_ms();
    let set = shaders.to_string();
    let mut problems = out.written.problems(&set, "pixels");
    if !out.no_payload.is_empty() {
        // Which stage wrote no payload is told by the f64 reference, which needs the meshes.
        let scene = load_still(args.scene.as_deref(), &args.viewpoint, &[&shaders])?;
        problems.extend(twinray_host::explain::no_payload::render_lines(&scene, &out, &set));
    }
    let peak = twinray_host::util::memory::peak_bytes();
    if args.frame.json {
        let value = serde_json::json!({
            "scene": name,
            "device": ctx.info.name,
            "set": shaders.to_string(),
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
            "peak_memory_bytes": peak,
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
        println!("{} {}x{} with {set} on {}: GPU {ms} of {}", name, out.width, out.height, ctx.info.name, out.rays);
        println!("  scene loaded in {load_ms:.0} ms; {}", out.accel);
        if let Some(bytes) = peak {
            println!("  host memory at its peak: {:.1} MiB", bytes as f64 / (1u64 << 20) as f64);
        }
        for problem in &problems {
            println!("FAIL: {problem} (magenta in {})", args.out.display());
        }
        println!("wrote {}", args.out.display());
    }
    Ok(if problems.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}
