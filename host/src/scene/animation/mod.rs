//! Moving scenes: an [`Animation`] poses a scene at each frame, writing the values of what
//! moves (objects, lights, camera) into a copy of the scene file. Frame k of an animated scene
//! is, by construction, the still scene holding frame k's values: the renderer builds both
//! from the same posed `SceneFile`.

pub mod format;
mod pose;
mod resolve;

pub use pose::{Animation, Clip, Cycle, Motion, MotionKind, Moves, Property, Target, Track};
pub use resolve::{resolve, MAX_FPS, MAX_FRAMES};

#[cfg(test)]
mod tests;
