//! The references twinray's numbers are measured against: the f64 answer for a ray and a
//! shape or a whole scene, and converged reference images.

pub mod condition;
pub mod cutout;
pub mod image;
mod ray;
pub mod scene;
pub mod shapes;
pub mod stage;
pub mod surface;
pub mod texel;
mod traced;
pub mod uv;
mod watertight;
#[cfg(test)]
mod watertight_tests;
