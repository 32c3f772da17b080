//! `twinray stage-bench`: what stage kinds and tracing methods cost.

use crate::args::{FrameArgs, GlobalArgs};
use crate::session::{context, create_dir, render_options, COMPARE_TRACES};
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::Scene;

/// One placement per render: `stage-bench`'s rounds are its placements.
const STAGE_TRACES: (u32, u32, u32) = (COMPARE_TRACES.0, COMPARE_TRACES.1, 1);

pub fn stage_bench(global: &GlobalArgs, args: StageBenchArgs) -> Result<ExitCode> {
    use twinray::bench::stages::{run, table, StagePlan, Variant};
    let scenes = args.scenes.iter().map(|name| Scene::load(Some(name))).collect::<Result<Vec<_>, _>>()?;
    let variants = Variant::parse_list(&args.variants)?;
    let sets = global.load_all("--sets", &twinray_host::sets::parse_specs(&args.sets)?)?;
    if args.frame.placements.is_some() {
        let why =
            "stage-bench: each round makes every pipeline afresh (a placement); give --rounds instead of --placements";
        return Err(twinray_host::Error::Input(why.into()).into());
    }
    for scene in &scenes {
        render_options(scene, &args.frame, STAGE_TRACES)?;
    }
    create_dir(&args.out)?;
    let ctx = context(global)?;
    let timer = args.alone.then(|| crate::timed_alone::stage_timer(global, &args.frame, args.scenes.clone()));
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
        twinray_host::util::output::write_atomically(&args.out.join(name), body.as_bytes())?;
    }
    print!("{text}");
    println!("report in {}", args.out.display());
    Ok(ExitCode::SUCCESS)
}

#[derive(Args)]
pub struct StageBenchArgs {
    /// Built-in scene names or scene files [default: cutout and showcase].
    #[arg(default_values_t = ["cutout".to_string(), "showcase".to_string()])]
    pub scenes: Vec<String>,
    /// Variants, comma-separated; each is timed against the first: as-is, opaque (cutouts made
    /// diffuse), solid-cutouts (any-hit without holes), trace-shadows, query-shadows,
    /// inline-materials, callable-materials, per-shape-hits, per-material-hits, pipeline,
    /// compute (the compute renderer with ray queries).
    #[arg(long, default_value = "opaque,solid-cutouts,as-is")]
    pub variants: String,
    /// Shader sets, as for `bench --sets`; each variant is also timed against the first set.
    #[arg(long, default_value = "rust,glsl")]
    pub sets: String,
    /// Rounds: every variant and set renders once per round, in an order rotated each round.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub rounds: u32,
    /// Time each round's render of each variant and set alone in a fresh process (a child
    /// `twinray stage-bench`), as `bench --processes` does; the renders here give the images.
    #[arg(long)]
    pub alone: bool,
    /// Number the rounds from N: each round makes the spacers of a placement of its own
    /// (see `compare --placements`), so the rounds time at different places; --alone gives
    /// each child its round. Give it to repeat a round.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=100))]
    pub first_round: u32,
    /// Image size and trace counts per render [default: each scene's size, 10 timed traces
    /// after 2 untimed].
    #[command(flatten)]
    pub frame: FrameArgs,
    /// Output folder for table.md and results.json (created if missing).
    #[arg(long, default_value = "bench/out-stages")]
    pub out: PathBuf,
}
