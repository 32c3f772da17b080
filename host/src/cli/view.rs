//! `twinray view`: serves the live page and prints its address.

use crate::args::{GlobalArgs, ViewArgs};
use anyhow::{Context, Result};
use std::process::ExitCode;
use twinray::view::{serve, ViewConfig};
use twinray::Error;

pub fn view(global: &GlobalArgs, args: ViewArgs) -> Result<ExitCode> {
    // Refuse bad sets now, with exit 2: later, a set that stops loading is a message in the page.
    for spec in [&args.a, &args.b] {
        spec.parse::<twinray::ShaderSet>()?;
    }
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
