//! Shader sets: which module each stage uses. A module comes from the built-in Rust or GLSL
//! set (the committed SPIR-V, embedded), or from a SPIR-V file on disk, validated and checked
//! before use; a folder of stage sources (a Rust shader crate, GLSL twins) is built first.
//! A set is text until it is loaded (`spec`, then `load`): parsing reads no file.
//! The pipeline code never branches on where a module came from, so any per-stage mix, and a
//! user's freshly built modules, are just other sets. A set's salted copy (`ShaderSet::copy`)
//! is the same code that no driver cache can take for the original.

mod builtin;
pub mod capabilities;
mod copies;
pub mod inspect;
pub mod load;
mod module;
pub mod own;
mod set;
pub mod spec;
mod validate;

pub use load::Loader;
pub use module::StageModule;
pub use set::ShaderSet;
pub use spec::{parse_specs, SetSpec};
pub use twinray_shared::catalog::{Language, ModuleSpec, Stage, MODULES};
