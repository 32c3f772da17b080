//! `--processes N` (`twinray bench` and `compare`): one set timed alone, by a child `twinray
//! bench` of that set only, with the parent's global flags and timing settings, whose placement
//! medians are read back from its results.json (see `twinray::bench::Isolation`).

use crate::args::{BenchArgs, GlobalArgs};
use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicU32, Ordering};
use twinray::shaders::ShaderSet;
use twinray::Error;

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
    pub fn of_bench(args: &BenchArgs, cache: PathBuf) -> Self {
        ChildSettings {
            runs: args.runs,
            warmup: args.warmup,
            placements: args.placements,
            size: args.width.zip(args.height),
            reference_spp: args.reference_spp,
            reference_set: args.reference_set.to_string(),
            cache,
        }
    }
}

/// `--processes N` of `compare` and `bisect` (none for 0), and the folder its children keep
/// their (1 spp, unread) reference in, for the caller to remove.
pub fn for_scene(
    global: &GlobalArgs,
    scene: String,
    opts: &twinray::render::RenderOptions,
    reference_set: &ShaderSet,
    processes: u32,
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
    let time_alone = std::sync::Arc::new(timer(global, settings, vec![scene]));
    ((processes > 0).then_some(twinray::bench::Isolation { processes, time_alone }), cache)
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

/// The timer `bench`, `compare` and `bisect` call per scene (an index into `scenes`, as given on the
/// command line), sample count and set.
pub fn timer(
    global: &GlobalArgs,
    settings: ChildSettings,
    scenes: Vec<String>,
) -> impl Fn(usize, u32, &ShaderSet) -> twinray::Result<Vec<f64>> + Send + Sync + 'static {
    let exe = std::env::current_exe().map_err(|e| e.to_string());
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
    move |scene, spp, set| {
        let exe = exe.as_ref().map_err(|e| Error::Unsupported(format!("finding twinray's own executable: {e}")))?;
        let n = CHILDREN.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("twinray-alone-{}-{n}", std::process::id()));
        let times = child_set(set).and_then(|text| {
            let ran = Command::new(exe)
                .args(&common)
                .arg(&scenes[scene])
                .args(["--sets", &text, "--spp", &spp.to_string(), "--out"])
                .arg(&dir)
                .output();
            ran.map_err(|e| Error::Unsupported(format!("starting {}: {e}", exe.display())))
                .and_then(|out| read_times(&out, &dir))
        });
        let _ = std::fs::remove_dir_all(&dir);
        times.map_err(|e| Error::Unsupported(format!("timing {set} alone on {} at {spp} spp: {e}", scenes[scene])))
    }
}

/// How a child is told `set`: its text, which must read back as the same modules (a set whose
/// text named another would have another set timed).
fn child_set(set: &ShaderSet) -> twinray::Result<String> {
    let text = set.to_string();
    if twinray::shaders::parse_sets(&text).ok().as_deref() != Some(std::slice::from_ref(set)) {
        return Err(Error::Unsupported(format!("{text} does not read back as the set it names")));
    }
    Ok(text)
}

/// The placement medians of the one set a child timed.
fn read_times(out: &std::process::Output, dir: &std::path::Path) -> twinray::Result<Vec<f64>> {
    if !out.status.success() {
        let said = String::from_utf8_lossy(&out.stderr);
        let last = said.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("no message");
        return Err(Error::Unsupported(format!("the child bench failed ({}): {last}", out.status)));
    }
    let text = std::fs::read_to_string(dir.join("results.json"))
        .map_err(|e| Error::Unsupported(format!("the child bench left no results.json: {e}")))?;
    let value: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| Error::Unsupported(format!("the child's results.json: {e}")))?;
    let times =
        value["rows"][0]["placements"]["median_ms"].as_array().map(|a| a.iter().filter_map(|v| v.as_f64()).collect());
    times
        .filter(|t: &Vec<f64>| !t.is_empty())
        .ok_or_else(|| Error::Unsupported("the child's results.json has no times".into()))
}
