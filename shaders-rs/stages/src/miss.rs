//! The miss stages: what a ray that hit nothing brings back.

use spirv_std::glam::UVec4;
use spirv_std::spirv;
use twinray_shared::bindings::NO_HIT;
use twinray_shared::layout::{FrameUniform, HitPayload, ShadowPayload};

/// Primary rays that hit nothing see the background.
#[spirv(miss)]
pub fn miss(
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
) {
    payload.color = frame.background;
    payload.ids = UVec4::splat(NO_HIT);
}

/// A shadow ray that reaches its light.
#[spirv(miss)]
pub fn shadow_miss(#[spirv(incoming_ray_payload)] shadow: &mut ShadowPayload) {
    shadow.occluded = 0;
}
