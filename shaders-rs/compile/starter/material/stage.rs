//! The callable stage of the material `{material}` (`{shared}::{material}`): twinray's
//! closest-hit stages call it with the surface's material, object-space point and normal, and
//! light the colour it writes.

use spirv_std::glam::Vec4Swizzles;
use spirv_std::spirv;
use twinray_shared::layout::MaterialCall;
use {shared}::{material}::color;

#[spirv(callable)]
pub fn {material}_material(#[spirv(incoming_callable_data)] call: &mut MaterialCall) {
    call.color = color(&call.material, call.point.xyz(), call.normal.xyz()).extend(1.0);
}
