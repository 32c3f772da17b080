//! The `twinray` command: `info`, `render` and `compare`. Bad input exits with code 2 and a
//! one-line error; a failed comparison exits with 1.

mod commands;

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;
use twinray::ShaderSet;

#[derive(Parser)]
#[command(
    name = "twinray",
    version,
    about = "Render ray tracing scenes with Rust or GLSL shader sets (or any per-stage mix) and compare them."
)]
struct Cli {
    #[command(flatten)]
    global: GlobalArgs,
    #[command(subcommand)]
    command: Command,
}

#[derive(Args, Clone)]
pub struct GlobalArgs {
    /// Enable the Khronos validation layer; its errors fail the command.
    #[arg(long, global = true)]
    validate: bool,
    /// Use the first ray tracing device whose name contains this text.
    #[arg(long, global = true, value_name = "NAME")]
    device: Option<String>,
    /// More log output (-v info, -vv debug); RUST_LOG overrides.
    #[arg(short, long, global = true, action = clap::ArgAction::Count)]
    verbose: u8,
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
    /// Render a scene with one shader set to a PNG.
    Render(RenderArgs),
    /// Render a scene with two shader sets and report how they differ in image and GPU time.
    Compare(CompareArgs),
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
}

/// Image size and timing options shared by `render` and `compare`.
#[derive(Args, Clone)]
pub struct FrameArgs {
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    height: Option<u32>,
    /// Timed traces; the median GPU time is reported [default: render 1, compare 10].
    #[arg(long)]
    runs: Option<u32>,
    /// Untimed traces before the timed ones [default: render 0, compare 2].
    #[arg(long)]
    warmup: Option<u32>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
pub struct RenderArgs {
    /// Scene file, or the name of a built-in scene [default: spheres].
    scene: Option<String>,
    /// Shader set: rust, glsl, or a mix such as rust,intersection=glsl.
    #[arg(long, default_value = "rust")]
    shaders: ShaderSet,
    /// Output PNG file.
    #[arg(long, default_value = "render.png")]
    out: PathBuf,
    #[command(flatten)]
    frame: FrameArgs,
}

#[derive(Args)]
pub struct CompareArgs {
    /// Scene file, or the name of a built-in scene [default: spheres].
    scene: Option<String>,
    /// First shader set.
    #[arg(long, default_value = "rust")]
    a: ShaderSet,
    /// Second shader set.
    #[arg(long, default_value = "glsl")]
    b: ShaderSet,
    /// Directory for a.png, b.png and diff.png (created if missing).
    #[arg(long, default_value = "compare")]
    out_dir: PathBuf,
    #[command(flatten)]
    frame: FrameArgs,
}

#[derive(Args)]
pub struct ProbeArgs {
    /// Probe case file (TOML; see docs/probe-format.md).
    case: PathBuf,
    /// Shader set: rust, glsl, or a mix such as rust,intersection=glsl.
    #[arg(long, default_value = "rust")]
    shaders: ShaderSet,
    /// Intersection formula for every shape that has both: robust, or naive (the textbook
    /// forms kept on purpose) [default: as the scene says].
    #[arg(long, value_parser = ["robust", "naive"])]
    formula: Option<String>,
    /// Timed passes over all the rays; the median is reported.
    #[arg(long, default_value_t = 10)]
    runs: u32,
    /// Untimed passes before the timed ones.
    #[arg(long, default_value_t = 2)]
    warmup: u32,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
pub struct StabilityArgs {
    /// Folder of probe cases.
    #[arg(long, default_value = "probes/stability")]
    dir: PathBuf,
    /// Shader sets, comma-separated with ';' between sets, e.g. "rust;glsl".
    #[arg(long, default_value = "rust;glsl")]
    sets: String,
    /// Timed passes per case, set and formula.
    #[arg(long, default_value_t = 5)]
    runs: u32,
    /// Untimed passes before the timed ones.
    #[arg(long, default_value_t = 1)]
    warmup: u32,
    /// Time each case over its rays repeated up to at least this many (0: the case's rays).
    #[arg(long, default_value_t = 262_144)]
    timing_rays: usize,
    /// Print one JSON array of rows.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
pub struct ReferenceArgs {
    /// Scene file, or the name of a built-in scene [default: spheres].
    scene: Option<String>,
    /// Samples per pixel: a square up to 256, or a multiple of 256.
    #[arg(long, default_value_t = 1024)]
    spp: u32,
    /// Shader set that renders it.
    #[arg(long, default_value = "glsl")]
    shaders: ShaderSet,
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    height: Option<u32>,
    /// Cache folder [default: $XDG_CACHE_HOME/twinray/references or ~/.cache/twinray/references].
    #[arg(long)]
    cache: Option<PathBuf>,
    /// Also write the reference as an 8-bit PNG.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
pub struct BenchArgs {
    /// Scene files or built-in names [default: every built-in scene].
    scenes: Vec<String>,
    /// Shader sets, comma-separated; a STAGE=LANGUAGE item changes the set before it, so
    /// "rust,glsl,rust,intersection=glsl" is three sets.
    #[arg(long, default_value = "rust,glsl")]
    sets: String,
    /// Samples per pixel to measure, comma-separated squares up to 256.
    #[arg(long, default_value = "1,4,16,64")]
    spp: String,
    /// Output folder (created if missing).
    #[arg(long, default_value = "bench/out")]
    out: PathBuf,
    /// Image width for every scene [default: each scene's].
    #[arg(long, requires = "height")]
    width: Option<u32>,
    /// Image height for every scene [default: each scene's].
    #[arg(long, requires = "width")]
    height: Option<u32>,
    /// Timed traces per measurement (at least 10).
    #[arg(long, default_value_t = 10)]
    runs: u32,
    /// Untimed traces before them.
    #[arg(long, default_value_t = 2)]
    warmup: u32,
    /// Samples per pixel of the references.
    #[arg(long, default_value_t = 1024)]
    reference_spp: u32,
    /// Shader set that renders the references.
    #[arg(long, default_value = "glsl")]
    reference_set: ShaderSet,
    /// Reference cache folder [default: as for `twinray reference`].
    #[arg(long)]
    cache: Option<PathBuf>,
    /// Shadow samples per rect light for the stratified-against-random study of soft-shadow
    /// scenes, comma-separated squares up to 256 ("none": no study).
    #[arg(long, default_value = "1,4,16,64")]
    shadow_spp: String,
    /// Probe cases for the robust-against-naive intersection study ("none": no study).
    #[arg(long, default_value = "probes/stability")]
    probes: PathBuf,
    /// Time each probe case over its rays repeated up to at least this many.
    #[arg(long, default_value_t = 1_048_576)]
    timing_rays: usize,
    /// Which renders to keep as PNG files with their FLIP maps (references are always kept).
    #[arg(long, value_enum, default_value = "all")]
    images: twinray::bench::Images,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
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
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or(level)).init();
    let result = match cli.command {
        Command::Info { json } => commands::info(&cli.global, json),
        Command::Scenes { json } => commands::scenes(json),
        Command::Render(args) => commands::render(&cli.global, args),
        Command::Compare(args) => commands::compare(&cli.global, args),
        Command::Probe(args) => commands::probe(&cli.global, args),
        Command::Stability(args) => commands::stability(&cli.global, args),
        Command::Reference(args) => commands::reference(&cli.global, args),
        Command::Bench(args) => commands::bench(&cli.global, args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            let input = e.downcast_ref::<twinray::Error>().is_some_and(twinray::Error::is_input);
            ExitCode::from(if input { 2 } else { 1 })
        }
    }
}
