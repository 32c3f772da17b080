//! Shader sets: which module each stage uses. A module comes from the built-in Rust or GLSL
//! set (the committed SPIR-V, embedded), or from a SPIR-V file on disk, validated and checked
//! before use; a folder of stage sources (a Rust shader crate, GLSL twins) is built first
//! (`sources`).
//! The pipeline code never branches on where a module came from, so any per-stage mix, and a
//! user's freshly built modules, are just other sets. A set's salted copy (`ShaderSet::copy`)
//! is the same code that no driver cache can take for the original.

mod builtin;
pub mod capabilities;
pub mod inspect;
mod module;
mod salt;
mod set;
pub mod sources;
mod validate;

pub use module::StageModule;
pub use set::{parse_sets, ShaderSet};
pub use twinray_shared::catalog::{Language, ModuleSpec, Stage, MODULES};
