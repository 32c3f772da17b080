//! The arguments several `twinray` commands share, as clap reads them: the global flags, a
//! frame, an animation, `--alone-in`; and those of `render`, `compare` and `bench`, which the
//! helper modules `frames` and `alone` read too (every other command's sit beside its handler).

use clap::Args;
use std::path::PathBuf;
use std::sync::OnceLock;
use twinray_host::render::{FrameRange, TlasKind, TlasMode};
use twinray_host::sets::{Loader, SetSpec, ShaderSet};

pub use crate::image_args::ViewpointArgs;

/// Most timed traces a command takes: past it, a typo (an extra zero or three) would hold the
/// GPU for hours. Work over 100 rounds shows progress.
pub const MAX_RUNS: u32 = 10_000;
/// Most untimed warm-up traces.
pub const MAX_WARMUP: u32 = 10_000;
/// The most placements a command takes: each makes every pipeline afresh.
pub const MAX_PLACEMENTS: u32 = 1_000;
/// Most rays a probe case is repeated to for timing: 2^23 rays and results take 512 MiB.
pub const MAX_TIMING_RAYS: u64 = 1 << 23;

#[derive(Args, Clone)]
pub struct GlobalArgs {
    /// Enable the Khronos validation layer; its errors fail the command. `--validate=gpu` adds
    /// its GPU-assisted validation, which instruments the stages (what the installed layer
    /// checks there: docs/broken-stages.md).
    #[arg(long, global = true, value_enum, value_name = "MODE", num_args = 0..=1, require_equals = true, default_missing_value = "core")]
    pub validate: Option<ValidateMode>,
    /// Use the first ray tracing device whose name contains this text.
    #[arg(long, global = true, value_name = "NAME")]
    pub device: Option<String>,
    /// How ray tracing pipelines are made: whole, or linked from per-stage libraries
    /// [default: libraries where the device has VK_KHR_pipeline_library].
    #[arg(long, global = true, value_enum)]
    pub pipeline: Option<twinray_host::vk::context::PipelineKind>,
    /// Threads that join each pipeline creation, a deferred host operation [default: the
    /// machine's cores].
    #[arg(long, global = true, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    /// Compile every pipeline cold: no pipeline cache is read or written.
    #[arg(long, global = true, conflicts_with = "pipeline_cache")]
    pub no_pipeline_cache: bool,
    /// Folder of the pipeline caches, one file per device and driver [default:
    /// $XDG_CACHE_HOME/twinray/pipelines or ~/.cache/twinray/pipelines].
    #[arg(long, global = true, value_name = "DIR")]
    pub pipeline_cache: Option<PathBuf>,
    /// Seconds one unit of GPU work (a trace, an acceleration structure build) or one
    /// pipeline creation may take; past it the command ends with exit code 3 and a line naming
    /// what did not finish [default: 120].
    #[arg(long, global = true, value_name = "SECONDS", value_parser = parse_timeout)]
    pub gpu_timeout: Option<std::time::Duration>,
    /// Seconds the compilation of a shader crate named as a set may take; past it the build is
    /// stopped and the command ends with exit code 2 [default: 1200].
    #[arg(long, global = true, value_name = "SECONDS", value_parser = parse_timeout)]
    pub build_timeout: Option<std::time::Duration>,
    /// Leave robust buffer and image access (VK_EXT_robustness2) off: a stage that reads
    /// outside a buffer then reads what the driver gives, not zeros [default: on where the
    /// device has it].
    #[arg(long, global = true)]
    pub no_robust_access: bool,
    /// Give every mesh a bottom-level acceleration structure of its own: no consecutive meshes
    /// placed alike (a glTF mesh's primitives) share one, each a geometry of it. The same
    /// image and hit ids, more structures: a check on the sharing.
    #[arg(long, global = true)]
    pub no_shared_blases: bool,
    /// More log output (-v info, -vv debug); RUST_LOG overrides.
    #[arg(short, long, global = true, action = clap::ArgAction::Count)]
    pub verbose: u8,
    /// The folder every file a model or scene names (buffers, images, material libraries,
    /// textures, meshes, placed models) must lie in [default: the folder of the file that
    /// names it]. A file elsewhere, by an absolute path, `..` or a symbolic link, is refused.
    #[arg(long, global = true, value_name = "DIR")]
    pub asset_root: Option<PathBuf>,
    /// The time, in seconds, at which a glTF model shows its animations (each that drives
    /// nothing an earlier one drives, as glTF-Sample-Viewer plays them): each node they move
    /// placed where their keys put it then, each animation looping over its own length
    /// [default: 0, the animations' start].
    #[arg(long, global = true, value_name = "SECONDS", value_parser = parse_time)]
    pub time: Option<f32>,
    /// Frames per second at which a glTF model's animations are played as a moving scene
    /// (`--frames`, and `--frame K` where a command takes one): frame k shows it at --time
    /// plus k / FPS seconds, up to their last key [default: 24].
    #[arg(long, global = true, value_name = "FPS", value_parser = parse_fps)]
    pub fps: Option<f32>,
    /// What PNGs of radiance do with values above 1 before the sRGB encoding: clip each
    /// channel, or map it by c / (1 + c) (reinhard). EXR output and every metric stay linear.
    #[arg(long, global = true, value_enum, value_name = "MAP", default_value_t = twinray_host::util::srgb::ToneMap::Clip)]
    pub tone_map: twinray_host::util::srgb::ToneMap,
    /// The loader of this command's sets, made at its first use: after the log and every
    /// option it needs (`--build-timeout`) are in place, never while the command line is read.
    #[arg(skip)]
    pub loader: OnceLock<Loader>,
}

impl GlobalArgs {
    /// The set `spec` names, loaded: folders of sources built within `--build-timeout`, every
    /// module from disk checked.
    /// `flag` names the option that gave it, in the error of a set that does not load.
    pub fn load(&self, flag: &str, spec: &SetSpec) -> twinray_host::Result<ShaderSet> {
        self.loader().load(spec).map_err(|e| named(flag, e))
    }

    /// Each of `specs`, loaded, as `load` loads one.
    pub fn load_all(&self, flag: &str, specs: &[SetSpec]) -> twinray_host::Result<Vec<ShaderSet>> {
        self.loader().load_all(specs).map_err(|e| named(flag, e))
    }

    /// This command's loader of sets.
    pub fn loader(&self) -> &Loader {
        self.loader.get_or_init(|| Loader::new(self.build_timeout))
    }

    /// The flags that gave these options, for a `twinray` child process (`view`'s renders).
    pub fn forwarded(&self) -> Vec<String> {
        let mut args = Vec::new();
        match self.validate {
            Some(ValidateMode::Core) => args.push("--validate".into()),
            Some(ValidateMode::Gpu) => args.push("--validate=gpu".into()),
            None => {}
        }
        let mut pair = |flag: &str, value: Option<String>| args.extend(value.map(|v| format!("{flag}={v}")));
        pair("--device", self.device.clone());
        pair(
            "--pipeline",
            self.pipeline.and_then(|p| clap::ValueEnum::to_possible_value(&p).map(|v| v.get_name().to_string())),
        );
        pair("--threads", self.threads.map(|n| n.to_string()));
        pair("--pipeline-cache", self.pipeline_cache.as_ref().map(|p| p.display().to_string()));
        pair("--gpu-timeout", self.gpu_timeout.map(|t| t.as_secs_f64().to_string()));
        pair("--build-timeout", self.build_timeout.map(|t| t.as_secs_f64().to_string()));
        pair("--asset-root", self.asset_root.as_ref().map(|p| p.display().to_string()));
        pair("--time", self.time.map(|t| t.to_string()));
        pair("--tone-map", clap::ValueEnum::to_possible_value(&self.tone_map).map(|v| v.get_name().to_string()));
        let switches = [
            (self.no_pipeline_cache, "--no-pipeline-cache"),
            (self.no_robust_access, "--no-robust-access"),
            (self.no_shared_blases, "--no-shared-blases"),
        ];
        args.extend(switches.into_iter().filter(|(on, _)| *on).map(|(_, flag)| flag.to_string()));
        args
    }
}

/// `e` said of the option `flag`, its kind kept (an input error stays one: exit 2).
fn named(flag: &str, e: twinray_host::Error) -> twinray_host::Error {
    match e {
        twinray_host::Error::Input(message) => twinray_host::Error::Input(format!("{flag}: {message}")),
        other => other,
    }
}

/// What `--validate` turns on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ValidateMode {
    /// The layer's checks of every Vulkan call.
    Core,
    /// Those, and GPU-assisted validation of the stages.
    Gpu,
}

/// A GPU timeout: seconds, more than 0 and at most a day.
fn parse_time(text: &str) -> Result<f32, String> {
    let seconds: f32 = text.trim().parse().map_err(|_| format!("{text:?} is not a number of seconds"))?;
    if !(seconds.is_finite() && seconds >= 0.0) {
        return Err(format!("{seconds} is not a time in seconds (0 or more)"));
    }
    Ok(seconds)
}

fn parse_fps(text: &str) -> Result<f32, String> {
    let fps: f32 = text.trim().parse().map_err(|_| format!("{text:?} is not a number of frames per second"))?;
    let most = twinray_host::scene::animation::MAX_FPS;
    if !(fps.is_finite() && fps > 0.0 && fps <= most) {
        return Err(format!("{fps} frames per second is not in (0, {most}]"));
    }
    Ok(fps)
}

fn parse_timeout(text: &str) -> Result<std::time::Duration, String> {
    let seconds: f64 = text.trim().parse().map_err(|_| format!("{text:?} is not a number of seconds"))?;
    if !(seconds > 0.0 && seconds <= 86_400.0) {
        return Err(format!("{seconds} s is not in (0, 86400]"));
    }
    Ok(std::time::Duration::from_secs_f64(seconds))
}

#[derive(Args, Clone)]
pub struct FrameArgs {
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// Timed traces per placement; the median GPU time is reported [default: render 1, compare 10].
    #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_RUNS)))]
    pub runs: Option<u32>,
    /// Independent placements: each set's pipeline, SBT and descriptors made afresh, in an order
    /// of their own, each giving one median per set; a ratio's 95% interval is taken over them
    /// [default: render 1, compare 6].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_PLACEMENTS)))]
    pub placements: Option<u32>,
    /// Untimed traces before the timed ones [default: render 0, compare 2].
    #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_WARMUP)))]
    pub warmup: Option<u32>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// What `render` and `compare` take for moving scenes.
#[derive(Args, Clone)]
pub struct AnimationArgs {
    /// Frames of an animated scene: A..B (B excluded), A..=B, A, or all. Without it, frame 0
    /// renders as a still image.
    #[arg(long, value_name = "RANGE")]
    pub frames: Option<FrameRange>,
    /// How the TLAS follows moving objects: rebuilt (preferring fast trace), rebuilt preferring
    /// fast build, or updated in place.
    #[arg(long, value_enum, default_value = "update")]
    pub tlas: TlasKind,
    /// With --tlas update: a full rebuild every N frames of the sequence (0: the first only).
    #[arg(long, value_name = "N", default_value_t = twinray_host::render::DEFAULT_TLAS.rebuild_every)]
    pub rebuild_every: u32,
}

impl AnimationArgs {
    pub fn mode(&self) -> TlasMode {
        TlasMode { kind: self.tlas, rebuild_every: self.rebuild_every }
    }
}

/// Where `--processes` times each set alone (bench, compare, bisect).
#[derive(Args)]
pub struct AloneArgs {
    /// With --processes: what each set is timed alone in. `processes`: child processes;
    /// `devices`: a fresh Vulkan device each, in this process, which times a set as a child
    /// process starting at the same place does, in half the time (docs/measuring.md).
    #[arg(long, value_enum, default_value = "processes", requires = "processes")]
    pub alone_in: twinray::bench::AloneIn,
}

#[derive(Args)]
pub struct RenderArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    pub scene: Option<String>,
    /// Shader set: rust, glsl, or a mix such as rust,intersection=glsl.
    #[arg(long, default_value = "rust")]
    pub shaders: SetSpec,
    /// Output PNG file; with --frames, an animated PNG, each frame also as STEM-NNNN.png beside it.
    #[arg(long, default_value = "render.png")]
    pub out: PathBuf,
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub viewpoint: ViewpointArgs,
    #[command(flatten)]
    pub animation: AnimationArgs,
}

#[derive(Args)]
pub struct CompareArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    pub scene: Option<String>,
    /// First shader set.
    #[arg(long, default_value = "rust")]
    pub a: SetSpec,
    /// Second shader set.
    #[arg(long, default_value = "glsl")]
    pub b: SetSpec,
    /// Directory for a.png, b.png and diff.png (created if missing); with --frames, those of
    /// the worst frame, and diff-NNNN.png of every frame outside the tolerance.
    #[arg(long, default_value = "compare")]
    pub out_dir: PathBuf,
    #[command(flatten)]
    pub frame: FrameArgs,
    #[command(flatten)]
    pub viewpoint: ViewpointArgs,
    #[command(flatten)]
    pub animation: AnimationArgs,
    /// Time each set alone in N processes of its own (child `twinray bench` runs of the scene,
    /// each with --placements placements), in rounds of alternating order, and take
    /// the ratio's interval over the rounds, as `bench --processes` does. 0: both sets timed in
    /// this process. Not with --frames, --frame, --eye or --look-at (the child takes none).
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=64))]
    pub processes: u32,
    #[command(flatten)]
    pub alone: AloneArgs,
}

#[derive(Args)]
pub struct BenchArgs {
    /// Scene files, models (.gltf, .glb, .obj) or built-in names [default: every built-in scene].
    pub scenes: Vec<String>,
    /// Shader sets, comma-separated; a STAGE=LANGUAGE item changes the set before it, so
    /// "rust,glsl,rust,intersection=glsl" is three sets.
    #[arg(long, default_value = "rust,glsl")]
    pub sets: String,
    /// Samples per pixel to measure, comma-separated squares up to 256.
    #[arg(long, default_value = "1,4,16,64")]
    pub spp: String,
    /// Output folder (created if missing).
    #[arg(long, default_value = "bench/out")]
    pub out: PathBuf,
    /// Image width for every scene [default: each scene's].
    #[arg(long, requires = "height")]
    pub width: Option<u32>,
    /// Image height for every scene [default: each scene's].
    #[arg(long, requires = "width")]
    pub height: Option<u32>,
    /// Timed traces per measurement and placement (at least 10).
    #[arg(long, default_value_t = 10, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_RUNS)))]
    pub runs: u32,
    /// Untimed traces before them.
    #[arg(long, default_value_t = 2, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_WARMUP)))]
    pub warmup: u32,
    /// Independent placements of every set's pipeline per measurement (see `compare
    /// --placements`); each set's ratio to the first set has a 95% interval over them.
    #[arg(long, default_value_t = twinray_host::render::DEFAULT_PLACEMENTS, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_PLACEMENTS)))]
    pub placements: u32,
    /// Also time a salted copy of the first set (the same code, built apart): the null
    /// control, whose ratio to the first set has an interval that should contain 1.
    #[arg(long)]
    pub null: bool,
    /// Samples per pixel of the references.
    #[arg(long, default_value_t = 1024)]
    pub reference_spp: u32,
    /// Shader set that renders the references [default: the second of --sets, the other of a
    /// pair; the first where --sets has one].
    #[arg(long)]
    pub reference_set: Option<SetSpec>,
    /// Reference cache folder [default: as for `twinray reference`].
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Shadow samples per rect light for the stratified-against-random study of soft-shadow
    /// scenes, comma-separated squares up to 256 ("none": no study).
    #[arg(long, default_value = "1,4,16,64")]
    pub shadow_spp: String,
    /// Probe cases for the robust-against-naive intersection study ("none": no study)
    /// [default: probes/stability, a checkout's hard cases, where there is one].
    #[arg(long)]
    pub probes: Option<PathBuf>,
    /// Time each probe case over its rays repeated up to at least this many.
    #[arg(long, default_value_t = 1_048_576, value_parser = clap::value_parser!(u64).range(0..=MAX_TIMING_RAYS))]
    pub timing_rays: u64,
    /// Which renders to keep as PNG files with their FLIP maps (references are always kept).
    #[arg(long, value_enum, default_value = "all")]
    pub images: twinray::bench::Images,
    /// Time each set alone in N processes of its own (each with --placements placements), in
    /// rounds ordered as the rows of a Williams design (for three sets a multiple of 6 balances
    /// every set's position), and take every ratio's interval over the rounds:
    /// sets timed in one process can settle into a regime that favours one of them
    /// (docs/measuring.md). 0: every set timed in this process.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=64))]
    pub processes: u32,
    #[command(flatten)]
    pub alone: AloneArgs,
    /// Make the spacers of placement N first, N+1 next, and so on (see `compare
    /// --placements`): where in the layouts the placements start. With --processes every
    /// process starts N further on, so that a second run times places the first did not.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_PLACEMENTS) * 64))]
    pub first_placement: u32,
}
