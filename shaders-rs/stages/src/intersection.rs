//! The intersection stages, one per procedural shape of `twinray_shared::shapes` (and one per
//! textbook variant a shape keeps, the probes' baseline): each runs its shape's routine on the
//! ray in object space and reports the first hit with the object-space normal as the hit
//! attribute, which the closest-hit stages read. The routines are shared with the CPU, and
//! with the ray queries that meet procedural primitives themselves (query.rs).

use spirv_std::glam::{Vec3, Vec4};
use spirv_std::matrix::Matrix4x3;
use spirv_std::spirv;
use twinray_shared::features::Features;
use twinray_shared::layout::Primitive;
use twinray_shared::shapes::{self, hit_kind};
use twinray_shared::surface::SurfaceHit;
use twinray_shared::transform::{self, StageRay};

/// The primitive at `index` of the primitive buffer (an object's first primitive is its
/// instance's custom index, and the AABB's `primitive_id` more).
#[inline(always)]
fn primitive(primitives: &[Primitive], index: u32) -> Primitive {
    // Not bounds-checked, as GLSL's twin is not: both parts of the index are the host's, made
    // from one primitive list. Timed over placements on the H100, the check cost 0.4% on
    // `cylinder` at 16 spp.
    // SAFETY: see above; every AABB of a BLAS has its primitive at that index.
    unsafe { *primitives.get_unchecked(index as usize) }
}

/// Reports `hit`, a shape's first hit on `ray` (whose t it is measured in), with `hit_kind`
/// and the object-space normal as the hit attribute `normal`.
#[inline(always)]
fn report(hit: Option<SurfaceHit>, ray: &StageRay, t_max: f32, hit_kind: u32, normal: &mut Vec3) {
    if let Some(hit) = hit {
        // Put back what was there if the hit is not taken (a cutout's any-hit stage ignored
        // it): lavapipe 25.0.7 hands closest-hit the attribute last written, not the one
        // reported with the committed hit (Vulkan-Docs #2681), so a hole in front of a shape
        // gave it this normal. Elsewhere the store is dead.
        let before = *normal;
        *normal = hit.normal;
        // SAFETY: called from an intersection stage, as OpReportIntersectionKHR requires.
        if !unsafe { spirv_std::arch::report_intersection(ray.world_t(hit.t, t_max), hit_kind) } {
            *normal = before;
        }
    }
}

/// The sphere.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn sphere_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        shapes::sphere::bound(&p),
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::sphere::intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::sphere, normal);
}

/// The sphere's textbook routine, kept as the probes' baseline.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn sphere_naive_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        Vec4::ZERO,
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::sphere::naive_intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::sphere, normal);
}

/// The plane.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn plane_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        shapes::plane::bound(&p),
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::plane::intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::plane, normal);
}

/// The box.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn box_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        shapes::boxes::bound(&p),
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::boxes::intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::boxes, normal);
}

/// The cylinder.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn cylinder_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        shapes::cylinder::bound(&p),
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::cylinder::intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::cylinder, normal);
}

/// The cylinder's textbook routine, kept as the probes' baseline.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn cylinder_naive_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        Vec4::ZERO,
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::cylinder::naive_intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::cylinder, normal);
}

/// The cone.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn cone_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        shapes::cone::bound(&p),
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::cone::intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::cone, normal);
}

/// The torus.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn torus_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        shapes::torus::bound(&p),
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::torus::intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::torus, normal);
}

/// The torus's textbook routine, kept as the probes' baseline.
#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn torus_naive_intersection(
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let p = primitive(primitives, primitive_base + primitive_id);
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there.
    let ray = transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        (world_origin, world_direction),
        (object_to_world.w_axis, world_to_object.to_mat3()),
        Vec4::ZERO,
    );
    let (near, far) = ray.range(t_min, t_max);
    let hit = shapes::torus::naive_intersect(ray.origin, ray.direction, &p, near, far);
    report(hit, &ray, t_max, hit_kind::torus, normal);
}
