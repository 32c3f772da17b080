//! The compute stages, which trace every ray inline with ray queries (`VK_KHR_ray_query`), with
//! no pipeline stage or SBT: the compute renderer `render_compute` (`renderer = "compute"`), and
//! `probe_query` and `explain_query`, which serve `twinray probe` and `twinray explain` on such
//! scenes. No hit stage runs in a ray query, so query.rs decides what the pipeline's stages
//! would, with the same shared code.

use crate::query;
use crate::render::{Options, Pixel, Target, Totals};
use crate::texture::Texture;
use crate::trace::{self, Lights};
use spirv_std::glam::{UVec2, UVec3, UVec4, Vec3, Vec3Swizzles, Vec4, Vec4Swizzles};
use spirv_std::ray_tracing::AccelerationStructure;
use spirv_std::{spirv, RuntimeArray};
use twinray_shared::bindings::{no_payload_word, EXPLAIN_SHADOW};
use twinray_shared::camera::Ray;
use twinray_shared::features::Features;
use twinray_shared::layout::{
    ExplainRay, ExplainResult, FrameUniform, HitPayload, Material, ObjectData, Primitive, ProbeRay, ProbeResult, Vertex,
};

/// The compute renderer: as `raygen` (ray_generation.rs), one invocation per pixel, in
/// workgroups of `RENDER_GROUP_SIZE` x `RENDER_GROUP_SIZE` (the literal is the attribute's),
/// its primary and shadow rays traced by ray queries.
#[spirv(compute(threads(8, 8)))]
#[allow(clippy::too_many_arguments)]
pub fn render_compute(
    #[spirv(global_invocation_id)] id: UVec3,
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
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
) {
    // Whole workgroups cover the image; compute has no launch size, so the frame says it.
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let options = Options::new(shadows, shadow_sampler, features, shaded_hits);
    let pixel = Pixel::new(id.xy(), UVec2::new(frame.width, frame.height));
    let (mut sample, mut sum, mut no_payload, mut shadow_rays) = (0, Vec3::ZERO, 0, 0);
    let mut payload = HitPayload::NONE;
    loop {
        let ray = pixel.ray(frame, sample, samples_per_side);
        payload.poison();
        let reach = (frame.reach.z, frame.reach.x);
        query::primary_query(
            tlas,
            ray,
            reach,
            options.features,
            &mut payload,
            frame,
            objects,
            primitives,
            materials,
            vertices,
            indices,
            textures,
        );
        let unwritten = payload.unwritten(true);
        if sample == 0 {
            pixel.first_hit(&payload, unwritten, hit_ids);
        }
        if unwritten {
            no_payload = no_payload_word(no_payload, sample);
        } else {
            let scene = ((objects, primitives, materials), (vertices, indices));
            let at = (pixel.index, sample);
            sum += trace::shade_query(tlas, (frame, lights), options, &payload, scene, textures, at, &mut shadow_rays);
        }
        sample += 1;
        if sample >= samples_per_side * samples_per_side {
            break;
        }
    }
    pixel.write(image, hit_ids, Totals { sum, no_payload, shadow_rays }, samples_per_side);
}

/// `twinray explain`'s stage for rays traced inline (`renderer = "compute"`, and the shadow
/// rays of `shadow_method = "query"`): as `explain`, with `query::primary_query` and
/// `query::visible_query`, which the compute renderer and `raygen_query` call; in workgroups of
/// `PROBE_GROUP_SIZE` (the literal is the attribute's).
#[spirv(compute(threads(64)))]
#[allow(clippy::too_many_arguments)]
pub fn explain_query(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ExplainRay],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ExplainResult],
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let features = Features::new(features);
    let i = id.x as usize;
    // Whole workgroups cover the rays; both buffers checked, as in `explain`.
    if i >= rays.len() || i >= results.len() {
        return;
    }
    let r = rays[i];
    let ray = Ray { origin: r.origin.xyz(), direction: r.direction.xyz() };
    results[i] = if r.kind.x == EXPLAIN_SHADOW {
        let scene = ((objects, primitives, materials), (vertices, indices));
        let lit = query::visible_query(tlas, ray.origin, ray.direction, r.direction.w, features, scene, textures);
        ExplainResult { hit: HitPayload::NONE, occluded: UVec4::new(if lit { 0 } else { 1 }, 0, 0, 0) }
    } else {
        let mut hit = HitPayload::NONE;
        let reach = (frame.reach.z, frame.reach.x);
        query::primary_query(
            tlas, ray, reach, features, &mut hit, frame, objects, primitives, materials, vertices, indices, textures,
        );
        ExplainResult { hit, occluded: UVec4::ZERO }
    };
}

/// The compute renderer's probe (a probe of a `renderer = "compute"` scene): one ray per
/// invocation, traced inline by the code that traces the renderer's primary rays, in
/// workgroups of `PROBE_GROUP_SIZE` (the literal is the attribute's); writes what it described,
/// or NO_HIT.
#[spirv(compute(threads(64)))]
#[allow(clippy::too_many_arguments)]
pub fn probe_query(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ProbeRay],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ProbeResult],
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let i = id.x as usize;
    // Whole workgroups cover the rays.
    if i >= rays.len() {
        return;
    }
    let probe = rays[i];
    let mut hit = HitPayload::NONE;
    let range = (probe.origin.w, probe.direction.w);
    let ray = Ray { origin: probe.origin.xyz(), direction: probe.direction.xyz() };
    let hit_buffers = (objects, primitives, materials);
    // No cone: probes judge geometry, and their rays come from no camera.
    let (mesh, features) = ((vertices, indices), Features::new(features));
    query::trace_query(tlas, ray, range, &mut hit, Vec4::ZERO, hit_buffers, mesh, textures, (0.0, features));
    results[i] = ProbeResult { normal_t: hit.shading_normal.xyz().extend(hit.position.w), ids: hit.ids };
}
