//! `twinray new DIR`: a shader crate of one's own, outside any checkout: the built-in Rust
//! stages, the contract they read (`twinray-shared/`), the toolchain file and a README; with
//! `--glsl`, the GLSL twins in `glsl/`. Unchanged, it renders exactly as the `rust` set.

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_compile::starter;
use twinray_host::Error;

#[derive(Args)]
pub struct NewArgs {
    /// The folder to write the crate in: new, or empty (nothing is overwritten).
    pub dir: PathBuf,
    /// The crate's package name [default: the folder's name].
    #[arg(long)]
    pub name: Option<String>,
    /// Also write the GLSL twins of every stage in DIR/glsl, a set of their own.
    #[arg(long)]
    pub glsl: bool,
}

pub fn new(args: NewArgs) -> Result<ExitCode> {
    let name = starter::package_name(&args.dir, args.name.as_deref()).map_err(|e| Error::Input(format!("{e:#}")))?;
    let written = starter::write(&args.dir, &name, args.glsl).map_err(|e| Error::Input(format!("{e:#}")))?;
    let dir = args.dir.display();
    println!("new: wrote {} files of the shader crate {name} in {dir}", written.files.len());
    println!("  src/             the stages: unchanged, they render exactly as the built-in rust set");
    println!("  twinray-shared/  the contract, twinray-shared {}", twinray_shared::contract::CONTRACT_VERSION);
    if args.glsl {
        println!("  glsl/            the GLSL twins, a set of their own");
    }
    println!("next: twinray build {dir}   then   twinray compare --a {dir} --b rust");
    Ok(ExitCode::SUCCESS)
}
