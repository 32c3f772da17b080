//! `twinray new DIR`: a shader crate of one's own, outside any checkout: the built-in Rust
//! stages, the contract they read (`twinray-shared/`), the crate's own shared library
//! (`shared/`), the toolchain file and a README; with `--glsl`, the GLSL twins in `glsl/`.
//! Unchanged, it renders exactly as the `rust` set. `--shape NAME` and `--material NAME` add a
//! shape or a material of the crate's own, to a new crate or to an existing one.

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_compile::{scaffold, starter};
use twinray_host::Error;

#[derive(Args)]
pub struct NewArgs {
    /// The folder to write the crate in: new, or empty (nothing is overwritten); with
    /// --shape or --material, also a crate's folder, to add them to.
    pub dir: PathBuf,
    /// The crate's package name [default: the folder's name].
    #[arg(long)]
    pub name: Option<String>,
    /// Also write the GLSL twins of every stage in DIR/glsl, a set of their own.
    #[arg(long)]
    pub glsl: bool,
    /// Add a procedural shape of the crate's own called NAME: its GPU intersection and f64
    /// definition (shared/src/NAME.rs), its stage (src/NAME.rs), its GLSL twin where DIR has
    /// glsl/, and scenes/NAME.toml and probes/NAME.toml, which render and probe it.
    #[arg(long, value_name = "NAME")]
    pub shape: Option<String>,
    /// Add a material of the crate's own called NAME: its GPU colour and keys
    /// (shared/src/NAME.rs), its callable stage (src/NAME.rs), its GLSL twin where DIR has
    /// glsl/, and scenes/NAME.toml, which renders it.
    #[arg(long, value_name = "NAME")]
    pub material: Option<String>,
}

pub fn new(args: NewArgs) -> Result<ExitCode> {
    let input = |e: anyhow::Error| Error::Input(format!("{e:#}"));
    let dir = args.dir.display().to_string();
    let existing = args.dir.join("Cargo.toml").is_file();
    let adds = args.shape.is_some() || args.material.is_some();
    if !(existing && adds) {
        let name = starter::package_name(&args.dir, args.name.as_deref()).map_err(input)?;
        let written = starter::write(&args.dir, &name, args.glsl).map_err(input)?;
        println!("new: wrote {} files of the shader crate {name} in {dir}", written.files.len());
        println!("  src/             the stages: unchanged, they render exactly as the built-in rust set");
        println!("  shared/          what the stages and the CPU share: the crate's own shapes and materials");
        println!("  twinray-shared/  the contract, twinray-shared {}", twinray_shared::contract::CONTRACT_VERSION);
        if args.glsl {
            println!("  glsl/            the GLSL twins, a set of their own");
        }
    } else if args.glsl || args.name.is_some() {
        let message = format!("{dir} is a crate already: --glsl and --name apply to a new one (nothing was written)");
        return Err(Error::Input(message).into());
    }
    if !adds {
        println!("next: twinray build {dir}   then   twinray compare --a {dir} --b rust");
        return Ok(ExitCode::SUCCESS);
    }
    let mut next = Vec::new();
    if let Some(shape) = &args.shape {
        let (written, hit_kind) = scaffold::add_shape(&args.dir, shape).map_err(input)?;
        println!("new: the shape {shape} (hit kind {hit_kind}) in {dir}: {} files written or changed", written.len());
        written.iter().for_each(|path| println!("  {}", path.display()));
        next.push(format!("twinray render {dir}/scenes/{shape}.toml --shaders {dir}"));
        next.push(format!("twinray probe {dir}/probes/{shape}.toml --shaders {dir}"));
    }
    if let Some(material) = &args.material {
        let written = scaffold::add_material(&args.dir, material).map_err(input)?;
        println!("new: the material {material} in {dir}: {} files written or changed", written.len());
        written.iter().for_each(|path| println!("  {}", path.display()));
        next.push(format!("twinray render {dir}/scenes/{material}.toml --shaders {dir}"));
    }
    println!("next: {}", next.join("   then   "));
    Ok(ExitCode::SUCCESS)
}
