//! `twinray pipeline-bench`: pipeline creation time per configuration, each measured in a
//! process of its own, and the trace time of linked pipelines against whole ones; and
//! `twinray stage-bench`: what stage kinds and tracing methods cost.

use crate::args::{GlobalArgs, PipelineBenchArgs, StageBenchArgs};
use crate::session::{context, options, render_options, COMPARE_TRACES};
use anyhow::Result;
use std::process::{Command, ExitCode};
use twinray::bench::linking::{linking_table, trace_linking};
use twinray::bench::pipelines::{measure, run, table, Config, Measured};
use twinray::{Error, Scene, ShaderSet};

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
        let sets = [ShaderSet::uniform(twinray::Language::Rust), ShaderSet::uniform(twinray::Language::Glsl)];
        let size = |s: &Scene| render_options(s, &args.frame, COMPARE_TRACES).expect("checked above");
        linking = trace_linking(&ctx, &trace_scenes, &sets, size, progress)?;
        text += &format!(
            "\nTrace time, linked against whole (interleaved, every build order):\n\n{}",
            linking_table(&linking)
        );
    }
    let json = serde_json::to_string_pretty(&serde_json::json!({ "creation": rows, "linking": linking }))?;
    for (name, body) in [("table.md", &text), ("results.json", &json)] {
        twinray::util::output::write_atomically(&args.out.join(name), body.as_bytes())?;
    }
    print!("{text}");
    println!("report in {}", args.out.display());
    Ok(ExitCode::SUCCESS)
}

/// One placement per render: `stage-bench`'s rounds are its placements.
const STAGE_TRACES: (u32, u32, u32) = (COMPARE_TRACES.0, COMPARE_TRACES.1, 1);

pub fn stage_bench(global: &GlobalArgs, args: StageBenchArgs) -> Result<ExitCode> {
    use twinray::bench::stages::{run, table, StagePlan, Variant};
    let scenes = args.scenes.iter().map(|name| Scene::load(Some(name))).collect::<Result<Vec<_>, _>>()?;
    let variants = Variant::parse_list(&args.variants)?;
    let sets = twinray::shaders::parse_sets(&args.sets)?;
    if args.frame.placements.is_some() {
        let why =
            "stage-bench: each round makes every pipeline afresh (a placement); give --rounds instead of --placements";
        return Err(twinray::Error::Input(why.into()).into());
    }
    for scene in &scenes {
        render_options(scene, &args.frame, STAGE_TRACES)?;
    }
    create_dir(&args.out)?;
    let ctx = context(global)?;
    let timer = args.alone.then(|| crate::alone::stage_timer(global, &args.frame, args.scenes.clone()));
    let alone = timer.as_ref().map(|t| t as &twinray::bench::stages::TimeCell);
    let (rounds, first_round) = (args.rounds, args.first_round);
    let plan = StagePlan { scenes: &scenes, variants: &variants, sets: &sets, rounds, first_round, alone };
    let opts = |s: &Scene| render_options(s, &args.frame, STAGE_TRACES).expect("checked above");
    let (rows, skipped) = run(&ctx, &plan, opts, |step| eprintln!("stage-bench: {step}"))?;
    let (round, times) = match args.alone {
        true => ("each render alone in a process of its own", "medians of the rounds' medians"),
        false => ("each a placement", "medians of every timed trace of every round"),
    };
    let text = format!(
        "{} on {}, {} rounds ({round}); times are {times}, ratios have their 95% interval over rounds\n\n{}",
        std::env::args().collect::<Vec<_>>().join(" "),
        ctx.info.name,
        args.rounds,
        table(&rows, &skipped)
    );
    let json = serde_json::to_string_pretty(&serde_json::json!({
        "device": ctx.info.name, "driver": ctx.info.driver_info, "alone": args.alone, "first_round": first_round, "rows": rows, "skipped": skipped,
    }))?;
    for (name, body) in [("table.md", &text), ("results.json", &json)] {
        twinray::util::output::write_atomically(&args.out.join(name), body.as_bytes())?;
    }
    print!("{text}");
    println!("report in {}", args.out.display());
    Ok(ExitCode::SUCCESS)
}

fn create_dir(dir: &std::path::Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io { what: "creating", path: dir.to_path_buf(), source })
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
fn measure_in_child(global: &GlobalArgs, args: &PipelineBenchArgs, config: &Config) -> twinray::Result<Measured> {
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
