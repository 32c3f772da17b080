//! The any-hit stages: cutouts, whose holes are ignored for primary and shadow rays alike. A
//! candidate hit in a hole is ignored, and the ray goes on to what lies behind.

use crate::texture::{self, Texture};
use spirv_std::glam::{Vec2, Vec3};
use spirv_std::{spirv, RuntimeArray};
use twinray_shared::bindings::CUTOUT_TEXTURE;
use twinray_shared::features::Features;
use twinray_shared::layout::{Material, ObjectData, Vertex};
use twinray_shared::shading;

/// Cutouts on meshes: as `cutout_any_hit`, and with the alpha pattern (glTF's alpha mode
/// MASK) the surface's own alpha at the hit: its opacity times its vertex colours' and its
/// texture's (at level 0).
#[spirv(any_hit)]
#[allow(clippy::too_many_arguments)]
pub fn triangle_cutout_any_hit(
    #[spirv(instance_id)] instance: u32,
    #[spirv(ray_geometry_index)] geometry: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(hit_attribute)] barycentrics: &Vec2,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(spec_constant(id = 3, default = 63))] features: u32,
) {
    let object = twinray_shared::bindings::mesh_object(instance, geometry);
    // Not bounds-checked, as the closest hits and GLSL's twin are not: this stage runs on
    // every candidate hit of a masked mesh, and its checks cost up to 1.8% of a frame on an
    // H200.
    // SAFETY: the object (instance id plus geometry index) and its material are the host's,
    // from the lists it uploads; robust access reads zeros where a stage from disk strays.
    let data = unsafe { *objects.get_unchecked(object as usize) };
    let material = unsafe { *materials.get_unchecked(data.material as usize) };
    let mut alpha = shading::cutout_alpha(&material, object_origin + object_direction * t);
    if material.cutout_pattern == CUTOUT_TEXTURE {
        let corners = crate::hit::corner_attributes(&data, primitive_id, vertices, indices);
        // Indexed here, not in `surface_alpha`: handed the array, that function read wrong
        // texels on NVIDIA's driver 580 (every hit a hole), not on lavapipe (twinray's guide, *Rust stages*).
        // SAFETY: the host writes every slot of the array, and a material's slot lies within it.
        let image = unsafe { textures.index(material.texture.x as usize) };
        let features = Features::new(features);
        alpha *= texture::surface_alpha(image, (&material, features), corners, *barycentrics);
    }
    if alpha < material.cutout_threshold {
        // SAFETY: called from an any-hit stage, as OpIgnoreIntersectionKHR requires.
        unsafe { spirv_std::arch::ignore_intersection() };
    }
}

/// Cutouts, for primary and shadow rays alike: a candidate hit in a hole of the object's
/// alpha pattern is ignored, and the ray goes on.
#[spirv(any_hit)]
pub fn cutout_any_hit(
    #[spirv(instance_id)] object: u32,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
) {
    // SAFETY: as in `triangle_cutout_any_hit`.
    let material = unsafe { *materials.get_unchecked(objects.get_unchecked(object as usize).material as usize) };
    if !shading::cutout_solid(&material, object_origin + object_direction * t) {
        // SAFETY: called from an any-hit stage, as OpIgnoreIntersectionKHR requires.
        unsafe { spirv_std::arch::ignore_intersection() };
    }
}
