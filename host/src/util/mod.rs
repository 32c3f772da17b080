//! Helpers below every other layer: statistics of timings and the confidence interval of a time ratio, the process's peak memory, bounded file input, atomic file output (PNG and animated PNG), progress, and the deadline and crash reports of GPU work (what is being done, a watchdog on driver calls, a fatal-signal handler).

pub mod activity;
pub mod apng;
pub mod checksum;
pub mod crash;
pub mod input;
pub mod interval;
pub mod memory;
pub mod output;
pub mod progress;
pub mod srgb;
pub mod stats;
pub mod watchdog;
