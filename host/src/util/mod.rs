//! Helpers below every other layer: statistics of timings, bounded file input, atomic file output and progress.

pub mod input;
pub mod output;
pub mod progress;
pub mod stats;
