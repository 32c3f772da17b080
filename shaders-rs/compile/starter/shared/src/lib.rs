//! What the stages and the CPU share: the crate's own shapes. Each is a module with its GPU
//! intersection (f32, used by its intersection stage in `src/`) and, on the CPU, its `SHAPE`:
//! the keys a scene gives it, the primitives it becomes, and its definition in f64, by which
//! twinray's reference judges the intersection (`twinray probe`). `twinray new . --shape NAME`
//! adds one.
#![cfg_attr(target_arch = "spirv", no_std)]

// The shapes' modules (`twinray new . --shape NAME` adds each after this line).

/// The shapes scenes may name (`kind = "NAME"`), which twinray reads from the CPU build.
#[cfg(not(target_arch = "spirv"))]
pub const SHAPES: &[twinray_shared::custom::CustomShape] = &[
    // The shapes (`twinray new . --shape NAME` adds each before this line).
];
