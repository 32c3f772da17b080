//! `--processes N` (`twinray bench`, `compare` and `bisect`): one set timed alone, by a child
//! `twinray bench` of that set only, with the parent's global flags and timing settings, whose
//! placement medians are read back from its results.json; or, with `--alone-in devices`, on a
//! fresh Vulkan device in this process (see `twinray::bench::Isolation`).

use crate::args::BenchArgs;
use crate::args::GlobalArgs;
use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;
use twinray::bench::stages::Variant;
use twinray::bench::{AloneIn, TimeAlone};
use twinray_host::render::RenderOptions;
use twinray_host::sets::{Loader, ShaderSet};
use twinray_host::Error;

/// Child folders made so far by this process: each child writes into a fresh one.
static CHILDREN: AtomicU32 = AtomicU32::new(0);

/// The parent's settings every child times with.
pub struct ChildSettings {
    pub runs: u32,
    pub warmup: u32,
    pub placements: u32,
    pub size: Option<(u32, u32)>,
    /// The child bench's reference image: its error figures go unread, so `compare` asks for
    /// the cheapest one; `bench` hands on its own, which its cache already holds.
    pub reference_spp: u32,
    pub reference_set: String,
    pub cache: PathBuf,
}

impl ChildSettings {
    pub fn of_bench(args: &BenchArgs, reference_set: &ShaderSet, cache: PathBuf) -> Self {
        ChildSettings {
            runs: args.runs,
            warmup: args.warmup,
            placements: args.placements,
            size: args.width.zip(args.height),
            reference_spp: args.reference_spp,
            reference_set: reference_set.to_string(),
            cache,
        }
    }
}

/// `--processes N` of `compare` and `bisect` (none for 0), and the folder its children keep
/// their (1 spp, unread) reference in, for the caller to remove.
pub fn for_scene(
    global: &GlobalArgs,
    scene: String,
    opts: &twinray_host::render::RenderOptions,
    reference_set: &ShaderSet,
    (processes, on): (u32, AloneIn),
) -> (Option<twinray::bench::Isolation>, PathBuf) {
    let cache = std::env::temp_dir().join(format!("twinray-scene-alone-{}", std::process::id()));
    let settings = ChildSettings {
        runs: opts.runs,
        warmup: opts.warmup,
        placements: opts.placements,
        size: Some((opts.width, opts.height)),
        reference_spp: 1,
        reference_set: reference_set.to_string(),
        cache: cache.clone(),
    };
    let time_alone = time_alone(global, settings, vec![scene], on);
    let placements = opts.placements;
    let first = opts.first_placement;
    let isolation = twinray::bench::Isolation { processes, placements, first, alone_in: on, time_alone };
    ((processes > 0).then_some(isolation), cache)
}

/// Each process is a `twinray bench`, whose floor for `--runs` is 10.
pub fn check_runs(processes: u32, runs: u32) -> Result<(), Error> {
    if processes > 0 && runs < 10 {
        let message =
            format!("--processes: each process is a `twinray bench`, which needs --runs of at least 10 (got {runs})");
        return Err(Error::Input(message));
    }
    Ok(())
}

/// `bench`'s timer of a set alone: in a child process ([`timer`]), or on a fresh Vulkan device
/// in this process ([`device_timer`]).
pub fn time_alone(global: &GlobalArgs, settings: ChildSettings, scenes: Vec<String>, on: AloneIn) -> Arc<TimeAlone> {
    match on {
        AloneIn::Processes => Arc::new(timer(global, settings, scenes)),
        AloneIn::Devices => Arc::new(device_timer(global, settings, scenes)),
    }
}

/// A set timed alone as a child process would time it, on a fresh Vulkan device (context,
/// upload, outputs) in this process: on the H100 each of 12 such devices timed its set within
/// 0.2% of the child process that started at the same place, in half the time
/// (bench/reports/placement/runs/alone-in-devices.tar.xz).
fn device_timer(
    global: &GlobalArgs,
    settings: ChildSettings,
    scenes: Vec<String>,
) -> impl Fn(usize, u32, &ShaderSet, u32) -> twinray_host::Result<Vec<f64>> + Send + Sync + 'static {
    let options = crate::session::options(global);
    move |scene, spp, set, first| {
        let start = std::time::Instant::now();
        let ctx = twinray_host::vk::context::Context::new(&options)?;
        let made_ms = start.elapsed().as_secs_f64() * 1e3;
        let mut loaded = twinray_host::scene::Scene::load(Some(&scenes[scene]))?;
        let loaded_ms = start.elapsed().as_secs_f64() * 1e3;
        loaded.file.image.samples = twinray::bench::side_of(spp)?;
        let image = &loaded.file.image;
        let (width, height) = settings.size.unwrap_or((image.width, image.height));
        let (warmup, runs, placements) = (settings.warmup, settings.runs, settings.placements);
        let opts = RenderOptions { width, height, warmup, runs, placements, first_placement: first };
        let out = twinray_host::render_sets(&ctx, &loaded, std::slice::from_ref(set), &opts)?;
        let total_ms = start.elapsed().as_secs_f64() * 1e3;
        log::debug!("{set} alone on a device from place {first}: device {made_ms:.0} ms, scene loaded at {loaded_ms:.0} ms, timed by {total_ms:.0} ms");
        Ok(out[0].placements.median_ms.clone())
    }
}

/// The timer `bench`, `compare` and `bisect` call per scene (an index into `scenes`, as given on the
/// command line), sample count, set and first placement.
pub fn timer(
    global: &GlobalArgs,
    settings: ChildSettings,
    scenes: Vec<String>,
) -> impl Fn(usize, u32, &ShaderSet, u32) -> twinray_host::Result<Vec<f64>> + Send + Sync + 'static {
    let exe = std::env::current_exe().map_err(|e| e.to_string());
    let loader = global.loader().clone();
    let mut common = global.forwarded();
    common.push("bench".into());
    let flags = [
        ("--runs", settings.runs.to_string()),
        ("--warmup", settings.warmup.to_string()),
        ("--placements", settings.placements.to_string()),
        ("--reference-spp", settings.reference_spp.to_string()),
        ("--reference-set", settings.reference_set),
        ("--cache", settings.cache.display().to_string()),
        ("--shadow-spp", "none".into()),
        ("--probes", "none".into()),
        ("--images", "none".into()),
    ];
    common.extend(flags.into_iter().flat_map(|(flag, value)| [flag.to_string(), value]));
    if let Some((w, h)) = settings.size {
        common.extend(["--width".into(), w.to_string(), "--height".into(), h.to_string()]);
    }
    move |scene, spp, set, first| {
        let times = child_set(&loader, set).and_then(|text| {
            let which = [scenes[scene].clone(), "--sets".into(), text, "--spp".into(), spp.to_string()];
            let args = [&common[..], &which[..], &["--first-placement".into(), first.to_string()]];
            let results = child_results(&exe, &args.concat())?;
            said_it_timed(&results, "first_placement", first)?;
            let times = results["rows"][0]["placements"]["median_ms"].as_array();
            let times: Vec<f64> = times.map_or(Vec::new(), |a| a.iter().filter_map(|v| v.as_f64()).collect());
            Some(times).filter(|t| !t.is_empty()).ok_or_else(|| no_times("bench"))
        });
        times.map_err(|e| Error::Unsupported(format!("timing {set} alone on {} at {spp} spp: {e}", scenes[scene])))
    }
}

/// The timer `stage-bench --alone` calls per scene (an index into `scenes`), variant, set and
/// round number: that round of that variant and set in a child `twinray stage-bench`, with
/// the parent's global flags and trace settings.
pub fn stage_timer(
    global: &GlobalArgs,
    frame: &crate::args::FrameArgs,
    scenes: Vec<String>,
) -> impl Fn(usize, Variant, &ShaderSet, u32) -> twinray_host::Result<f64> {
    let exe = std::env::current_exe().map_err(|e| e.to_string());
    let loader = global.loader().clone();
    let mut common = global.forwarded();
    common.extend(["stage-bench".into(), "--rounds".into(), "1".into()]);
    let flags =
        [("--width", frame.width), ("--height", frame.height), ("--runs", frame.runs), ("--warmup", frame.warmup)];
    common.extend(flags.into_iter().filter_map(|(f, v)| v.map(|v| [f.to_string(), v.to_string()])).flatten());
    move |scene, variant, set, round| {
        let ms = child_set(&loader, set).and_then(|text| {
            let (v, r) = (variant.name().to_string(), round.to_string());
            let which =
                [scenes[scene].clone(), "--variants".into(), v, "--sets".into(), text, "--first-round".into(), r];
            let results = child_results(&exe, &[&common[..], &which[..]].concat())?;
            said_it_timed(&results, "first_round", round)?;
            results["rows"][0]["round_ms"][0].as_f64().ok_or_else(|| no_times("stage-bench"))
        });
        ms.map_err(|e| Error::Unsupported(format!("timing {} {} with {set} alone: {e}", scenes[scene], variant.name())))
    }
}

/// Whether the child's results say it timed `key` = `want`, as it was told: a child that timed
/// other places would hand back times of another measurement.
fn said_it_timed(results: &serde_json::Value, key: &str, want: u32) -> twinray_host::Result<()> {
    match results[key] == want {
        true => Ok(()),
        false => Err(Error::Unsupported(format!("the child timed {key} {}, not {want}", results[key]))),
    }
}

fn no_times(command: &str) -> Error {
    Error::Unsupported(format!("the child {command}'s results.json has no times"))
}

/// How a child is told `set`: its text, which must read back as the same modules (a set whose
/// text named another would have another set timed).
fn child_set(loader: &Loader, set: &ShaderSet) -> twinray_host::Result<String> {
    let text = set.to_string();
    let read_back = twinray_host::sets::parse_specs(&text).and_then(|specs| loader.load_all(&specs));
    if read_back.ok().as_deref() != Some(std::slice::from_ref(set)) {
        return Err(Error::Unsupported(format!("{text} does not read back as the set it names")));
    }
    Ok(text)
}

/// Runs `twinray ARGS --out DIR`, DIR a fresh folder removed after, and hands back the
/// results.json it wrote there.
fn child_results(exe: &Result<PathBuf, String>, args: &[String]) -> twinray_host::Result<serde_json::Value> {
    let exe = exe.as_ref().map_err(|e| Error::Unsupported(format!("finding twinray's own executable: {e}")))?;
    let n = CHILDREN.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("twinray-alone-{}-{n}", std::process::id()));
    let ran = Command::new(exe).args(args).arg("--out").arg(&dir).output();
    let results = ran.map_err(|e| Error::Unsupported(format!("starting {}: {e}", exe.display()))).and_then(|out| {
        if !out.status.success() {
            let said = String::from_utf8_lossy(&out.stderr);
            let last = said.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("no message");
            return Err(Error::Unsupported(format!("the child failed ({}): {last}", out.status)));
        }
        let text = std::fs::read_to_string(dir.join("results.json"))
            .map_err(|e| Error::Unsupported(format!("the child left no results.json: {e}")))?;
        serde_json::from_str(&text).map_err(|e| Error::Unsupported(format!("the child's results.json: {e}")))
    });
    let _ = std::fs::remove_dir_all(&dir);
    results
}
