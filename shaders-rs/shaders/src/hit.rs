//! The closest-hit stages, as macros the crate root invokes (an entry point's name is its path,
//! and the module names are the catalog's). They only describe the surface in the payload; each
//! comes in two forms: with the material's colour computed inline, and (`_callable`) computed
//! by the callable its kind selects in the SBT's callable region (`material_shading =
//! "callable"`).

use core::arch::asm;
use spirv_std::glam::{UVec4, Vec3, Vec4Swizzles};
use twinray_shared::layout::{HitPayload, Material, MaterialCall};

/// Defines a closest-hit entry point for every procedural shape, `$name`: the surface from the
/// reported object-space normal, its colour `$color` of the material `$m`, object-space point
/// `$p` and normal `$n` (the entry also declares `$params`).
macro_rules! procedural_closest_hit {
    ($(#[$doc:meta])* $name:ident, [$($params:tt)*], |$m:ident, $p:ident, $n:ident| $color:expr) => {
$(#[$doc])*
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn $name(
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
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    $($params)*
) {
    let data = objects[object as usize];
    let material = materials[data.material as usize];
    let tint = primitives[(primitive_base + primitive_id) as usize].tint.xyz();
    let ($m, $p, $n) = (&material, object_origin + object_direction * t, *normal);
    let color = $color * tint;
    let (geometric, shading_normal) = shading::surface_normals(world_to_object.to_mat3(), *normal, *normal, direction);
    let ids = UVec4::new(object, primitive_id, material.kind, hit_kind);
    hit::describe(payload, origin + direction * t, t, geometric, shading_normal, color, ids);
}
    };
}

/// Defines a closest-hit entry point for triangle meshes, `$name`: normals from the triangle's
/// vertices (interpolated with the barycentrics), the colour as for `procedural_closest_hit!`.
macro_rules! triangle_closest_hit {
    ($(#[$doc:meta])* $name:ident, [$($params:tt)*], |$m:ident, $p:ident, $n:ident| $color:expr) => {
$(#[$doc])*
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn $name(
    #[spirv(instance_id)] object: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(hit_attribute)] barycentrics: &Vec2,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    $($params)*
) {
    let data = objects[object as usize];
    let material = materials[data.material as usize];
    let first = (data.index_base + 3 * primitive_id) as usize;
    let v0 = vertices[(data.vertex_base + indices[first]) as usize];
    let v1 = vertices[(data.vertex_base + indices[first + 1]) as usize];
    let v2 = vertices[(data.vertex_base + indices[first + 2]) as usize];
    let p = [v0.position.xyz(), v1.position.xyz(), v2.position.xyz()];
    let n = [v0.normal.xyz(), v1.normal.xyz(), v2.normal.xyz()];
    let (object_geometric, object_shading) = shading::triangle_normals(p, n, barycentrics.x, barycentrics.y);
    let ($m, $p, $n) = (&material, object_origin + object_direction * t, object_geometric);
    let color = $color;
    let (geometric, shading_normal) =
        shading::surface_normals(world_to_object.to_mat3(), object_geometric, object_shading, direction);
    let ids = UVec4::new(object, primitive_id, material.kind, hit_kind);
    hit::describe(payload, origin + direction * t, t, geometric, shading_normal, color, ids);
}
    };
}

/// The colour of `material` at an object-space point and normal, from the callable of the
/// SBT's callable region that the material's kind selects (one record per kind).
pub fn call_material(call: &mut MaterialCall, material: &Material, point: Vec3, normal: Vec3) -> Vec3 {
    call.material = *material;
    call.point = point.extend(1.0);
    call.normal = normal.extend(0.0);
    // SAFETY: `call` is this stage's callable data; the host gives the callable region a record
    // for every material kind. `spirv_std::arch::execute_callable` takes only a constant index.
    unsafe {
        asm!("OpExecuteCallableKHR {id} {data}", id = in(reg) material.kind, data = in(reg) call);
    }
    call.color.xyz()
}

/// The payload of a hit at world point `point`, ray parameter `t`.
pub fn describe(
    payload: &mut HitPayload,
    point: Vec3,
    t: f32,
    geometric: Vec3,
    shading: Vec3,
    color: Vec3,
    ids: UVec4,
) {
    payload.position = point.extend(t);
    payload.shading_normal = shading.extend(0.0);
    payload.geometric_normal = geometric.extend(0.0);
    payload.color = color.extend(1.0);
    payload.ids = ids;
}
