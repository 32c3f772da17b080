//! Comparing two shader sets on one scene: image and hit-id differences, the verdict against
//! the scene's parity tolerance, and the report `twinray compare` prints.

pub mod bisect;
pub mod diff;
pub mod edges;
pub mod frames;
pub mod pixels;
pub mod report;

pub use diff::{color_diff, color_verdict, diff, diff_image, hit_count, verdict, ColorDiff, ImageDiff, DIFF_LEGEND};
pub use edges::scene_diff;
pub use frames::{compare_frames, FrameFigures, FramesReport};
pub use report::{compare_sets, CompareReport, Comparison};
