//! `twinray pipeline-bench`: pipeline creation time per configuration, each measured in a
//! process of its own, and the trace time of linked pipelines against whole ones.

use crate::args::{FrameArgs, GlobalArgs};
use crate::session::{context, create_dir, options, render_options, COMPARE_TRACES};
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::{Command, ExitCode};
use twinray::bench::linking::{linking_table, trace_linking};
use twinray::bench::pipelines::{measure, run, table, Config, Measured};
use twinray_host::{Error, Scene, ShaderSet};

pub fn pipeline_bench(global: &GlobalArgs, args: PipelineBenchArgs) -> Result<ExitCode> {
    let scene = Scene::load(Some(&args.scene))?;
    let cache = args.out.join("caches");
    let mut base = options(global);
    base.pipeline_cache = None;
    if let Some(config) = &args.measure_one {
        let config: Config = serde_json::from_str(config).map_err(|e| Error::Input(format!("--measure-one: {e}")))?;
        println!("{}", serde_json::to_string(&measure(&base, &scene, &config, &cache)?)?);
        return Ok(ExitCode::SUCCESS);
    }
    let threads = thread_counts(args.thread_counts.as_deref())?;
    let trace_scenes = args
        .trace_scenes
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|name| Scene::load(Some(name)))
        .collect::<Result<Vec<_>, _>>()?;
    for scene in &trace_scenes {
        render_options(scene, &args.frame, COMPARE_TRACES)?;
    }
    create_dir(&args.out)?;
    let _ = std::fs::remove_dir_all(&cache);
    let progress = |step: &str| eprintln!("pipeline-bench: {step}");
    let configs = Config::all(&threads);
    let rows = if args.in_process {
        run(&configs, args.repeats as usize, |c| measure(&base, &scene, c, &cache), progress)?
    } else {
        run(&configs, args.repeats as usize, |c| measure_in_child(global, &args, c), progress)?
    };
    let _ = std::fs::remove_dir_all(&cache);
    let mut text = table(&rows);
    let mut linking = Vec::new();
    if !trace_scenes.is_empty() {
        let ctx = context(global)?;
        let sets = [ShaderSet::uniform(twinray_host::Language::Rust), ShaderSet::uniform(twinray_host::Language::Glsl)];
        let size = |s: &Scene| render_options(s, &args.frame, COMPARE_TRACES).expect("checked above");
        linking = trace_linking(&ctx, &trace_scenes, &sets, size, progress)?;
        text += &format!(
            "\nTrace time, linked against whole (interleaved, every build order):\n\n{}",
            linking_table(&linking)
        );
    }
    let json = serde_json::to_string_pretty(&serde_json::json!({ "creation": rows, "linking": linking }))?;
    for (name, body) in [("table.md", &text), ("results.json", &json)] {
        twinray_host::util::output::write_atomically(&args.out.join(name), body.as_bytes())?;
    }
    print!("{text}");
    println!("report in {}", args.out.display());
    Ok(ExitCode::SUCCESS)
}

fn thread_counts(text: Option<&str>) -> Result<Vec<usize>, Error> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    match text {
        None if cores > 1 => Ok(vec![1, cores]),
        None => Ok(vec![1]),
        Some(text) => text
            .split(',')
            .map(|t| t.trim().parse::<usize>().ok().filter(|n| (1..=1024).contains(n)))
            .collect::<Option<_>>()
            .ok_or_else(|| {
                Error::Input(format!("--thread-counts {text:?}: expected counts in 1..=1024, comma-separated"))
            }),
    }
}

/// One measurement in a fresh process of this program, with the same device and validation.
fn measure_in_child(global: &GlobalArgs, args: &PipelineBenchArgs, config: &Config) -> twinray_host::Result<Measured> {
    let failed = |why: String| Error::Unsupported(format!("measuring {config:?} in a child process: {why}"));
    let exe = std::env::current_exe().map_err(|e| failed(e.to_string()))?;
    let mut command = Command::new(exe);
    match global.validate {
        Some(crate::args::ValidateMode::Core) => command.arg("--validate"),
        Some(crate::args::ValidateMode::Gpu) => command.arg("--validate=gpu"),
        None => &mut command,
    };
    if let Some(device) = &global.device {
        command.args(["--device", device]);
    }
    let json = serde_json::to_string(config).map_err(|e| failed(e.to_string()))?;
    command.args(["pipeline-bench", &args.scene, "--measure-one", &json, "--out"]).arg(&args.out);
    let out = command.output().map_err(|e| failed(e.to_string()))?;
    if !out.status.success() {
        return Err(failed(String::from_utf8_lossy(&out.stderr).trim().to_string()));
    }
    serde_json::from_slice(&out.stdout).map_err(|e| failed(format!("{e}: {}", String::from_utf8_lossy(&out.stdout))))
}

#[derive(Args)]
pub struct PipelineBenchArgs {
    /// Scene whose pipelines are made [default: showcase, every hit group kind].
    #[arg(default_value = "showcase")]
    pub scene: String,
    /// Joining thread counts to compare, comma-separated [default: 1 and the machine's cores].
    #[arg(long)]
    pub thread_counts: Option<String>,
    /// Timed repeats per configuration (the median is reported), each on a fresh device.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub repeats: u32,
    /// Scenes whose trace time is measured whole against linked, comma-separated ("" for
    /// none); each renders at its own size unless --width and --height are given.
    #[arg(long, default_value = "showcase,spheres,meshes,lights")]
    pub trace_scenes: String,
    /// Image size and trace counts of the trace-time part [default: each scene's size, 10
    /// timed traces after 2 untimed].
    #[command(flatten)]
    pub frame: FrameArgs,
    /// Measure every configuration in this process instead of one process each (NVIDIA's
    /// driver 580 stops making instances after about 30 in one process).
    #[arg(long)]
    pub in_process: bool,
    /// Internal: measure one configuration (JSON) with caches under --out and print the result.
    #[arg(long, hide = true)]
    pub measure_one: Option<String>,
    /// Output folder for table.md, linking.md and results.json (created if missing).
    #[arg(long, default_value = "bench/out-pipelines")]
    pub out: PathBuf,
}
