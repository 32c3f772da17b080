//! What the stages and the CPU share: the crate's own shapes and materials.
//!
//! A shape is a module with its GPU intersection (f32, used by its intersection stage in `src/`)
//! and, on the CPU, its `SHAPE`: the keys a scene gives it, the primitives it becomes, and its
//! definition in f64, by which twinray's reference judges the intersection (`twinray probe`).
//! `twinray new . --shape NAME` adds one.
//!
//! A material is a module with its GPU colour (used by its callable stage in `src/`) and, on
//! the CPU, its `MATERIAL`: the keys a scene gives it and the parameters its callable reads.
//! `twinray new . --material NAME` adds one.
#![cfg_attr(target_arch = "spirv", no_std)]

// The shapes' and materials' modules (`twinray new` adds each after this line).

/// The shapes scenes may name (`kind = "NAME"`), which twinray reads from the CPU build.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPES: &[twinray_shared::custom::CustomShape] = &[
    // The shapes (`twinray new . --shape NAME` adds each before this line).
];

/// The materials scenes may name (`kind = "NAME"`), which twinray reads from the CPU build.
#[cfg(not(target_arch = "spirv"))]
pub const MATERIALS: &[twinray_shared::custom::CustomMaterial] = &[
    // The materials (`twinray new . --material NAME` adds each before this line).
];
