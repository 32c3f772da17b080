//! Probing: rays traced one by one through a scene's ordinary pipeline and judged against the
//! f64 reference; probe case files, their ray generators, and the hard-case suite.

pub mod builtin;
pub mod case;
mod edges;
pub mod generate;
#[cfg(test)]
mod generate_tests;
pub mod origins;
pub mod random;
pub mod report;
pub mod run;
pub mod split;
pub mod stability;

pub use run::{probe, ProbeOutput, ProbeRay, ProbeResult};
