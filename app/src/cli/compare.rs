//! `twinray compare`: two sets on one scene, image against image and GPU time against GPU time.

use crate::args::{CompareArgs, GlobalArgs};
use crate::session::{context, load_still, refuse_viewpoint_with_frames, render_options, COMPARE_TRACES};
use anyhow::Result;
use std::process::ExitCode;
use twinray_host::compare::report::compare_sets;
use twinray_host::Error;

pub fn compare(global: &GlobalArgs, args: CompareArgs) -> Result<ExitCode> {
    if args.processes > 0 && (args.animation.frames.is_some() || args.viewpoint.given()) {
        let message = "--processes times the scene's own still image: not with --frames, --frame, --eye or --look-at";
        return Err(Error::Input(message.into()).into());
    }
    if let Some(range) = args.animation.frames {
        refuse_viewpoint_with_frames(&args.viewpoint)?;
        return crate::frames::compare(global, args, range);
    }
    if args.out_dir.exists() && !args.out_dir.is_dir() {
        return Err(Error::Input(format!("--out-dir {}: exists and is not a directory", args.out_dir.display())).into());
    }
    // The sets first: a scene may name the kinds of the crates they were built from.
    let a = global.load("--a", &args.a)?;
    let b = global.load("--b", &args.b)?;
    let scene = load_still(args.scene.as_deref(), &args.viewpoint, &[&a, &b])?;
    let opts = render_options(&scene, &args.frame, COMPARE_TRACES)?;
    crate::timed_alone::check_runs(args.processes, opts.runs)?;
    let ctx = context(global)?;
    let scene_arg = args.scene.clone().unwrap_or_else(|| twinray_host::scene::DEFAULT_SCENE.to_string());
    let (isolation, cache) =
        crate::timed_alone::for_scene(global, scene_arg, &opts, &a, (args.processes, args.alone.alone_in));
    let comparison = compare_sets(&ctx, &scene, (&a, &b), &opts, isolation.as_ref());
    let _ = std::fs::remove_dir_all(cache);
    let comparison = comparison?;
    comparison.write_images(&args.out_dir)?;
    let report = &comparison.report;
    if args.frame.json {
        println!("{}", serde_json::to_string(report)?);
    } else {
        print!("{}", report.summary());
        println!("  wrote a.png, b.png, diff.png in {}", args.out_dir.display());
        println!("  diff.png: {}", twinray_host::compare::DIFF_LEGEND);
    }
    Ok(if report.pass { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}
