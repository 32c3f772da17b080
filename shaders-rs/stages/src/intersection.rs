//! The intersection stages, one per procedural shape of `twinray_shared::shapes` (and one per
//! textbook variant a shape keeps, the probes' baseline): each runs its shape's routine on the
//! ray in object space and reports the first hit with the object-space normal as the hit
//! attribute, which the closest-hit stages read. The routines are shared with the CPU, and
//! with the ray queries that meet procedural primitives themselves (query.rs).

use spirv_std::glam::{Mat3, Vec3, Vec4};
use spirv_std::matrix::Matrix4x3;
use spirv_std::spirv;
use twinray_shared::features::Features;
use twinray_shared::layout::Primitive;
use twinray_shared::shapes::{self, hit_kind};
use twinray_shared::surface::SurfaceHit;
use twinray_shared::transform::{self, StageRay};

/// What every intersection stage does with its shape's `routine` (the first hit of an
/// object-space ray's origin and direction on a primitive, between two t): finds the hit on
/// the ray brought near the primitive's bounding sphere (`bound`; zero leaves the driver's
/// object-space ray as it is) and reports it with `hit_kind` and the normal in `normal`. The
/// ray is the world ray, the object-space ray and t_min and t_max; `placed` is the instance's
/// translation and world-to-object 3x3 part; the primitive is at `index`
/// (an object's first primitive is its instance's custom index, and the AABB's `primitive_id`
/// more).
#[allow(clippy::too_many_arguments)]
fn report(
    (routine, bound, hit_kind): (
        impl Fn(Vec3, Vec3, &Primitive, f32, f32) -> Option<SurfaceHit>,
        impl Fn(&Primitive) -> Vec4,
        u32,
    ),
    (world, object, (t_min, t_max)): ((Vec3, Vec3), (Vec3, Vec3), (f32, f32)),
    placed: (Vec3, Mat3),
    primitives: &[Primitive],
    index: u32,
    normal: &mut Vec3,
    features: u32,
) {
    // Not bounds-checked, as GLSL's twin is not: the index is the instance's custom index (its
    // object's first primitive) plus the AABB's index in its BLAS, both made by the host from
    // one primitive list. Timed over placements on the H100, the check cost 0.4% on `cylinder`
    // at 16 spp.
    // SAFETY: see above; every AABB of a BLAS has its primitive at that index.
    let p = unsafe { *primitives.get_unchecked(index as usize) };
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first, not the driver's, which loses precision there
    // (twinray_shared::transform).
    let ray: StageRay = transform::stage_ray(Features::new(features), object, world, placed, bound(&p));
    let (near, far) = ray.range(t_min, t_max);
    if let Some(hit) = routine(ray.origin, ray.direction, &p, near, far) {
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

/// The textbook routines keep the textbook transform: no bound, the ray not moved.
fn no_bound(_: &Primitive) -> Vec4 {
    Vec4::ZERO
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::sphere::intersect, shapes::sphere::bound, hit_kind::sphere);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::sphere::naive_intersect, no_bound, hit_kind::sphere);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::plane::intersect, shapes::plane::bound, hit_kind::plane);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::boxes::intersect, shapes::boxes::bound, hit_kind::boxes);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::cylinder::intersect, shapes::cylinder::bound, hit_kind::cylinder);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::cylinder::naive_intersect, no_bound, hit_kind::cylinder);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::cone::intersect, shapes::cone::bound, hit_kind::cone);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::torus::intersect, shapes::torus::bound, hit_kind::torus);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
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
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
) {
    let shape = (shapes::torus::naive_intersect, no_bound, hit_kind::torus);
    let ray = ((world_origin, world_direction), (object_origin, object_direction), (t_min, t_max));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    report(shape, ray, placed, primitives, primitive_base + primitive_id, normal, features);
}
