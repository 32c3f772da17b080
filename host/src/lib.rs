//! twinray: render ray tracing scenes with Rust (rust-gpu) or GLSL shader sets, or any
//! per-stage mix, through one ash host, and compare the two image for image and in GPU time.

pub mod bench;
pub mod compare;
pub mod error;
pub mod output;
pub mod probe;
pub mod probe_case;
pub mod probe_generate;
pub mod probe_report;
pub mod reference;
pub mod reference_image;
pub mod reference_scene;
pub mod render;
pub mod report;
pub mod scene;
pub mod shader_set;
pub mod stability;
pub mod stats;
mod tracing;
mod upload;
pub mod vk;

pub use error::{Error, Result};
pub use render::{render, render_sets, RenderOptions, RenderOutput};
pub use scene::Scene;
pub use shader_set::{Language, ShaderSet, Stage};
pub use vk::context::{Context, ContextOptions};
pub use vk::validation::Validation;
