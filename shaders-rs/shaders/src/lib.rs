//! twinray's Rust ray tracing stages. Each `pub fn` with a `#[spirv(...)]` stage attribute is an
//! entry point; `cargo xtask shaders` writes one SPIR-V module per entry point to `spirv/rust/`.
//! Bindings are literals here because attributes need them; a test checks them against
//! `twinray_shared::bindings`.
#![cfg_attr(target_arch = "spirv", no_std)]

use spirv_std::glam::{UVec3, Vec3, Vec3Swizzles, Vec4, Vec4Swizzles};
use spirv_std::ray_tracing::{AccelerationStructure, RayFlags};
use spirv_std::{spirv, Image};
use twinray_shared::bindings::{NO_HIT, T_MAX, T_MIN};
use twinray_shared::layout::{CameraUniform, RayPayload, Sphere};
use twinray_shared::{camera, shading, sphere};

/// One primary ray per pixel; writes the colour and the primitive id it hit.
#[spirv(ray_generation)]
pub fn raygen(
    #[spirv(launch_id)] launch_id: UVec3,
    #[spirv(launch_size)] launch_size: UVec3,
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(descriptor_set = 0, binding = 1)] image: &Image!(2D, format = rgba8, sampled = false),
    #[spirv(uniform, descriptor_set = 0, binding = 2)] camera: &CameraUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] hit_ids: &mut [u32],
    #[spirv(ray_payload)] payload: &mut RayPayload,
) {
    let ray = camera::primary_ray(camera, launch_id.xy(), launch_size.xy());
    // SAFETY: the TLAS is bound and built; the payload is this stage's ray_payload variable.
    unsafe {
        tlas.trace_ray(RayFlags::OPAQUE, 0xff, 0, 0, 0, ray.origin, T_MIN, ray.direction, T_MAX, payload);
    }
    // SAFETY: launch_id lies inside the image, which the host sizes to the launch.
    unsafe { image.write(launch_id.xy(), payload.color) };
    hit_ids[(launch_id.y * launch_size.x + launch_id.x) as usize] = payload.primitive;
}

/// Background: grey, no primitive.
#[spirv(miss)]
pub fn miss(#[spirv(incoming_ray_payload)] payload: &mut RayPayload) {
    payload.color = Vec4::new(shading::MISS_GREY, shading::MISS_GREY, shading::MISS_GREY, 1.0);
    payload.primitive = NO_HIT;
}

/// Analytic sphere of the AABB `primitive_id`.
#[spirv(intersection)]
pub fn sphere_intersection(
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(object_ray_origin)] origin: Vec3,
    #[spirv(object_ray_direction)] direction: Vec3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] spheres: &[Sphere],
) {
    let s = spheres[primitive_id as usize].center_radius;
    let roots = sphere::intersect(origin, direction, s.xyz(), s.w);
    if let Some(t) = sphere::reported_root(roots, t_min, t_max) {
        // SAFETY: called from an intersection stage, as OpReportIntersectionKHR requires.
        unsafe { spirv_std::arch::report_intersection(t, 0) };
    }
}

/// Lambert shading of the sphere that was hit; the normal is recomputed from the hit point.
#[spirv(closest_hit)]
pub fn sphere_closest_hit(
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(object_ray_origin)] origin: Vec3,
    #[spirv(object_ray_direction)] direction: Vec3,
    #[spirv(ray_tmax)] t_hit: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] spheres: &[Sphere],
    #[spirv(incoming_ray_payload)] payload: &mut RayPayload,
) {
    let s = spheres[primitive_id as usize];
    // Object space is world space here: the scene's one instance has the identity transform.
    let normal = (origin + direction * t_hit - s.center_radius.xyz()).normalize();
    payload.color = shading::lambert(s.color.xyz(), normal).extend(1.0);
    payload.primitive = primitive_id;
}
