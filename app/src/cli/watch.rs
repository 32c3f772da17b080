//! `twinray watch DIR [SCENE]`: the edit loop of a folder of stage sources outside any
//! checkout. On every save in DIR or in a folder or file `--against` names (outside their
//! `target/`), `twinray compare` of DIR against `--against` runs in a process of its own,
//! which builds both first; its verdict is printed with the time from the save to it. A build
//! error, a refused module or a stage that never returns is a verdict line too, and the next
//! save is compared as usual.

use crate::args::GlobalArgs;
use anyhow::{Context, Result};
use clap::Args;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::{Duration, SystemTime};
use twinray_compile::exit_words;
use twinray_compile::folder::{source_files, sources_in};
use twinray_host::sets::SetSpec;
use twinray_host::Error;

#[derive(Args)]
pub struct WatchArgs {
    /// The folder of sources to watch: a shader crate or GLSL twins (set a of each compare).
    pub dir: PathBuf,
    /// The scene to compare on [default: spheres].
    pub scene: Option<String>,
    /// The set DIR is compared with (set b); the folders and files it names are watched too.
    #[arg(long, default_value = "rust")]
    pub against: String,
    /// How often DIR is looked at for saves, in milliseconds.
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(10..=60_000))]
    pub poll_ms: u64,
    /// Stop after this many saves (0: watch until interrupted).
    #[arg(long, default_value_t = 0)]
    pub changes: u32,
    /// More `twinray compare` arguments, after `--`; they follow (and override) watch's
    /// `--runs 1 --warmup 0 --placements 1 --gpu-timeout=20`.
    #[arg(last = true)]
    pub compare_args: Vec<String>,
}

/// When each watched file was last written: DIR's files by their names in it, the files of
/// what `--against` names by their paths as written.
type Snapshot = BTreeMap<PathBuf, SystemTime>;

/// The folders and files whose saves start a compare: DIR, then each folder or `.spv` file
/// `--against` names (a crate's GLSL twins, `--against ./mine/glsl`, among them).
fn watched(args: &WatchArgs) -> Result<Vec<PathBuf>> {
    let against: SetSpec = args.against.parse().map_err(|e: Error| Error::Input(format!("--against: {e}")))?;
    let mut roots = vec![args.dir.clone()];
    roots.extend(against.paths().filter(|p| !same_place(p, &args.dir)).map(Path::to_path_buf));
    Ok(roots)
}

fn same_place(a: &Path, b: &Path) -> bool {
    a == b || a.canonicalize().ok().is_some_and(|a| b.canonicalize().ok() == Some(a))
}

fn snapshot(roots: &[PathBuf]) -> Snapshot {
    let modified = |path: &Path| path.metadata().ok()?.modified().ok();
    let mut out = Snapshot::new();
    for (k, root) in roots.iter().enumerate() {
        if root.is_file() {
            out.extend(modified(root).map(|t| (root.clone(), t)));
            continue;
        }
        for file in source_files(root).unwrap_or_default() {
            let name = if k == 0 { file.clone() } else { root.join(&file) };
            out.extend(modified(&root.join(&file)).map(|t| (name, t)));
        }
    }
    out
}

pub fn watch(global: &GlobalArgs, args: WatchArgs) -> Result<ExitCode> {
    if sources_in(&args.dir).is_none() {
        let message = format!("{}: no shader sources to watch (a Cargo.toml or a raygen.rgen)", args.dir.display());
        return Err(Error::Input(message).into());
    }
    let roots = watched(&args)?;
    println!("watch: {} against {} (Ctrl-C to stop)", args.dir.display(), args.against);
    // Seen before the first compare: a save while it runs is the next turn's, not lost.
    let mut seen = snapshot(&roots);
    compare(global, &args)?;
    let mut saves = 0;
    while args.changes == 0 || saves < args.changes {
        std::thread::sleep(Duration::from_millis(args.poll_ms));
        let now = snapshot(&roots);
        let changed: Vec<_> =
            now.iter().filter(|(f, t)| seen.get(*f) != Some(t)).map(|(f, t)| (f.clone(), *t)).collect();
        let removed = seen.keys().any(|f| !now.contains_key(f));
        if changed.is_empty() && !removed {
            continue;
        }
        seen = now;
        saves += 1;
        let saved = changed.iter().map(|(_, t)| *t).max().unwrap_or_else(SystemTime::now);
        let names: Vec<String> = changed.iter().map(|(f, _)| f.display().to_string()).collect();
        println!(
            "\nwatch: changed {}",
            if names.is_empty() { "(a file was removed)".into() } else { names.join(", ") }
        );
        compare(global, &args)?;
        let to_verdict = SystemTime::now().duration_since(saved).unwrap_or_default();
        println!("watch: save to verdict {:.1} s", to_verdict.as_secs_f64());
    }
    Ok(ExitCode::SUCCESS)
}

/// One `twinray compare` in a process of its own; what it prints is the verdict, and an exit
/// that is not a verdict (a refusal, a deadline, a crash) gets a line of its own.
fn compare(global: &GlobalArgs, args: &WatchArgs) -> Result<()> {
    let exe = std::env::current_exe().context("finding the twinray binary")?;
    let mut command = Command::new(exe);
    command.args(global.forwarded()).arg("compare").args(args.scene.as_deref());
    command.arg("--a").arg(&args.dir).arg("--b").arg(&args.against);
    command.args(["--runs", "1", "--warmup", "0", "--placements", "1", "--gpu-timeout=20"]);
    command.args(&args.compare_args);
    // Its error lines go where its verdicts go, in order.
    use std::os::fd::AsFd;
    command.stderr(std::process::Stdio::from(std::io::stdout().as_fd().try_clone_to_owned()?));
    let status = command.status().context("starting twinray compare")?;
    if let Some(line) = exit_words(status) {
        println!("watch: verdict: {line}");
    }
    Ok(())
}
