//! `twinray places`: what a place changes on this device (docs/measuring.md, *Places*).

use crate::args::GlobalArgs;
use crate::session::context;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::render::place_study::{self, Move};
use twinray_host::scene::check_size;
use twinray_host::{Error, RenderOptions, Scene};

#[derive(Args)]
pub struct PlacesArgs {
    /// Built-in scene name or scene file [default: sphere].
    pub scene: Option<String>,
    /// Comma-separated shader sets, each a set spec as for compare.
    #[arg(long, default_value = "glsl,rust")]
    pub sets: String,
    /// What to move from place to place, one at a time.
    #[arg(long, value_delimiter = ',', default_value = "none,code,sbt,buffers")]
    pub moves: Vec<Move>,
    /// Places per move and set.
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u32).range(2..=1000))]
    pub places: u32,
    /// Samples per pixel (a square up to 256) [default: the scene's].
    #[arg(long)]
    pub spp: Option<u32>,
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// Timed traces per place (after the place's warm-up traces).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub runs: u32,
    /// Write every place's times (and the summary) as JSON to this file.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn places(global: &GlobalArgs, args: PlacesArgs) -> Result<ExitCode> {
    let mut scene = Scene::load(args.scene.as_deref())?;
    if let Some(spp) = args.spp {
        scene.file.image.samples = twinray::bench::side_of(spp)?;
    }
    let size = (args.width.unwrap_or(scene.file.image.width), args.height.unwrap_or(scene.file.image.height));
    check_size(size.0, size.1).map_err(Error::Input)?;
    let sets = twinray_host::sets::ShaderSet::distinct(
        &global.load_all("--sets", &twinray_host::sets::parse_specs(&args.sets)?)?,
    );
    if let Some(out) = &args.out {
        twinray_host::util::output::check_file_target(out)?;
    }
    let ctx = context(global)?;
    let opts = RenderOptions { runs: args.runs, ..RenderOptions::once(size.0, size.1, 0, args.runs) };
    let times = place_study::study(&ctx, &scene, &sets, &args.moves, args.places, &opts)?;
    let spreads = place_study::spreads(&times);
    let side = scene.file.image.samples;
    println!(
        "scene {} {}x{} at {} spp on {}: {} places per move and set, {} timed traces each",
        scene.name(),
        size.0,
        size.1,
        side * side,
        ctx.info.name,
        args.places,
        args.runs
    );
    println!(
        "{:<8} {:<24} {:>9} {:>7} {:>17} {:>10} {:>8}  against the first set",
        "move", "set", "mean ms", "sd %", "min..max ms", "1st warm", "make ms"
    );
    for s in &spreads {
        let against = s.to_first.map_or(String::new(), |r| format!("{:.4} ({})", r.ratio, r.ci_text()));
        println!(
            "{:<8} {:<24} {:>9.4} {:>7.2} {:>8.4}..{:<8.4} {:>10.3} {:>8.1}  {against}",
            format!("{:?}", s.moved).to_lowercase(),
            s.set,
            s.mean_ms,
            100.0 * s.sd,
            s.min_ms,
            s.max_ms,
            s.first_warm,
            s.make_ms
        );
    }
    if let Some(out) = &args.out {
        let value = serde_json::json!({
            "device": ctx.info.name,
            "scene": scene.name(),
            "width": size.0,
            "height": size.1,
            "spp": side * side,
            "runs": args.runs,
            "spreads": spreads,
            "places": times,
        });
        twinray_host::util::output::write_atomically(out, serde_json::to_string_pretty(&value)?.as_bytes())?;
        println!("wrote {}", out.display());
    }
    Ok(ExitCode::SUCCESS)
}
