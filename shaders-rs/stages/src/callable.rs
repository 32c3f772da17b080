//! The callable stages: the colours of twinray's material kinds, for closest hits that call
//! them (`material_shading = "callable"`; the SBT's callable region has a record per kind).
//! The caller hands the material, the object-space point and normal in `call`, and reads
//! `call.color` back.

use spirv_std::glam::Vec4Swizzles;
use spirv_std::spirv;
use twinray_shared::layout::MaterialCall;
use twinray_shared::shading;

/// Diffuse, emissive and cutout materials: their one colour.
#[spirv(callable)]
pub fn flat_material(#[spirv(incoming_callable_data)] call: &mut MaterialCall) {
    call.color = call.material.color_a;
}

/// Checker materials: the pattern at the point.
#[spirv(callable)]
pub fn checker_material(#[spirv(incoming_callable_data)] call: &mut MaterialCall) {
    call.color = shading::material_color(&call.material, call.point.xyz(), call.normal.xyz()).extend(1.0);
}
