//! The `twinray` command: one module per subcommand, named after it (`render`, `compare`,
//! `bench`, `pipeline-bench` in `pipeline_bench`, ...), its arguments beside its handler but
//! where a helper module takes them too (`render`'s, `compare`'s and `bench`'s are in `args`,
//! as `frames` and `alone` read them):
//! `info`, `scenes`, `new`, `build`, `watch`, `render`, `compare`, `bisect`, `explain`, `view`,
//! `inspect`, `probe`, `stability`, `reference`, `bench`, `animate-bench`, `pipeline-bench`,
//! `stage-bench`, `places`, `crosscheck`. What several share: `args` (global flags, frame, animation and
//! `--alone-in` arguments), `image_args` (the viewpoint), `session` (the context and render
//! options), `frames` (moving scenes' frames for `render` and `compare`), `alone` (sets timed
//! in processes or devices of their own).
//!
//! Bad input exits with code 2 and a one-line error; a failed comparison exits with 1; GPU
//! work that did not finish in time (or a lost device) with 3; a crash (a fatal signal,
//! usually in the driver) with 4.

mod animate_bench;
mod args;
mod bench;
mod bisect;
mod build;
mod compare;
mod crosscheck;
mod explain;
mod frames;
mod image_args;
mod info;
mod inspect;
mod new;
mod pipeline_bench;
mod places;
mod probe;
mod reference;
mod render;
mod scenes;
mod session;
mod stability;
mod stage_bench;
mod timed_alone;
mod view;
mod watch;

use animate_bench::AnimateBenchArgs;
use args::BenchArgs;
use args::CompareArgs;
use args::GlobalArgs;
use args::RenderArgs;
use bisect::BisectArgs;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use explain::ExplainArgs;
use pipeline_bench::PipelineBenchArgs;
use probe::ProbeArgs;
use reference::ReferenceArgs;
use stability::StabilityArgs;
use stage_bench::StageBenchArgs;
use std::process::ExitCode;
use twinray_host::util::{activity, crash, watchdog};
use view::ViewArgs;

#[derive(Parser)]
#[command(
    name = "twinray",
    version,
    about = "Render ray tracing scenes with Rust or GLSL shader sets (or any per-stage mix) and compare them.",
    // A flag given twice takes its last value: `cargo xtask watch -- --runs 10` follows the
    // `--runs 1` watch gives by default.
    args_override_self = true
)]
struct Cli {
    #[command(flatten)]
    global: GlobalArgs,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Show the Vulkan device twinray would use: driver and ray tracing properties.
    Info {
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// List the built-in scenes, and every kind of shape, material and light a scene file can use.
    Scenes {
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// Write a shader crate of your own in a new folder: the built-in Rust stages, the contract
    /// (twinray-shared) and the toolchain file; with --glsl, the GLSL twins too.
    New(new::NewArgs),
    /// Build a folder of stage sources (a shader crate, GLSL twins) into a set; every command
    /// that takes a set builds the folder it names the same way.
    Build(build::BuildArgs),
    /// Compare a folder of stage sources with a set on every save: rebuilt, compared, and the
    /// verdict printed with the time from the save to it.
    Watch(watch::WatchArgs),
    /// Render a scene with one shader set to a PNG; with --frames, a moving scene's frames.
    Render(RenderArgs),
    /// Render a scene with two shader sets and report how they differ in image and GPU time;
    /// with --frames, on every frame of a moving scene.
    Compare(CompareArgs),
    /// Which stage makes two sets differ: renders A, B, and every set that takes one stage (or,
    /// where none explains it, two) from the other, and reports each stage's share of the image
    /// and time differences. Exit code 0 when every difference was pinned on a stage or pair.
    Bisect(BisectArgs),
    /// Every ray one pixel traces, in each set and in the f64 reference, and the first place
    /// they part: which sample, which ray, which set is wrong and which stage made it so.
    Explain(ExplainArgs),
    /// A live page in the browser: A and B side by side, as a wipe or flipped, and their
    /// difference, re-rendered on every save of a shader source, set folder or the scene;
    /// click a pixel to explain it. Serves 127.0.0.1 and prints the address.
    View(ViewArgs),
    /// What each stage keeps alive across each traceRay and executeCallable call (computed on
    /// its SPIR-V), beside the stack size the driver gives it; `--a`/`--b` put two sets side by
    /// side. Works on a set from disk or one .spv file.
    Inspect(inspect::InspectArgs),
    /// Trace a probe case's rays with a shader set and judge each against the f64 reference.
    Probe(ProbeArgs),
    /// The hard-case suite: every probe case of a folder, per set and formula, against the
    /// reference and the cases' targets.
    Stability(StabilityArgs),
    /// Render (or read from the cache) a scene's converged reference image.
    Reference(ReferenceArgs),
    /// Speed against error: per scene, set and samples per pixel, GPU time, rays per second and
    /// error against a converged reference; writes tables, plots and index.html.
    Bench(BenchArgs),
    /// Moving scenes: per frame, GPU time of the TLAS work for each mode (rebuild, fast-build,
    /// update) and of the trace as objects drift, at several instance counts; writes tables,
    /// plots and index.html.
    AnimateBench(AnimateBenchArgs),
    /// Pipeline creation time: both sets and every per-stage mix, whole or linked from
    /// libraries, joined by 1 or N threads, from a cold or a warm pipeline cache.
    PipelineBench(PipelineBenchArgs),
    /// What a stage kind or tracing method costs: scenes in variants (opaque, cutouts with
    /// any-hit, shadows by traceRay or ray queries), timed against the first variant, with
    /// each image against that variant's.
    StageBench(StageBenchArgs),
    /// What a place changes on this device: each set timed over many places with its code, its
    /// SBT or the scene's buffers moved, one at a time, and with nothing moved.
    Places(places::PlacesArgs),
    /// twinray's converged references against Mitsuba 3's renders of the same scenes, in linear
    /// radiance (docs/shading-model.md); `cargo xtask crosscheck` sets up Mitsuba and runs it.
    Crosscheck(crosscheck::CrosscheckArgs),
}

/// Image size and timing options shared by `render` and `compare`.
/// Longest error line printed.
const MAX_ERROR_CHARS: usize = 2000;

fn main() -> ExitCode {
    let parsed = Cli::command().try_get_matches().and_then(|m| Ok((Cli::from_arg_matches(&m)?, m)));
    let (cli, matches) = match parsed {
        Ok(parsed) => parsed,
        Err(e) if !e.use_stderr() => {
            // --help and --version: clap's own output, exit 0.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            // Usage errors in one line (clap adds usage and tips below the first).
            let text = e.render().to_string();
            eprintln!("{} (see --help)", text.lines().next().unwrap_or("error: invalid arguments"));
            return ExitCode::from(2);
        }
    };
    let level = match cli.global.verbose {
        0 => "warn",
        1 => "info",
        _ => "debug",
    };
    init_logging(cli.global.verbose, level);
    session::show_progress();
    crash::report_crashes();
    crash::quiet_caught_panics();
    let _command = activity::doing(format!("twinray {}", matches.subcommand_name().unwrap_or_default()));
    twinray_host::util::srgb::set_tone_map(cli.global.tone_map);
    twinray_host::scene::gltf::set_playing(twinray_host::scene::gltf::Playing {
        time: cli.global.time.unwrap_or(0.0),
        fps: cli.global.fps.unwrap_or(twinray_host::scene::gltf::DEFAULT_FPS),
    });
    if let Some(Err(e)) = cli.global.asset_root.as_deref().map(twinray_host::util::input::set_asset_root) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    let result = match cli.command {
        Command::Info { json } => info::info(&cli.global, json),
        Command::Scenes { json } => scenes::scenes(json),
        Command::New(args) => new::new(args),
        Command::Build(args) => build::build(&cli.global, args),
        Command::Watch(args) => watch::watch(&cli.global, args),
        Command::Render(args) => render::render(&cli.global, args),
        Command::Compare(args) => compare::compare(&cli.global, args),
        Command::Bisect(args) => bisect::bisect(&cli.global, args),
        Command::Explain(args) => explain::explain(&cli.global, args),
        Command::View(args) => view::view(&cli.global, args),
        Command::Inspect(args) => inspect::inspect(&cli.global, args),
        Command::Probe(args) => probe::probe(&cli.global, args),
        Command::Stability(args) => stability::stability(&cli.global, args),
        Command::Reference(args) => reference::reference(&cli.global, args),
        Command::Bench(args) => bench::bench(&cli.global, args),
        Command::AnimateBench(args) => animate_bench::animate_bench(&cli.global, args),
        Command::PipelineBench(args) => pipeline_bench::pipeline_bench(&cli.global, args),
        Command::StageBench(args) => stage_bench::stage_bench(&cli.global, args),
        Command::Places(args) => places::places(&cli.global, args),
        Command::Crosscheck(args) => crosscheck::crosscheck(&cli.global, args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            // One line, and not a megabyte one when a hostile input is echoed in it.
            let text = format!("{e:#}").replace('\n', " ");
            let short: String = text.chars().take(MAX_ERROR_CHARS).collect();
            let more = if short.len() < text.len() { "..." } else { "" };
            eprintln!("error: {short}{more}");
            let error = e.downcast_ref::<twinray_host::Error>();
            if error.is_some_and(twinray_host::Error::is_stalled) {
                // The GPU (or a lavapipe thread) may still be running the stage: exit's
                // handlers would wait for it, so end at once.
                use std::io::Write;
                let _ = std::io::stdout().flush();
                // SAFETY: _exit ends the process; nothing after it runs.
                unsafe { libc::_exit(watchdog::EXIT_STALLED) }
            }
            ExitCode::from(if error.is_some_and(twinray_host::Error::is_input) { 2 } else { 1 })
        }
    }
}

/// Warnings and errors read as a tool's, one `warning: ...` line each; with `-v` or `RUST_LOG`,
/// the user asked for logs, and every record carries its time, level and module.
fn init_logging(verbose: u8, level: &str) {
    let mut builder = env_logger::Builder::from_env(env_logger::Env::default().default_filter_or(level));
    if verbose == 0 && std::env::var_os("RUST_LOG").is_none() {
        builder.format(|out, record| {
            use std::io::Write;
            let label = match record.level() {
                log::Level::Error => "error",
                log::Level::Warn => "warning",
                log::Level::Info => "info",
                _ => "debug",
            };
            writeln!(out, "{label}: {}", record.args())
        });
    }
    builder.init();
}
