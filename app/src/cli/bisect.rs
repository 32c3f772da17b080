//! `twinray bisect`: which stage makes two sets differ, in image (or probe results) and time.

use crate::args::{AloneArgs, FrameArgs, GlobalArgs};
use crate::session::{context, render_options, COMPARE_TRACES};
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::compare::bisect::{bisect as run_bisect, BisectReport, ImageSubject, ProbeSubject};
use twinray_host::sets::SetSpec;
use twinray_host::{Error, Scene};

pub fn bisect(global: &GlobalArgs, args: BisectArgs) -> Result<ExitCode> {
    let (a, b) = (global.load("--a", &args.a)?, global.load("--b", &args.b)?);
    let own = twinray_host::ShaderSet::own_kinds(&[&a, &b]);
    let report = match &args.probe {
        Some(path) => {
            if args.frame.width.is_some() || args.frame.height.is_some() || args.processes > 0 {
                return Err(Error::Input("--width, --height and --processes do not apply to --probe".into()).into());
            }
            let case = twinray_host::probe::builtin::open(path, &own)?;
            let ctx = context(global)?;
            let (warmup, runs, placements) = COMPARE_TRACES;
            let mut subject = ProbeSubject {
                ctx: &ctx,
                case: &case,
                warmup: args.frame.warmup.unwrap_or(warmup),
                runs: args.frame.runs.unwrap_or(runs),
                placements: args.frame.placements.unwrap_or(placements),
            };
            run_bisect(&mut subject, &a, &b)?
        }
        None => {
            let scene = Scene::load_with(args.scene.as_deref(), &own)?;
            let opts = render_options(&scene, &args.frame, COMPARE_TRACES)?;
            crate::timed_alone::check_runs(args.processes, opts.runs)?;
            let ctx = context(global)?;
            let scene_arg = args.scene.clone().unwrap_or_else(|| twinray_host::scene::DEFAULT_SCENE.to_string());
            let (isolation, cache) =
                crate::timed_alone::for_scene(global, scene_arg, &opts, &a, (args.processes, args.alone.alone_in));
            let report = run_bisect(&mut ImageSubject { ctx: &ctx, scene: &scene, opts, isolation }, &a, &b);
            let _ = std::fs::remove_dir_all(cache);
            report?
        }
    };
    print_report(&report, args.frame.json)?;
    Ok(if report.pinned && report.failures.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

fn print_report(report: &BisectReport, json: bool) -> Result<()> {
    if json {
        println!("{}", serde_json::to_string(report)?);
    } else {
        print!("{}", report.summary());
    }
    Ok(())
}

#[derive(Args)]
pub struct BisectArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    #[arg(conflicts_with = "probe")]
    pub scene: Option<String>,
    /// Bisect on a probe case's rays (TOML, see docs/probe-format.md, or a built-in case's
    /// name) instead of a scene's image: which stage makes false hits or misses.
    #[arg(long, value_name = "CASE")]
    pub probe: Option<PathBuf>,
    /// Set A.
    #[arg(long, default_value = "rust")]
    pub a: SetSpec,
    /// Set B.
    #[arg(long, default_value = "glsl")]
    pub b: SetSpec,
    #[command(flatten)]
    pub frame: FrameArgs,
    /// Time each set alone in N processes of its own, as `compare --processes` does (not with
    /// --probe). 0: every set timed in this process.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=64))]
    pub processes: u32,
    #[command(flatten)]
    pub alone: AloneArgs,
}
