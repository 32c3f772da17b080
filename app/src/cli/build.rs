//! `twinray build DIR`: a folder of stage sources (a Rust shader crate, GLSL twins) built into
//! a set, `DIR/target/twinray/set/`, as every command that names the folder builds it: the
//! pinned toolchain installed when missing, the backend built once per machine, nothing built
//! when no file changed, every module checked as sets from disk are.

use crate::args::GlobalArgs;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::sets::load::summary;
use twinray_host::Error;

#[derive(Args)]
pub struct BuildArgs {
    /// The folder of sources: a shader crate (`twinray new` writes one) or GLSL twins.
    pub dir: PathBuf,
    /// Build even when no file changed since the last build.
    #[arg(long)]
    pub force: bool,
}

pub fn build(global: &GlobalArgs, args: BuildArgs) -> Result<ExitCode> {
    if !args.dir.is_dir() {
        return Err(Error::Input(format!("{}: no such folder", args.dir.display())).into());
    }
    let built = global.loader().build_now(&args.dir, args.force).map_err(|e| Error::Input(format!("{e:#}")))?;
    println!("build: {}", summary(&args.dir, &built));
    println!("set: {}", built.set.display());
    Ok(ExitCode::SUCCESS)
}
