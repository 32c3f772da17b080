//! twinray-host: the render library of twinray. It renders ray tracing scenes with Rust
//! (rust-gpu) or GLSL shader sets, or any per-stage mix, through one ash host, and compares the
//! two image for image and ray for ray against an f64 reference. It links no command-line,
//! web or plotting crate: the `twinray` app (commands, bench reports, the live viewer) sits on
//! top of it, and so can any Rust program.
//!
//! ```no_run
//! use twinray_host::sets::{Loader, SetSpec};
//! use twinray_host::{Context, ContextOptions, RenderOptions, Scene};
//!
//! # fn main() -> twinray_host::Result<()> {
//! let ctx = Context::new(&ContextOptions::default())?;
//! let scene = Scene::load(Some("spheres"))?;
//! // A set is text until it is loaded: the loader builds folders of sources and checks modules.
//! let loader = Loader::default();
//! let rust = loader.load(&"rust".parse::<SetSpec>()?)?;
//! let mix = loader.load(&"rust,intersection=glsl".parse::<SetSpec>()?)?;
//! let options = RenderOptions::once(256, 256, 1, 5);
//! let (a, b) = (twinray_host::render(&ctx, &scene, &rust, &options)?, twinray_host::render(&ctx, &scene, &mix, &options)?);
//! let diff = twinray_host::compare::diff(&a, &b, 2);
//! let verdict = twinray_host::compare::verdict(&diff, &scene.file.parity, 256 * 256);
//! println!("rmse {:.6}, {} hit mismatches, {verdict:?}", diff.color.rmse, diff.hit_mismatches);
//! println!("GPU {:?} ms against {:?} ms (median of the timed traces)", a.median_ms(), b.median_ms());
//! # Ok(())
//! # }
//! ```
//!
//! The modules are layers, listed here from the bottom up; each imports only from the layers
//! below it (`docs/architecture.md`, checked by `app/tests/architecture.rs`):
//!
//! - [`error`](mod@error), [`util`]: the error type, statistics and file output;
//! - [`vk`](mod@vk): Vulkan objects, each owning its handles, fed plain Vulkan-shaped inputs;
//! - [`sets`](mod@sets): shader sets as text (`SetSpec`) and loaded (`ShaderSet`), their modules checked;
//! - [`scene`](mod@scene): the scene format, its checks, and a scene's GPU data and pipeline plan;
//! - [`render`](mod@render): uploading a scene, building a set's pipeline and tracing it, timed;
//! - [`reference`](mod@reference): the f64 reference of shapes and scenes; converged images;
//! - [`probe`](mod@probe): probe cases, their generators, judging rays, and the hard-case suite;
//! - [`explain`](mod@explain): every ray of one pixel, made on the CPU as the GPU makes it;
//! - [`compare`](mod@compare): image differences, verdicts and the report of two sets;
//! - [`fuzz`](mod@fuzz): what the fuzz targets feed arbitrary bytes.

pub mod error;
pub mod util;

pub mod vk;

pub mod sets;

pub mod scene;

pub mod render;

pub mod reference;

pub mod probe;

pub mod explain;

pub mod compare;

pub mod fuzz;

pub use error::{Error, Result};
pub use render::{render, render_owned, render_sets, RenderOptions, RenderOutput};
pub use scene::Scene;
pub use sets::{Language, ShaderSet, Stage};
pub use vk::context::{Context, ContextOptions};
pub use vk::validation::Validation;
