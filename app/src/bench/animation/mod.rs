//! `twinray animate-bench`: a moving scene at several instance counts, rendered frame by frame
//! with each TLAS mode. Per frame it records the GPU time of the TLAS work and of the trace, so
//! the report shows what each mode costs per frame, and what an updated (refitted) TLAS costs
//! in trace time as the objects drift away from where it was built.

mod measure;
mod report;
mod resize;

pub use measure::{run, summarise, AnimateConfig, AnimateReport, FrameRow, ModeSummary};
pub use report::{table as report_table, write};
pub use resize::resize_grid;
