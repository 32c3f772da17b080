//! twinray: render ray tracing scenes with Rust (rust-gpu) or GLSL shader sets, or any
//! per-stage mix, through one ash host, and compare the two image for image, ray for ray and
//! in GPU time.
//!
//! The modules are layers, listed here from the bottom up; each imports only from the layers
//! below it (`docs/architecture.md`, checked by `host/tests/architecture.rs`):
//!
//! - [`error`](mod@error), [`util`]: the error type, statistics and file output;
//! - [`vk`](mod@vk): Vulkan objects, each owning its handles, fed plain Vulkan-shaped inputs;
//! - [`shaders`](mod@shaders): shader sets, their modules (built in or from disk), checked;
//! - [`scene`](mod@scene): the scene format, its checks, and a scene's GPU data and pipeline plan;
//! - [`render`](mod@render): uploading a scene, building a set's pipeline and tracing it, timed;
//! - [`reference`](mod@reference): the f64 reference of shapes and scenes; converged images;
//! - [`probe`](mod@probe): probe cases, their generators, judging rays, and the hard-case suite;
//! - [`explain`](mod@explain): every ray of one pixel, made on the CPU as the GPU makes it;
//! - [`compare`](mod@compare): image differences, verdicts and the report of two sets;
//! - [`bench`](mod@bench): speed against error, with tables, plots and HTML;
//! - [`crosscheck`](mod@crosscheck): twinray's references against Mitsuba 3's renders;
//! - [`fuzz`](mod@fuzz): what the fuzz targets feed arbitrary bytes;
//! - [`view`](mod@view): the live page in the browser (its GPU work runs `twinray` children).

pub mod error;
pub mod util;

pub mod vk;

pub mod shaders;

pub mod scene;

pub mod render;

pub mod reference;

pub mod probe;

pub mod explain;

pub mod compare;

pub mod bench;

pub mod crosscheck;

pub mod fuzz;

pub mod view;

pub use error::{Error, Result};
pub use render::{render, render_sets, RenderOptions, RenderOutput};
pub use scene::Scene;
pub use shaders::{Language, ShaderSet, Stage};
pub use vk::context::{Context, ContextOptions};
pub use vk::validation::Validation;
