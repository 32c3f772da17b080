//! `twinray explain` (issue 27, in progress): every ray one pixel traces, made on the CPU by the
//! same shared code and seed as the GPU's ray generation stage, traced through each set's real
//! stages and judged against the f64 reference.
//!
//! Built so far: the pixel's primary rays (`rays`).

pub mod rays;
