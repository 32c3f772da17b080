//! Helpers below every other layer: statistics of timings and atomic file output.

pub mod output;
pub mod stats;
