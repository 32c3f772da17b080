//! twinray's Rust ray tracing stages. Each `pub fn` with a `#[spirv(...)]` stage attribute is an
//! entry point, and a build (`twinray build`, or twinray's own for its built-in set) writes one
//! SPIR-V module per entry point, named by the function. The entry points are in one file per
//! stage kind, as the GLSL twins are in one file per stage; the files without entry points hold
//! what stages share.
//!
//! Entry points of one kind repeat their parameter lists: each declares what its module reads,
//! as a GLSL stage declares its layout, and no macro hides them. Bindings are literals there
//! because attributes need them; twinray checks every module's against
//! `twinray_shared::bindings` when it builds or loads it.
#![cfg_attr(target_arch = "spirv", no_std)]
// `spirv_std::ray_query!` declares its ray query object with inline assembly, and material
// callables are called by an index known only at run time (hit.rs).
#![cfg_attr(target_arch = "spirv", feature(asm_experimental_arch))]

// The entry points, by stage kind.
pub mod any_hit;
pub mod callable;
pub mod closest_hit;
pub mod compute;
pub mod intersection;
pub mod miss;
pub mod ray_generation;

// What the stages share.
mod flags;
mod hit;
mod query;
mod render;
mod texture;
mod trace;
