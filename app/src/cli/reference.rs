//! `twinray reference`: a scene's converged reference image, rendered or read from the cache.

use crate::args::GlobalArgs;
use crate::session::context;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::scene::check_size;
use twinray_host::sets::SetSpec;
use twinray_host::util::output::{check_image_target, write_image};
use twinray_host::{Error, Scene, ShaderSet};

pub fn reference(global: &GlobalArgs, args: ReferenceArgs) -> Result<ExitCode> {
    // The set first: a scene may name the kinds of the crate it was built from.
    let shaders = global.load("--shaders", &args.shaders)?;
    let scene = Scene::load_with(args.scene.as_deref(), &ShaderSet::own_kinds(&[&shaders]))?;
    let size = (args.width.unwrap_or(scene.file.image.width), args.height.unwrap_or(scene.file.image.height));
    check_size(size.0, size.1).map_err(Error::Input)?;
    twinray_host::reference::image::frames(args.spp)?;
    if let Some(out) = &args.out {
        check_image_target(out)?;
    }
    let cache = args.cache.unwrap_or_else(twinray_host::reference::image::default_cache);
    let ctx = context(global)?;
    let start = std::time::Instant::now();
    let r = twinray_host::reference::image::reference(&ctx, &scene, &shaders, size, args.spp, &cache)?;
    if let Some(out) = &args.out {
        write_image(out, (r.width, r.height), &r.linear, &twinray_host::render::to_picture(&r.linear))?;
    }
    if args.json {
        let value = serde_json::json!({
            "scene": scene.name(),
            "set": shaders.to_string(),
            "width": r.width,
            "height": r.height,
            "spp": r.spp,
            "path": r.path,
            "cached": r.cached,
            "seconds": start.elapsed().as_secs_f64(),
        });
        println!("{value}");
    } else {
        let how = if r.cached { "read from the cache" } else { "rendered" };
        println!(
            "{} {}x{} at {} spp with {}: {how}, {}",
            scene.name(),
            r.width,
            r.height,
            r.spp,
            shaders,
            r.path.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}

#[derive(Args)]
pub struct ReferenceArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    pub scene: Option<String>,
    /// Samples per pixel: a square up to 256, or a multiple of 256.
    #[arg(long, default_value_t = 1024)]
    pub spp: u32,
    /// Shader set that renders it.
    #[arg(long, default_value = "glsl")]
    pub shaders: SetSpec,
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// Cache folder [default: $XDG_CACHE_HOME/twinray/references or ~/.cache/twinray/references].
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Also write the reference as an 8-bit PNG.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}
