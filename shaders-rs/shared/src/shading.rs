//! Surfaces: world-space normals of transformed objects, and material colours.

use crate::bindings::MATERIAL_CHECKER;
use crate::layout::Material;
use glam::{Mat3, Vec3, Vec4Swizzles};

/// World-space unit normal from an object-space normal; `world_to_object` is the 3x3 part of
/// the instance's inverse transform (normals transform by the inverse transpose).
pub fn world_normal(world_to_object: Mat3, object_normal: Vec3) -> Vec3 {
    (world_to_object.transpose() * object_normal).normalize()
}

/// `n` flipped, if needed, to face against the ray direction `d`.
pub fn face_forward(n: Vec3, d: Vec3) -> Vec3 {
    if n.dot(d) > 0.0 {
        -n
    } else {
        n
    }
}

/// The colour a material shows at an object-space point: albedo, or radiance if emissive.
pub fn material_color(material: &Material, object_point: Vec3) -> Vec3 {
    if material.kind == MATERIAL_CHECKER {
        let cell = (object_point * material.color_b.w).floor();
        let parity = (cell.x + cell.y + cell.z) as i32 & 1;
        if parity == 0 {
            material.color_a.xyz()
        } else {
            material.color_b.xyz()
        }
    } else {
        material.color_a.xyz()
    }
}
