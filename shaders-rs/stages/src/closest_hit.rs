//! The closest-hit stages: each describes the surface its ray met in the payload (where,
//! its normals, its colour and the radiance it emits; ids of what it is), and ray generation
//! shades it. One set for procedural shapes (the intersection stage reported the object-space
//! normal) and one for triangle meshes (normals from the vertices); each gets the material's
//! colour in one of three ways (hit.rs, `MaterialColor`). Last, the probe's witnesses.

use crate::hit::{self, Computed, Flat, SurfaceHit};
use crate::texture::Texture;
use spirv_std::glam::{UVec4, Vec2, Vec3, Vec4, Vec4Swizzles};
use spirv_std::matrix::Matrix4x3;
use spirv_std::{spirv, RuntimeArray};
use twinray_shared::features::Features;
use twinray_shared::layout::{FrameUniform, HitPayload, Material, MaterialCall, ObjectData, Primitive, Vertex};

/// Every procedural shape, the material's colour computed here.
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn procedural_closest_hit(
    #[spirv(instance_id)] object: u32,
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(hit_attribute)] normal: &Vec3,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let rays = ((origin, direction), (object_origin, object_direction));
    let hit = SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    let features = Features::new(features);
    hit::procedural_surface(
        &hit,
        primitive_base,
        *normal,
        frame,
        objects,
        primitives,
        materials,
        textures,
        features,
        Computed,
        payload,
    );
}

/// Every procedural shape of diffuse, emissive and cutout materials: their one colour, no
/// branch on the kind (`hit_groups = "per-material"`).
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn procedural_closest_hit_flat(
    #[spirv(instance_id)] object: u32,
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(hit_attribute)] normal: &Vec3,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let rays = ((origin, direction), (object_origin, object_direction));
    let hit = SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    let features = Features::new(features);
    hit::procedural_surface(
        &hit,
        primitive_base,
        *normal,
        frame,
        objects,
        primitives,
        materials,
        textures,
        features,
        Flat,
        payload,
    );
}

/// Every procedural shape, the material's colour from its callable.
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn procedural_closest_hit_callable(
    #[spirv(instance_id)] object: u32,
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(hit_attribute)] normal: &Vec3,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
    #[spirv(callable_data)] call: &mut MaterialCall,
) {
    let rays = ((origin, direction), (object_origin, object_direction));
    let hit = SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    let features = Features::new(features);
    hit::procedural_surface(
        &hit,
        primitive_base,
        *normal,
        frame,
        objects,
        primitives,
        materials,
        textures,
        features,
        call,
        payload,
    );
}

/// Triangle meshes, the material's colour computed here.
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn triangle_closest_hit(
    #[spirv(instance_id)] instance: u32,
    #[spirv(ray_geometry_index)] geometry: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(hit_attribute)] barycentrics: &Vec2,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let rays = ((origin, direction), (object_origin, object_direction));
    let object = twinray_shared::bindings::mesh_object(instance, geometry);
    let hit = SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    let features = Features::new(features);
    hit::triangle_surface(
        hit,
        *barycentrics,
        object_to_world,
        frame,
        objects,
        materials,
        vertices,
        indices,
        textures,
        features,
        Computed,
        payload,
    );
}

/// Triangle meshes of diffuse, emissive and cutout materials: their one colour, no branch on
/// the kind (`hit_groups = "per-material"`).
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn triangle_closest_hit_flat(
    #[spirv(instance_id)] instance: u32,
    #[spirv(ray_geometry_index)] geometry: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(hit_attribute)] barycentrics: &Vec2,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let rays = ((origin, direction), (object_origin, object_direction));
    let object = twinray_shared::bindings::mesh_object(instance, geometry);
    let hit = SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    let features = Features::new(features);
    hit::triangle_surface(
        hit,
        *barycentrics,
        object_to_world,
        frame,
        objects,
        materials,
        vertices,
        indices,
        textures,
        features,
        Flat,
        payload,
    );
}

/// Triangle meshes, the material's colour from its callable.
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn triangle_closest_hit_callable(
    #[spirv(instance_id)] instance: u32,
    #[spirv(ray_geometry_index)] geometry: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(hit_attribute)] barycentrics: &Vec2,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
    #[spirv(callable_data)] call: &mut MaterialCall,
) {
    let rays = ((origin, direction), (object_origin, object_direction));
    let object = twinray_shared::bindings::mesh_object(instance, geometry);
    let hit = SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    let features = Features::new(features);
    hit::triangle_surface(
        hit,
        *barycentrics,
        object_to_world,
        frame,
        objects,
        materials,
        vertices,
        indices,
        textures,
        features,
        call,
        payload,
    );
}

/// The probe's witness: a closest-hit stage twinray puts in place of a hit group's own (same
/// intersection and any-hit stages) for one extra pass of the probe. It packs the
/// object-space ray the intersection stages use (`twinray_shared::transform::stage_ray`,
/// chosen and brought near the primitive as they do it), how far along the world ray it
/// starts, and the t they reported, into the payload fields the probe ray generation stage
/// copies out (as `ProbeResult` documents), so a probe can judge the stages against the
/// ray they used, apart from the transform's error.
///
/// A triangle's hit the stages measure again where the scene has far instances
/// (`twinray_shared::transform::triangle_t`): its witness is the ray brought near the
/// triangle and the t measured on it, or, where the ray was not moved, the driver's ray.
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn probe_witness(
    #[spirv(instance_id)] object: u32,
    #[spirv(ray_geometry_index)] geometry: u32,
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] world_origin: Vec3,
    #[spirv(world_ray_direction)] world_direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let world = (world_origin, world_direction);
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    use twinray_shared::bindings::{HIT_KIND_TRIANGLE_BACK, HIT_KIND_TRIANGLE_FRONT};
    use twinray_shared::features::FAR_INSTANCES;
    if (hit_kind == HIT_KIND_TRIANGLE_FRONT) | (hit_kind == HIT_KIND_TRIANGLE_BACK) {
        let mut ray =
            twinray_shared::transform::StageRay { origin: object_origin, direction: object_direction, shift: 0.0 };
        let mesh = twinray_shared::bindings::mesh_object(object, geometry);
        if Features::new(features).has::<FAR_INSTANCES>() & ((mesh as usize) < objects.len()) {
            // SAFETY: the index checked above; the vertices and indices are the host's.
            let data = unsafe { *objects.get_unchecked(mesh as usize) };
            let v = hit::triangle_vertices(&data, primitive_id, vertices, indices);
            let p = [v[0].position.xyz(), v[1].position.xyz(), v[2].position.xyz()];
            let near = twinray_shared::transform::triangle_ray(world, placed, p);
            if near.shift > 0.0 {
                ray = near;
            }
            let t = twinray_shared::transform::plane_t(&near, p, t);
            witness(payload, (ray.origin, ray.direction), t, ray.shift);
            return;
        }
        witness(payload, (ray.origin, ray.direction), t, 0.0);
        return;
    }
    // The bound the intersection stage used: its object's routine (zero for the naive ones).
    let mut bound = Vec4::ZERO;
    let primitive = (primitive_base + primitive_id) as usize;
    if (object as usize) < objects.len() && primitive < primitives.len() {
        // SAFETY: both indices checked above.
        let shape = unsafe { objects.get_unchecked(object as usize) }.shape;
        bound = twinray_shared::shapes::shape_bound(shape, unsafe { primitives.get_unchecked(primitive) });
    }
    let ray = twinray_shared::transform::stage_ray(
        Features::new(features),
        (object_origin, object_direction),
        world,
        placed,
        bound,
    );
    witness(payload, (ray.origin, ray.direction), t, ray.shift);
}

/// The second witness, of what the driver's transform would have cost: as
/// `probe_witness`, with the object-space ray the driver hands a hit group
/// (`ObjectRayOriginKHR`, `ObjectRayDirectionKHR`), which the intersection stages do not use.
#[spirv(closest_hit)]
pub fn probe_witness_driver(
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
) {
    witness(payload, (object_origin, object_direction), t, 0.0);
}

/// A witness's record: the object-space ray, where it starts along the world ray and t,
/// in the fields `probe` copies out.
fn witness(payload: &mut HitPayload, (origin, d): (Vec3, Vec3), t: f32, shift: f32) {
    payload.position.w = t;
    payload.shading_normal = origin.extend(payload.shading_normal.w);
    payload.ids = UVec4::new(d.x.to_bits(), d.y.to_bits(), d.z.to_bits(), shift.to_bits());
}
