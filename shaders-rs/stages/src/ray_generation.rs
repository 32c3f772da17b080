//! The ray generation stages: the image renderers `raygen` and `raygen_query`, and `probe` and
//! `explain`, which trace rays read from a buffer as the renderers trace them. Ray generation
//! shades; the hit stages only describe the surface they found (closest_hit.rs).

use crate::render::{Options, Pixel, Target, Totals};
use crate::texture::Texture;
use crate::trace::{self, Lights};
use spirv_std::glam::{UVec3, UVec4, Vec3, Vec3Swizzles, Vec4, Vec4Swizzles};
use spirv_std::ray_tracing::AccelerationStructure;
use spirv_std::{spirv, RuntimeArray};
use twinray_shared::bindings::{no_payload_word, EXPLAIN_SHADOW, MISS_PRIMARY, NO_HIT, PROBE_NO_PAYLOAD};
use twinray_shared::camera;
use twinray_shared::features::Features;
use twinray_shared::layout::{
    ExplainRay, ExplainResult, FrameUniform, HitPayload, Material, ObjectData, Primitive, ProbeRay, ProbeResult,
    ShadowPayload, Vertex,
};

/// The renderer: M x M primary rays per pixel (M is `samples_per_side`), each traced into
/// `payload` and shaded here with shadow rays traced by `traceRay` (the shadow miss stage
/// clears `shadow`); writes the mean colour and what the first sample hit.
///
/// The payload is poisoned before each trace: a ray whose hit or miss stage left it so is not
/// shaded but counted in the pixel's fourth hit-id word, and the pixel's colour is NaN.
#[spirv(ray_generation)]
#[allow(clippy::too_many_arguments)]
pub fn raygen(
    #[spirv(launch_id)] launch_id: UVec3,
    #[spirv(launch_size)] launch_size: UVec3,
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(descriptor_set = 0, binding = 1)] image: &Target,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] lights: &Lights,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 7)] hit_ids: &mut [u32],
    #[spirv(spec_constant(id = 0, default = 0))] shadows: u32,
    #[spirv(spec_constant(id = 1, default = 1))] samples_per_side: u32,
    #[spirv(spec_constant(id = 2, default = 0))] shadow_sampler: u32,
    // The scene's features (twinray_shared::features; 31 is `ALL`, for a host that sets none).
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
    #[spirv(spec_constant(id = 4, default = 0))] shaded_hits: u32,
    #[spirv(ray_payload)] payload: &mut HitPayload,
    #[spirv(ray_payload)] shadow: &mut ShadowPayload,
) {
    let options = Options::new(shadows, shadow_sampler, features, shaded_hits);
    let pixel = Pixel::new(launch_id.xy(), launch_size.xy());
    // What changes from sample to sample, in locals (`Pixel` says why).
    let (mut sample, mut sum, mut no_payload, mut shadow_rays) = (0, Vec3::ZERO, 0, 0);
    // Tested at the bottom: there is at least one sample, and rust-gpu tests a `while`
    // condition again after the body, which keeps it alive across the body's traces.
    loop {
        let ray = pixel.ray(frame, sample, samples_per_side);
        payload.poison();
        trace::primary(tlas, ray, (frame.reach.z, frame.reach.x), options.features, payload);
        let unwritten = payload.unwritten(true);
        if sample == 0 {
            pixel.first_hit(payload, unwritten, hit_ids);
        }
        if unwritten {
            no_payload = no_payload_word(no_payload, sample);
        } else {
            let at = (pixel.index, sample);
            sum += trace::shade(tlas, (frame, lights), options, payload, shadow, at, &mut shadow_rays);
        }
        sample += 1;
        if sample >= samples_per_side * samples_per_side {
            break;
        }
    }
    pixel.write(image, hit_ids, Totals { sum, no_payload, shadow_rays }, samples_per_side);
}

/// The renderer with shadow rays traced inline by ray queries (`shadow_method = "query"`,
/// `VK_KHR_ray_query`): as `raygen`, but a shadow ray runs no stage of the pipeline, so its
/// query intersects procedural primitives and decides cutouts itself, from the scene's buffers.
#[spirv(ray_generation)]
#[allow(clippy::too_many_arguments)]
pub fn raygen_query(
    #[spirv(launch_id)] launch_id: UVec3,
    #[spirv(launch_size)] launch_size: UVec3,
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(descriptor_set = 0, binding = 1)] image: &Target,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] lights: &Lights,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 7)] hit_ids: &mut [u32],
    #[spirv(spec_constant(id = 0, default = 0))] shadows: u32,
    #[spirv(spec_constant(id = 1, default = 1))] samples_per_side: u32,
    #[spirv(spec_constant(id = 2, default = 0))] shadow_sampler: u32,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
    #[spirv(spec_constant(id = 4, default = 0))] shaded_hits: u32,
    #[spirv(ray_payload)] payload: &mut HitPayload,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
) {
    let options = Options::new(shadows, shadow_sampler, features, shaded_hits);
    let pixel = Pixel::new(launch_id.xy(), launch_size.xy());
    let (mut sample, mut sum, mut no_payload, mut shadow_rays) = (0, Vec3::ZERO, 0, 0);
    loop {
        let ray = pixel.ray(frame, sample, samples_per_side);
        payload.poison();
        trace::primary(tlas, ray, (frame.reach.z, frame.reach.x), options.features, payload);
        let unwritten = payload.unwritten(true);
        if sample == 0 {
            pixel.first_hit(payload, unwritten, hit_ids);
        }
        if unwritten {
            no_payload = no_payload_word(no_payload, sample);
        } else {
            let scene = ((objects, primitives, materials), (vertices, indices));
            let at = (pixel.index, sample);
            sum += trace::shade_query(tlas, (frame, lights), options, payload, scene, textures, at, &mut shadow_rays);
        }
        sample += 1;
        if sample >= samples_per_side * samples_per_side {
            break;
        }
    }
    pixel.write(image, hit_ids, Totals { sum, no_payload, shadow_rays }, samples_per_side);
}

/// The probe: one ray per launch index from the ray buffer, traced through the same pipeline
/// as renders (so it measures the very intersection and hit stages images use); writes what
/// the closest-hit stage described, or NO_HIT (and a zero normal and t), or `PROBE_NO_PAYLOAD`
/// where the stage that took the ray left the poisoned payload as it was.
#[spirv(ray_generation)]
pub fn probe(
    #[spirv(launch_id)] launch_id: UVec3,
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ProbeRay],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ProbeResult],
    #[spirv(ray_payload)] payload: &mut HitPayload,
) {
    let i = launch_id.x as usize;
    // Checked before the trace: a bounds check of the write after it would keep the buffer's
    // length alive across the call.
    if i >= rays.len() || i >= results.len() {
        return;
    }
    // SAFETY: i < rays.len(), checked above.
    let ray = unsafe { *rays.get_unchecked(i) };
    payload.poison();
    // SAFETY: the TLAS is bound and built; the payload is this stage's ray_payload variable.
    unsafe {
        tlas.trace_ray(
            crate::flags::PRIMARY_RAY_FLAGS,
            0xff,
            0,
            0,
            MISS_PRIMARY as i32,
            ray.origin.xyz(),
            ray.origin.w,
            ray.direction.xyz(),
            ray.direction.w,
            payload,
        );
    }
    // A miss writes no normal or t: zeros, not the poison.
    let normal_t =
        if payload.ids.w == NO_HIT { Vec4::ZERO } else { payload.shading_normal.xyz().extend(payload.position.w) };
    let ids = if payload.unwritten(false) { UVec4::splat(PROBE_NO_PAYLOAD) } else { payload.ids };
    // SAFETY: i < results.len(), checked before the trace.
    unsafe { *results.get_unchecked_mut(i) = ProbeResult { normal_t, ids } };
}

/// `twinray explain`'s stage: one ray per launch index, traced as the renderer traces rays of
/// its kind (`trace::primary` or `trace::visible`, the functions `raygen` calls); writes the
/// primary ray's payload, or whether the shadow ray was occluded.
#[spirv(ray_generation)]
pub fn explain(
    #[spirv(launch_id)] launch_id: UVec3,
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ExplainRay],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ExplainResult],
    #[spirv(ray_payload)] payload: &mut HitPayload,
    #[spirv(ray_payload)] shadow: &mut ShadowPayload,
) {
    let i = launch_id.x as usize;
    if i >= rays.len() || i >= results.len() {
        return;
    }
    // SAFETY: i < rays.len(), checked above.
    let r = unsafe { *rays.get_unchecked(i) };
    let ray = camera::Ray { origin: r.origin.xyz(), direction: r.direction.xyz() };
    let result = if r.kind.x == EXPLAIN_SHADOW {
        let lit = trace::visible(tlas, ray.origin, ray.direction, r.direction.w, Features::all(), shadow);
        ExplainResult { hit: HitPayload::NONE, occluded: UVec4::new(if lit { 0 } else { 1 }, 0, 0, 0) }
    } else {
        payload.poison();
        trace::primary(tlas, ray, (frame.reach.z, frame.reach.x), Features::all(), payload);
        ExplainResult { hit: *payload, occluded: UVec4::ZERO }
    };
    // SAFETY: i < results.len(), checked above.
    unsafe { *results.get_unchecked_mut(i) = result };
}
