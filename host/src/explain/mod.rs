//! `twinray explain`: every ray one pixel traces, made on the CPU by the same shared code and
//! seed as the GPU's ray generation stage (`rays`, `shading`), traced through each set's real
//! stages (`trace`), judged against the f64 reference (`pixel`), and the first place they part
//! (`parting`), and what each hit is on (`surface`: object, material, triangle, texture
//! coordinates and level of detail), in words and JSON (`report`).

pub mod no_payload;
pub mod parting;
pub mod pixel;
pub mod rays;
pub mod report;
pub mod shading;
pub mod surface;
pub mod trace;
