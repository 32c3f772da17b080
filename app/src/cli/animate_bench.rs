//! `twinray animate-bench` (AS time per frame for each TLAS mode, and trace time of each
//! mode's TLAS as objects drift, at several instance counts) and `twinray pipeline-bench`
//! (pipeline creation time per way of making them).

use crate::args::{GlobalArgs, MAX_PLACEMENTS, MAX_RUNS, MAX_WARMUP};
use crate::session::context;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray::bench::animation::{resize_grid, run, write, AnimateConfig};
use twinray_host::render::{TlasKind, TlasMode};
use twinray_host::scene::check_size;
use twinray_host::sets::SetSpec;
use twinray_host::{Error, Scene};

/// Most instances the bench resizes a grid to: the scene limit.
const MAX_INSTANCES: usize = twinray_host::scene::MAX_OBJECTS;

fn instance_counts(text: &str) -> Result<Vec<usize>, Error> {
    let bad = || Error::Input(format!("--instances {text:?}: expected counts in 1..={MAX_INSTANCES}, comma-separated"));
    let counts: Vec<usize> =
        text.split(',').map(|c| c.trim().parse::<usize>().map_err(|_| bad())).collect::<Result<_, _>>()?;
    if counts.is_empty() || counts.iter().any(|&c| c == 0 || c > MAX_INSTANCES) {
        return Err(bad());
    }
    Ok(counts)
}

fn modes(text: &str, rebuild_every: u32) -> Result<Vec<TlasMode>, Error> {
    use clap::ValueEnum;
    text.split(',')
        .map(|m| {
            TlasKind::from_str(m.trim(), false)
                .map(|kind| TlasMode { kind, rebuild_every })
                .map_err(|_| Error::Input(format!("--modes: {m:?} is not rebuild, fast-build or update")))
        })
        .collect()
}

pub fn animate_bench(global: &GlobalArgs, args: AnimateBenchArgs) -> Result<ExitCode> {
    let modes = modes(&args.modes, args.rebuild_every)?;
    let scenes = scenes(&args)?;
    let first = &scenes[0];
    if first.animation.is_none() {
        return Err(Error::Input(format!(
            "{}: a still scene; animate-bench needs an [animation], or a glTF model's animation",
            args.scene
        ))
        .into());
    }
    let frames = args.frames.unwrap_or(first.frame_count());
    twinray_host::render::frames::check_frames(first, &(0..frames))?;
    let (width, height) =
        (args.width.unwrap_or(first.file.image.width), args.height.unwrap_or(first.file.image.height));
    check_size(width, height).map_err(Error::Input)?;
    std::fs::create_dir_all(&args.out).map_err(|source| Error::Io {
        what: "creating",
        path: args.out.clone(),
        source,
    })?;
    let shaders = global.load("--shaders", &args.shaders)?;
    let ctx = context(global)?;
    let config = AnimateConfig {
        scenes,
        set: shaders.clone(),
        modes,
        frames,
        width,
        height,
        warmup: args.warmup,
        runs: args.runs,
        placements: args.placements,
    };
    let report = run(&ctx, &config, |step| eprintln!("animate-bench: {step}"))?;
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    write(&report, &command, &args.out)?;
    print!("{}", twinray::bench::animation::report_table(&report));
    println!("report in {}", args.out.display());
    Ok(ExitCode::SUCCESS)
}

/// The scene at each instance count; a glTF model as it is (its clip is what moves).
fn scenes(args: &AnimateBenchArgs) -> Result<Vec<Scene>, Error> {
    if twinray_host::scene::gltf::is_gltf(std::path::Path::new(&args.scene)) {
        if args.instances.is_some() {
            return Err(Error::Input(format!(
                "{}: --instances resizes a scene file's grid; a glTF model is measured as it is",
                args.scene
            )));
        }
        return Ok(vec![Scene::load(Some(&args.scene))?]);
    }
    let (text, source, mesh_files) = Scene::read(Some(&args.scene))?;
    instance_counts(args.instances.as_deref().unwrap_or(DEFAULT_INSTANCES))?
        .into_iter()
        .map(|n| Scene::parse(&resize_grid(&text, n)?, &source, mesh_files.clone()))
        .collect()
}

const DEFAULT_INSTANCES: &str = "1000,10000,100000";

#[derive(Args)]
pub struct AnimateBenchArgs {
    /// A moving scene with a [[grids]] table (its first grid is resized), or a glTF model with
    /// an animation, measured as it is: a skinned or morphed one refits its meshes' BLASes
    /// where the TLAS is updated and rebuilds them where it is rebuilt [default: swarm].
    #[arg(default_value = "swarm")]
    pub scene: String,
    /// Instance counts, comma-separated (each made an n x n grid, n the nearest square root)
    /// [default: 1000,10000,100000]; not for a glTF model.
    #[arg(long)]
    pub instances: Option<String>,
    /// TLAS modes, comma-separated: rebuild, fast-build, update.
    #[arg(long, default_value = "rebuild,fast-build,update")]
    pub modes: String,
    /// For the update mode: a full rebuild every N frames (0: the first frame only, so the
    /// TLAS is refitted through the whole motion).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub rebuild_every: u32,
    /// Frames 0..N of the scene [default: all of them].
    #[arg(long)]
    pub frames: Option<u32>,
    /// Shader set that traces.
    #[arg(long, default_value = "rust")]
    pub shaders: SetSpec,
    /// Image width [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// Timed traces per frame.
    #[arg(long, default_value_t = 3, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_RUNS)))]
    pub runs: u32,
    /// Untimed traces before the first frame (and at least 1000 ms of GPU time when above 0;
    /// before each later frame, at least a fifth of that).
    #[arg(long, default_value_t = 2, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_WARMUP)))]
    pub warmup: u32,
    /// Renderings of the whole animation, each mode's pipeline made afresh in an order of its
    /// own; the trace-time ratios' 95% intervals are over them.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_PLACEMENTS)))]
    pub placements: u32,
    /// Output folder (created if missing).
    #[arg(long, default_value = "bench/out-animation")]
    pub out: PathBuf,
}
