//! Rendering a scene with a shader set: upload the scene's acceleration structures and buffers,
//! build the set's pipeline, descriptors and SBT, trace (warm-up traces, then timed ones between
//! timestamps) once per placement, and read back colour and hit ids.

mod barriers;
pub mod frames;
pub mod isolated;
pub mod layout;
pub mod libraries;
mod moving;
pub mod output;
pub mod pipeline;
pub mod place_study;
pub mod placement;
pub(crate) mod prepare;
pub mod sentinel;
mod sets;
pub mod stacks;
mod textures;
mod tracing;
mod upload;

pub(crate) use barriers::{transition, STORAGE_IMAGE, UNUSED_IMAGE};
pub use frames::{AsWork, Frame, FrameRange, TlasKind, TlasMode, DEFAULT_TLAS};
pub use moving::{render_frames, FrameRenderer};
pub use output::{
    hit_id, to_picture, to_rgba8, to_srgb8, NoPayloadPixel, RayCounts, RenderOptions, RenderOutput, Written,
    NOT_A_NUMBER_RGB, NO_HIT_ID,
};
pub use placement::{PlacementTimes, DEFAULT_PLACEMENTS};
pub use prepare::MIN_WARM_MS;
pub(crate) use prepare::{min_warm_ms, place_warm_ms, prepare, prepare_uploaded, storage_buffer, Prepared};
pub use sets::{render, render_made, render_owned, render_sets};
pub(crate) use tracing::{submit, Trace};
