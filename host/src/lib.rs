//! twinray: render ray tracing scenes with Rust (rust-gpu) or GLSL shader sets, or any
//! per-stage mix, through one ash host, and compare the two image for image, ray for ray and
//! in GPU time.
//!
//! The modules are layers, listed here from the bottom up; each imports only from the layers
//! below it (`docs/architecture.md`, checked by `tests/architecture.rs`):
//!
//! - [`error`], [`util`]: the error type, statistics and file output;
//! - [`vk`]: Vulkan objects, each owning its handles, fed plain Vulkan-shaped inputs;
//! - [`shaders`]: shader sets, their modules (built in, or from disk) and the checks on them;
//! - [`scene`]: the scene format, its checks and the GPU data and pipeline plan of a scene;
//! - [`render`]: uploading a scene, building a set's pipeline and tracing it, timed;
//! - [`reference`]: the f64 reference for shapes and scenes, and converged reference images;
//! - [`probe`]: probe cases, their generators, judging rays, and the hard-case suite;
//! - [`compare`]: image differences, verdicts and the report of two sets;
//! - [`bench`]: speed against error, with tables, plots and HTML.

pub mod error;
pub mod util;

pub mod vk;

pub mod shaders;

pub mod scene;

pub mod render;

pub mod reference;

pub mod probe;

pub mod compare;

pub mod bench;

pub use error::{Error, Result};
pub use render::{render, render_sets, RenderOptions, RenderOutput};
pub use scene::Scene;
pub use shaders::{Language, ShaderSet, Stage};
pub use vk::context::{Context, ContextOptions};
pub use vk::validation::Validation;
