//! Helpers below every other layer: statistics of timings, bounded file input, atomic file output (PNG and animated PNG) and progress.

pub mod apng;
pub mod checksum;
pub mod input;
pub mod output;
pub mod progress;
pub mod stats;
