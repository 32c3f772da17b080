//! Surfaces: world-space normals of transformed objects, and material colours.

use crate::bindings::{CUTOUT_CHECKER, CUTOUT_DISCS, CUTOUT_TEXTURE, MATERIAL_CHECKER};
use crate::layout::Material;
use glam::{Mat3, Vec2, Vec3, Vec4Swizzles};

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

/// A cutout's alpha at an object-space point, from its pattern over x and z (extruded along
/// y, so a plane or rectangle in its own space shows the pattern flat): 1 where solid.
/// Checker: 1 in cells whose x and z indices add up even, else 0. Discs: the distance from
/// the cell's centre in half-cells, clamped to 1. Materials without a cutout are solid.
pub fn cutout_alpha(material: &Material, object_point: Vec3) -> f32 {
    let q = Vec2::new(object_point.x, object_point.z) * material.cutout_scale;
    let cell = q.floor();
    if material.cutout_pattern == CUTOUT_CHECKER {
        let parity = (cell.x + cell.y) as i32 & 1;
        if parity == 0 {
            1.0
        } else {
            0.0
        }
    } else if material.cutout_pattern == CUTOUT_DISCS {
        ((q - cell - Vec2::splat(0.5)) * 2.0).length().min(1.0)
    } else if material.cutout_pattern == CUTOUT_TEXTURE {
        // The part of the surface's own alpha known without its vertices: its opacity. The
        // triangle any-hit stage multiplies in the texture's and the vertex colours'.
        material.color_a.w
    } else {
        1.0
    }
}

/// Whether a cutout's surface is there at an object-space point (not a hole).
pub fn cutout_solid(material: &Material, object_point: Vec3) -> bool {
    cutout_alpha(material, object_point) >= material.cutout_threshold
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
            cutout_pattern: 0,
            cutout_scale: 0.0,
            cutout_threshold: 0.0,
            color_a: Vec4::new(1.0, 1.0, 1.0, 1.0),
            color_b: Vec4::new(0.0, 0.0, 0.0, 2.0),
            ..Material::default()
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

    /// Checker holes alternate over x and z and ignore y; disc holes sit at cell centres with
    /// the threshold as their radius in half-cells.
    #[test]
    fn cutout_patterns() {
        let checker = Material::cutout(CUTOUT_CHECKER, 2.0, 0.5);
        assert!(cutout_solid(&checker, Vec3::new(0.25, 0.0, 0.25)));
        assert!(!cutout_solid(&checker, Vec3::new(0.75, 0.0, 0.25)));
        assert!(cutout_solid(&checker, Vec3::new(0.75, 5.0, 0.75)));
        assert!(!cutout_solid(&checker, Vec3::new(-0.25, 0.0, 0.25)), "cells below zero alternate too");
        let discs = Material::cutout(CUTOUT_DISCS, 1.0, 0.5);
        assert!(!cutout_solid(&discs, Vec3::new(0.5, 0.0, 0.5)), "a cell's centre is a hole");
        assert!(!cutout_solid(&discs, Vec3::new(0.5 + 0.24, 0.0, 0.5)));
        assert!(cutout_solid(&discs, Vec3::new(0.5 + 0.26, 0.0, 0.5)));
        assert!(cutout_solid(&discs, Vec3::new(0.0, 0.0, 0.0)), "a cell's corner is solid");
        let mut plain = discs;
        plain.cutout_pattern = crate::bindings::CUTOUT_NONE;
        assert!(cutout_solid(&plain, Vec3::new(0.5, 0.0, 0.5)));
    }
}
