//! `twinray explain`: every ray of one pixel, in each set and in the f64 reference, with the
//! first place they part.

use crate::args::{GlobalArgs, ViewpointArgs};
use crate::session::{context, load_still};
use anyhow::Result;
use clap::Args;
use std::process::ExitCode;
use twinray_host::explain::pixel::explain_pixel;
use twinray_host::explain::report::{Converged, ExplainReport};
use twinray_host::probe::report::Outcome::NoPayload;
use twinray_host::reference::image::{default_cache, reference};
use twinray_host::scene::check_size;
use twinray_host::sets::SetSpec;
use twinray_host::Error;

pub fn explain(global: &GlobalArgs, args: ExplainArgs) -> Result<ExitCode> {
    let names = args.names.clone().map_or([None, None], |(a, b)| [Some(a), Some(b)]);
    let [name_a, name_b] = names;
    let a = global.load("--a", &args.a)?;
    let mut sets = vec![(name_a.unwrap_or_else(|| label(&a, "A")), a.clone())];
    if let Some(b) = &args.b {
        let b = global.load("--b", b)?;
        sets.push((name_b.unwrap_or_else(|| label(&b, "B")), b));
    }
    let loaded: Vec<_> = sets.iter().map(|(_, s)| s).collect();
    let scene = load_still(args.scene.as_deref(), &args.viewpoint, &loaded)?;
    let size = (args.width.unwrap_or(scene.file.image.width), args.height.unwrap_or(scene.file.image.height));
    check_size(size.0, size.1).map_err(Error::Input)?;
    if sets.len() == 2 && sets[0].0 == sets[1].0 {
        sets[0].0 = format!("A ({})", sets[0].0);
        sets[1].0 = format!("B ({})", sets[1].0);
    }
    let ctx = context(global)?;
    let px = explain_pixel(&ctx, &scene, &sets, size, args.pixel)?;
    let converged = match args.converged {
        Some(spp) => {
            let image = reference(&ctx, &scene, &a, size, spp, &default_cache())?;
            let index = (args.pixel.1 * size.0 + args.pixel.0) as usize;
            Some(Converged { spp, value: image.linear[index] })
        }
        None => None,
    };
    let mut report = ExplainReport::new(&px, args.viewpoint.frame.unwrap_or(0), converged);
    let specs = [Some(&args.a), args.b.as_ref()].into_iter().flatten().zip(&sets);
    report.specs = specs
        .filter(|(set, (label, _))| set.to_string() != *label)
        .map(|(set, (label, _))| format!("{label} = {set}"))
        .collect();
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print!("{}", report.summary());
    }
    // A ray whose hit or miss stage wrote no payload fails, as it fails every other command.
    let no_payload =
        |s: &twinray_host::explain::pixel::SetRays| s.samples.iter().filter(|x| x.outcome == NoPayload).count();
    let failed: Vec<String> = px
        .sets
        .iter()
        .filter(|s| no_payload(s) > 0)
        .map(|s| format!("{} of {}'s primary rays got no payload from their hit or miss stage", no_payload(s), s.label))
        .collect();
    if failed.is_empty() {
        return Ok(ExitCode::SUCCESS);
    }
    if !args.json {
        println!("FAIL: {}", failed.join("; "));
    }
    Ok(ExitCode::FAILURE)
}

/// A set's name in the report: its spec, or `which` (A or B) when that is long (a folder or
/// file path).
fn label(set: &twinray_host::ShaderSet, which: &str) -> String {
    let text = set.to_string();
    if text.len() <= 40 {
        text
    } else {
        format!("set {which}")
    }
}

#[derive(Args)]
pub struct ExplainArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    pub scene: Option<String>,
    /// The pixel: column X and row Y from the top left, as compare's images number them.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub pixel: (u32, u32),
    /// Set A.
    #[arg(long, default_value = "rust")]
    pub a: SetSpec,
    /// Set B; without it, set A alone against the f64 reference.
    #[arg(long)]
    pub b: Option<SetSpec>,
    #[command(flatten)]
    pub viewpoint: ViewpointArgs,
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// What the report calls sets A and B, as A,B [default: their specs, or "set A" and
    /// "set B" where a spec is long].
    #[arg(long, value_name = "A,B", value_parser = parse_names)]
    pub names: Option<(String, String)>,
    /// Also show the pixel of a converged reference image of SPP samples per pixel, rendered
    /// by set A (or read from the cache `twinray reference` keeps).
    #[arg(long, value_name = "SPP")]
    pub converged: Option<u32>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// "A,B" as two names, neither empty.
fn parse_names(text: &str) -> Result<(String, String), String> {
    match text.split_once(',') {
        Some((a, b)) if !a.trim().is_empty() && !b.trim().is_empty() && a.trim() != b.trim() => {
            Ok((a.trim().to_string(), b.trim().to_string()))
        }
        _ => Err(format!("names are A,B: two different names (got {text:?})")),
    }
}

/// "X,Y" as two pixel coordinates.
fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("a pixel is X,Y with two whole numbers (got {text:?})");
    let (x, y) = text.split_once(',').ok_or_else(bad)?;
    Ok((x.trim().parse().map_err(|_| bad())?, y.trim().parse().map_err(|_| bad())?))
}
