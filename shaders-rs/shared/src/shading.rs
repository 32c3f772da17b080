//! Surfaces: world-space normals of transformed objects, and material colours.

use crate::bindings::MATERIAL_CHECKER;
use crate::layout::Material;
use glam::{Mat3, Vec3, Vec4Swizzles};

/// World-space unit normal from an object-space normal; `world_to_object` is the 3x3 part of
/// the instance's inverse transform (normals transform by the inverse transpose).
pub fn world_normal(world_to_object: Mat3, object_normal: Vec3) -> Vec3 {
    (world_to_object.transpose() * object_normal).normalize()
}

/// World-space geometric and shading normals of a hit seen along `direction`: both from
/// object-space normals, the geometric one faced against the ray and the shading one turned
/// to the same side (so rays leave from the side they arrived on).
pub fn surface_normals(world_to_object: Mat3, geometric: Vec3, shading: Vec3, direction: Vec3) -> (Vec3, Vec3) {
    let g = face_forward(world_normal(world_to_object, geometric), direction);
    let s = world_normal(world_to_object, shading);
    let s = if s.dot(g) < 0.0 { -s } else { s };
    (g, s)
}

/// `n` flipped, if needed, to face against the ray direction `d`.
pub fn face_forward(n: Vec3, d: Vec3) -> Vec3 {
    if n.dot(d) > 0.0 {
        -n
    } else {
        n
    }
}

/// Object-space geometric normal (from the winding) and shading normal (vertex normals
/// interpolated with barycentrics (u, v) of vertices 1 and 2) of a triangle.
pub fn triangle_normals(p: [Vec3; 3], n: [Vec3; 3], u: f32, v: f32) -> (Vec3, Vec3) {
    let geometric = (p[1] - p[0]).cross(p[2] - p[0]);
    let shading = n[0] * (1.0 - u - v) + n[1] * u + n[2] * v;
    (geometric, shading)
}

/// Depth, in checker cells, below the surface at which the checker is evaluated: on a plane
/// through a cell boundary (a floor at y = 0) the pattern would otherwise flip with the
/// rounding of each hit point.
pub const CHECKER_DEPTH: f32 = 1.0e-3;

/// The colour a material shows at an object-space point with object-space normal
/// `object_normal` (any length): albedo, or radiance if emissive.
pub fn material_color(material: &Material, object_point: Vec3, object_normal: Vec3) -> Vec3 {
    if material.kind == MATERIAL_CHECKER {
        let scale = material.color_b.w;
        let inside = object_point - object_normal.normalize() * (CHECKER_DEPTH / scale);
        let cell = (inside * scale).floor();
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    /// Points on a floor at y = 0, a rounding error above or below it, show one colour.
    #[test]
    fn checker_on_a_cell_boundary_is_stable() {
        let m = Material {
            kind: MATERIAL_CHECKER,
            _pad0: 0,
            _pad1: 0,
            _pad2: 0,
            color_a: Vec4::new(1.0, 1.0, 1.0, 1.0),
            color_b: Vec4::new(0.0, 0.0, 0.0, 2.0),
        };
        let colors: Vec<Vec3> =
            [1e-7f32, 0.0, -1e-7].iter().map(|y| material_color(&m, Vec3::new(0.3, *y, 0.3), Vec3::Y)).collect();
        assert!(colors.iter().all(|c| *c == colors[0]), "{colors:?}");
        // Across a cell boundary in x the colour does change.
        assert_ne!(
            material_color(&m, Vec3::new(0.3, 0.0, 0.3), Vec3::Y),
            material_color(&m, Vec3::new(0.7, 0.0, 0.3), Vec3::Y)
        );
    }
}
