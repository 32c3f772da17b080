//! `twinray view`: serves the live page and prints its address.

use crate::args::GlobalArgs;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray::view::{serve, ViewConfig};
use twinray_host::Error;

pub fn view(global: &GlobalArgs, args: ViewArgs) -> Result<ExitCode> {
    // Refuse bad sets now, with exit 2: later, a set that stops loading is a message in the page.
    let a = global.load("--a", &args.a.parse()?)?;
    let b = global.load("--b", &args.b.parse()?)?;
    // The kinds of the sets' crates, which the page's scene may name: read from them as first
    // built (a kind added later is known to the renders, not to the page's size and camera).
    let own = twinray_host::ShaderSet::own_kinds(&[&a, &b]);
    let sources = match &args.sources {
        Some(dir) if !dir.is_dir() => {
            return Err(Error::Input(format!("--sources {}: no such folder", dir.display())).into());
        }
        Some(dir) => Some(dir.canonicalize().with_context(|| format!("--sources {}", dir.display()))?),
        None => std::env::current_dir().ok().and_then(|d| checkout_above(&d)),
    };
    if !args.bind.is_loopback() {
        eprintln!(
            "warning: serving on {}: anyone who can reach this address can see the renders and make this \
             machine render; prefer ssh -L (docs/commands.md, `twinray view`)",
            args.bind
        );
    }
    let work_dir = std::env::temp_dir().join(format!("twinray-view-{}", std::process::id()));
    let config = ViewConfig {
        scene: args.scene,
        own,
        sets: [args.a, args.b],
        sources,
        bind: args.bind,
        port: args.port,
        size: (args.width, args.height),
        preview_width: args.preview_width,
        twinray: std::env::current_exe().context("finding the twinray binary")?,
        global: global.forwarded(),
        work_dir: work_dir.clone(),
    };
    let served = serve(config, |address| {
        let host = if address.ip().is_unspecified() { "127.0.0.1".to_string() } else { address.ip().to_string() };
        let host = if address.is_ipv6() && !address.ip().is_unspecified() { format!("[{host}]") } else { host };
        println!("twinray view: serving http://{host}:{}/ (Ctrl-C to stop)", address.port());
    });
    let _ = std::fs::remove_dir_all(&work_dir);
    served?;
    Ok(ExitCode::SUCCESS)
}

/// The twinray checkout `dir` lies in (it holds `shaders-glsl/` and `shaders-rs/`), if any.
fn checkout_above(dir: &std::path::Path) -> Option<std::path::PathBuf> {
    dir.ancestors().find(|d| d.join("shaders-glsl").is_dir() && d.join("shaders-rs").is_dir()).map(|d| d.to_path_buf())
}

#[derive(Args)]
pub struct ViewArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    pub scene: Option<String>,
    /// Set A: rust, glsl, a folder of modules, or a mix (as for compare).
    #[arg(long, default_value = "rust")]
    pub a: String,
    /// Set B.
    #[arg(long, default_value = "glsl")]
    pub b: String,
    /// Port to listen on (0: any free port, printed).
    #[arg(long, default_value_t = 7878)]
    pub port: u16,
    /// Address to listen on. Anything but loopback lets other machines see the renders and
    /// make this one render: prefer `ssh -L` [default: 127.0.0.1].
    #[arg(long, value_name = "ADDR", default_value = "127.0.0.1")]
    pub bind: std::net::IpAddr,
    /// A twinray checkout whose shader sources rebuild the built-in sets (rust, glsl) on every
    /// save [default: the checkout the current folder is in, if any; else their embedded
    /// modules, not rebuilt].
    #[arg(long, value_name = "DIR")]
    pub sources: Option<PathBuf>,
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// Width of the quick render shown first after every change, before the full size.
    #[arg(long, default_value_t = 320, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub preview_width: u32,
}
