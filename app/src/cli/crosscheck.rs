//! `twinray crosscheck`: twinray's references against Mitsuba 3's renders of the same scenes.

use crate::args::GlobalArgs;
use crate::session::context;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray::crosscheck::report::{html, table};
use twinray::crosscheck::{check, run};
use twinray_host::reference::image::{default_cache, frames};
use twinray_host::scene::check_size;
use twinray_host::sets::SetSpec;
use twinray_host::{Error, Scene};

#[derive(Args)]
pub struct CrosscheckArgs {
    /// Scene files or built-in names [default: sphere, plane, box, cylinder, cone, torus, meshes].
    pub scenes: Vec<String>,
    /// A Python with `mitsuba` (`cargo xtask crosscheck` makes one): renders the Mitsuba
    /// passes. Without it, each scene's passes are read from OUT/SCENE/mitsuba, as an earlier
    /// run left them.
    #[arg(long)]
    pub python: Option<PathBuf>,
    /// Mitsuba variant.
    #[arg(long, default_value = "scalar_rgb")]
    pub variant: String,
    /// Image width for every scene [default: each scene's].
    #[arg(long, requires = "height")]
    pub width: Option<u32>,
    /// Image height for every scene [default: each scene's].
    #[arg(long, requires = "width")]
    pub height: Option<u32>,
    /// Samples per pixel of twinray's reference: a square up to 256, or a multiple of 256.
    #[arg(long, default_value_t = 1024)]
    pub spp: u32,
    /// Samples per pixel of each Mitsuba pass: twice a square (its two halves estimate its noise).
    #[arg(long, default_value_t = 2048)]
    pub mitsuba_spp: u32,
    /// Shader set that renders twinray's reference.
    #[arg(long, default_value = "glsl")]
    pub shaders: SetSpec,
    /// Reference cache folder [default: as for `twinray reference`].
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Output folder: per scene the Mitsuba passes and the images; summary.md, results.json.
    #[arg(long, default_value = "bench/out/crosscheck")]
    pub out: PathBuf,
}

/// The scenes the cross-check covers unless told otherwise: every analytic shape and meshes
/// under directional, point and rect lights, without checkers or cutouts.
pub const DEFAULT_SCENES: &[&str] = &["sphere", "plane", "box", "cylinder", "cone", "torus", "meshes"];

pub fn crosscheck(global: &GlobalArgs, args: CrosscheckArgs) -> Result<ExitCode> {
    frames(args.spp)?;
    run::check_mitsuba_spp(args.mitsuba_spp)?;
    let names: Vec<String> = if args.scenes.is_empty() {
        DEFAULT_SCENES.iter().map(|s| s.to_string()).collect()
    } else {
        args.scenes.clone()
    };
    // Every scene is loaded and converted before any rendering, so bad input costs nothing.
    let mut scenes = Vec::new();
    for name in &names {
        let scene = Scene::load(Some(name))?;
        let size = (args.width.unwrap_or(scene.file.image.width), args.height.unwrap_or(scene.file.image.height));
        check_size(size.0, size.1).map_err(Error::Input)?;
        twinray::crosscheck::convert::convert(&scene, size, 1)?;
        if args.python.is_none() {
            let dir = mitsuba_dir(&args, &scene);
            let manifest = run::read_mitsuba(&dir)?.0;
            if (manifest.width, manifest.height) != size {
                return Err(Error::Input(format!(
                    "{}: Mitsuba rendered {}x{}, not {}x{} (pass --width and --height, or --python to render again)",
                    dir.display(),
                    manifest.width,
                    manifest.height,
                    size.0,
                    size.1
                ))
                .into());
            }
        }
        scenes.push((scene, size));
    }
    let shaders = global.load("--shaders", &args.shaders)?;
    let ctx = context(global)?;
    let cache = args.cache.clone().unwrap_or_else(default_cache);
    let mut checks = Vec::new();
    for (scene, size) in &scenes {
        let mitsuba = mitsuba_dir(&args, scene);
        let dir = mitsuba.parent().unwrap_or(&args.out).to_path_buf();
        if let Some(python) = &args.python {
            eprintln!("crosscheck {}: Mitsuba passes ({} spp each)", scene.name(), args.mitsuba_spp);
            run::write_mitsuba(scene, &mitsuba, *size, args.mitsuba_spp, &args.variant)?;
            run::render_mitsuba(python, &mitsuba)?;
        }
        eprintln!("crosscheck {}: twinray reference ({} spp)", scene.name(), args.spp);
        let (radiance, uncovered) = run::twinray_side(&ctx, scene, &shaders, *size, args.spp, &cache)?;
        let c = check(&radiance, &uncovered, args.spp, &mitsuba, Some(&dir))?;
        eprintln!(
            "crosscheck {}: relative RMSE {:.4} (Mitsuba noise {:.5} of RMSE {:.5}), {} coverage mismatches",
            c.scene, c.figures.relative_rmse, c.figures.mitsuba_noise, c.figures.rmse, c.figures.coverage_mismatches
        );
        checks.push(c);
    }
    let mut summary = format!("# twinray against Mitsuba 3 (`twinray crosscheck`)\n\n{}", table(&checks));
    for c in checks.iter().filter(|c| !c.notes.is_empty()) {
        summary += &format!("\n- {}: {}", c.scene, c.notes.join("; "));
    }
    let write = |name: &str, text: String| {
        let path = args.out.join(name);
        std::fs::write(&path, text).map_err(|source| Error::Io { what: "writing", path, source })
    };
    write("summary.md", summary.clone() + "\n")?;
    write("results.json", serde_json::to_string_pretty(&checks)?)?;
    let command: Vec<String> = std::env::args().collect();
    write("index.html", html(&checks, &command.join(" ")))?;
    println!("{summary}\nreport in {}", args.out.display());
    Ok(ExitCode::SUCCESS)
}

/// Where a scene's Mitsuba passes are written and read: OUT/SCENE/mitsuba.
fn mitsuba_dir(args: &CrosscheckArgs, scene: &Scene) -> PathBuf {
    args.out.join(twinray_host::util::output::file_safe(scene.name())).join("mitsuba")
}
