//! `cargo xtask <task>`: set-up, shader builds, golden images, the demo and CI.

mod bundle;
mod caches;
mod clone_builds;
mod crosscheck;
mod new_shape;
mod planted;
mod process;
mod setup;
mod shaders;
mod suite;
mod watch;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use process::{cargo, repo_root};
use setup::Scope;

#[derive(Parser)]
#[command(name = "cargo xtask", about = "twinray's build tasks")]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

#[derive(Subcommand)]
enum Task {
    /// Install what is missing (idempotent): the pinned nightly for rust-gpu, and, as root with
    /// apt, Mesa lavapipe, glslang, SPIRV-Tools, the validation layer, and chromium with
    /// chromedriver (the browser tests of `twinray view`). Otherwise prints the commands to run.
    Setup {
        /// Only the Vulkan loader and driver (what rendering needs), not the shader toolchain.
        #[arg(long)]
        vulkan_only: bool,
    },
    /// Build both shader sets into spirv/, validate every module and check its entry points.
    Shaders {
        /// Build into a scratch folder and fail if a committed module is stale.
        #[arg(long, conflicts_with = "out")]
        check: bool,
        /// Build both sets into OUT/rust and OUT/glsl instead of spirv/ (sets to load from
        /// disk, e.g. `--sets OUT/rust`).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// With --out, build both sets without the code of these features (comma-separated:
        /// textures, area-lights, alpha-masks, emission): the baseline that measures what
        /// specialising on a feature leaves behind.
        #[arg(long, value_delimiter = ',', requires = "out")]
        without: Vec<String>,
    },
    /// Re-render the golden images of tests/golden/ from the current shaders: of every built-in
    /// scene, or only of the scenes named.
    Golden {
        /// Built-in scene names [default: all].
        scenes: Vec<String>,
    },
    /// Re-take the screenshot of `twinray view` in docs/images/view.png, as its browser test
    /// takes it (showcase with a planted miss stage, a pixel explained).
    Screenshot,
    /// Scaffold a procedural shape in both languages (shared math with a placeholder robust
    /// intersection and CPU tests, its registry line, the GLSL twin, a built-in scene), build
    /// the shaders and compare its scene's renders with both sets.
    NewShape {
        /// The shape's name: lowercase letters, digits and underscores (e.g. capsule).
        name: String,
    },
    /// Rebuild a shader set on every save under shaders-rs/ or shaders-glsl/ and compare the
    /// fresh Rust and GLSL modules on a scene, printing the verdict and the time from the save.
    Watch {
        /// Scene file or built-in name [default: twinray's default scene].
        scene: Option<String>,
        /// How often to look for changes, in milliseconds.
        #[arg(long, default_value_t = 200)]
        poll_ms: u64,
        /// Stop after this many rebuilds [default: run until interrupted].
        #[arg(long)]
        changes: Option<u32>,
        /// More `twinray compare` arguments (after --), e.g. -- --width 1024 --height 768.
        #[arg(last = true)]
        compare_args: Vec<String>,
    },
    /// Render the default scene with both shader sets and print the comparison; with
    /// --animated, the moving `orbit` scene: its frames as an animated PNG, and both sets
    /// compared on every frame.
    Demo {
        #[arg(long)]
        animated: bool,
    },
    /// What CI runs: setup, fmt check, clippy and rustdoc (warnings denied), shaders --check
    /// (beside the builds), all tests as `cargo xtask test` runs them.
    Ci,
    /// Every test of the workspace, as `cargo test --workspace --release` has them, built once
    /// and run several test binaries at a time; prints each binary's time. Logs go to
    /// target/ci-tests/.
    Test {
        /// Test binaries run at once [default: the number of cores].
        #[arg(long)]
        jobs: Option<usize>,
        /// The edit loop's subset, in about a minute warm: the libraries' unit tests, Rust
        /// against GLSL on the default scene (tests/parity.rs) and `shaders --check`.
        #[arg(long, conflicts_with_all = ["jobs", "only"])]
        quick: bool,
        /// Run only the binaries whose source path contains one of these (e.g. golden, host/tests).
        only: Vec<String>,
    },
    /// The defects that tests made lighter must still catch: applies each patch of
    /// tests/planted/ (or those named) in turn, runs the test its `# test:` line names, reverts
    /// the patch, and fails unless every such test failed. Needs no tracked change in the tree.
    Planted {
        /// Patch names (file names without .patch) [default: all].
        names: Vec<String>,
    },
    /// twinray's references against Mitsuba 3 renders of the same scenes (docs/shading-model.md):
    /// makes, once, a Python virtual environment in target/crosscheck/venv with Mitsuba pinned,
    /// and runs `twinray crosscheck` with it (default scenes: every analytic shape and meshes
    /// under directional, point and rect lights). --refresh rewrites the Mitsuba data the tests
    /// compare against (tests/crosscheck/). Arguments after `--` go to `twinray crosscheck`.
    Crosscheck {
        /// Scene files or built-in names.
        scenes: Vec<String>,
        /// Rewrite the Mitsuba data of tests/crosscheck/ instead.
        #[arg(long)]
        refresh: bool,
        /// Passed on to `twinray crosscheck`.
        #[arg(last = true)]
        twinray_args: Vec<String>,
    },
    /// One folder (and .tar.gz) that runs the whole bench on an NVIDIA machine without
    /// network: the release build, the Vulkan loader and GL dispatch libraries, run.sh.
    Bundle {
        /// Where to put it.
        #[arg(long, default_value = "target/twinray-bench")]
        out: std::path::PathBuf,
    },
}

fn main() -> Result<()> {
    match Cli::parse().task {
        Task::Setup { vulkan_only } => setup::run(if vulkan_only { Scope::Vulkan } else { Scope::Full }),
        Task::Shaders { without, out: Some(out), .. } => shaders::build_into(&out, &without),
        Task::Shaders { check, .. } => shaders::run(check),
        Task::Golden { scenes } => golden(&scenes),
        Task::Screenshot => screenshot(),
        Task::NewShape { name } => new_shape::run(&name),
        Task::Watch { scene, poll_ms, changes, compare_args } => watch::run(&watch::WatchArgs {
            scene,
            poll: std::time::Duration::from_millis(poll_ms),
            changes,
            compare_args,
        }),
        Task::Demo { animated } => demo(animated),
        Task::Ci => ci(),
        Task::Test { quick: true, .. } => suite::quick(),
        Task::Test { jobs, only, .. } => suite::run(suite::build()?, jobs.unwrap_or_else(default_jobs), &only, || {}),
        Task::Planted { names } => planted::run(&names),
        Task::Crosscheck { scenes, refresh, twinray_args } => crosscheck::run(&scenes, refresh, &twinray_args),
        Task::Bundle { out } => bundle::run_bundle(&repo_root().join(out)),
    }
}

fn golden(scenes: &[String]) -> Result<()> {
    let only = scenes.join(",");
    let env = [("TWINRAY_REFRESH_GOLDEN", "1"), ("TWINRAY_GOLDEN_SCENES", only.as_str())];
    cargo(&["test", "--release", "-p", "twinray-tests", "--test", "golden"], &env)?;
    println!("golden images rewritten in tests/golden/; review them with git diff before committing");
    Ok(())
}

fn screenshot() -> Result<()> {
    let test = "the_page_follows_saves_explains_pixels_and_recovers_from_broken_stages";
    let env = [("TWINRAY_REFRESH_SCREENSHOT", "1")];
    cargo(&["test", "--release", "-p", "twinray", "--test", "view", "--", "--exact", test], &env)?;
    println!("screenshot rewritten in docs/images/view.png; look at it before committing");
    Ok(())
}

fn demo(animated: bool) -> Result<()> {
    setup::run(Scope::Vulkan)?;
    let out = repo_root().join("target/demo");
    let dir = out.to_string_lossy();
    // Built first with cargo's progress shown (minutes on a fresh machine, silent under
    // `--quiet`); the runs after it are quiet, as the build is done.
    println!("demo: building twinray (release)");
    cargo(&["build", "--release", "-p", "twinray"], &[])?;
    let twinray = ["run", "--release", "--quiet", "-p", "twinray", "--"];
    if !animated {
        // Four placements of 5 traces: an interval in about half a minute on lavapipe.
        let compare = ["compare", "--runs", "5", "--placements", "4", "--out-dir", &dir];
        return cargo(&[&twinray[..], &compare[..]].concat(), &[]);
    }
    // Half the scene's size: lavapipe renders the 48 frames in about a minute.
    std::fs::create_dir_all(&out).with_context(|| format!("creating {dir}"))?;
    let movie = out.join("orbit.png");
    let size = ["--width", "320", "--height", "180"];
    let render = ["render", "orbit", "--frames", "all", "--out", &movie.to_string_lossy()];
    cargo(&[&twinray[..], &render, &size].concat(), &[])?;
    let compare = ["compare", "orbit", "--frames", "all", "--runs", "1", "--warmup", "0", "--out-dir"];
    cargo(&[&twinray[..], &compare, &[dir.as_ref()], &size].concat(), &[])
}

fn ci() -> Result<()> {
    let started = std::time::Instant::now();
    let caches = caches::survey(&repo_root());
    process::step("setup", || setup::run(Scope::Full))?;
    process::step("rustfmt", || {
        cargo(&["fmt", "--all", "--", "--check"], &[])?;
        process::run_tool(
            "rustfmt",
            &["--check", "--edition", "2021", "shaders-rs/stages/src/lib.rs", "shaders-rs/builder/src/main.rs"],
        )
    })?;
    // The shader check builds rust-gpu on the pinned nightly in target folders of its own: on a
    // cold machine, minutes that the workspace's build shares the cores with.
    let shaders = process::Background::start("shaders --check", process::xtask_command(&["shaders", "--check"])?)?;
    let mut binaries = Vec::new();
    process::step("build tests, clippy", || {
        binaries = suite::build()?;
        // Doc tests are not binaries: cargo runs them itself (the libraries are built by now).
        cargo(&["test", "--workspace", "--release", "--doc"], &suite::CLIPPY)
    })?;
    shaders.wait()?;
    // The library's public API is documented and its doc links resolve. In the release profile,
    // so that rustdoc reuses the build scripts (FLIP's C++ among them) and most proc macros of the
    // test build: 56 s alone on 2 cores where the debug profile took 112 s from nothing. No test
    // runs cargo on this target while it works (the tutorial's copy has a target of its own).
    // It fills the cores the tests leave while lavapipe compiles a pipeline on one. It starts once the
    // binaries that assert on GPU timings have run alone: beside rustdoc, the planted
    // twice-the-work stage of tests/timing.rs measured 0.28 of the time (bound 0.35).
    let mut docs = None;
    let tests = process::step("tests", || {
        suite::run(binaries, default_jobs(), &[], || {
            let rustdoc = [("RUSTDOCFLAGS", "-D warnings")];
            let doc = process::cargo_command(
                &["doc", "--release", "--no-deps", "-p", "twinray-host", "-p", "twinray", "-p", "twinray-shared"],
                &rustdoc,
            );
            docs = Some(process::Background::start("docs", doc));
        })
    });
    if let Some(docs) = docs {
        docs?.wait()?;
    }
    tests?;
    // Kept only from a run that passed: a fresh clone on this machine starts from them.
    process::step("keep the dependencies' builds", || {
        let root = repo_root();
        let bytes =
            clone_builds::save(&process::target_dir(&root), &clone_builds::own_packages(&root)?, &clone_builds::dir())?;
        println!("kept {:.0} MB in {}", bytes as f64 / 1e6, clone_builds::dir().display());
        Ok(())
    })?;
    summary(&caches, started.elapsed().as_secs_f64());
    Ok(())
}

/// The run's steps and total, and whether it started cold or warm: the two figures
/// docs/testing.md keeps for 2 cores.
fn summary(caches: &[caches::Cache], total: f64) {
    println!("ci: caches at the start:");
    let width = caches.iter().map(|c| c.what.len()).max().unwrap_or(0);
    for c in caches {
        println!("  {:<width$} {:<5} {}", c.what, if c.warm { "warm" } else { "cold" }, c.path.display());
    }
    println!("ci: steps (\"beside\": in a child process beside the steps after it):");
    for (name, seconds) in process::steps() {
        println!("  {name:<28} {seconds:>7.1} s");
    }
    println!("ci: every step passed in {total:.0} s, {}", caches::verdict(caches));
}

/// One test binary per core: run one at a time, the tests kept 1.4 of 2 cores busy on average
/// (lavapipe compiles a pipeline on one); with more, CPU-bound tests only wait on each other.
fn default_jobs() -> usize {
    std::thread::available_parallelism().map_or(2, |n| n.get())
}
