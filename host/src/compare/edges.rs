//! Edges inside one surface. Where two sets' first samples hit two triangles of one mesh
//! instance that share an edge, at the same distance, on that edge, either answer is right:
//! the driver intersects triangles for both sets, and their camera rays differ by a few ULPs, so
//! a ray on a shared diagonal goes to one triangle in one set and to the other in the other.
//! Such pixels are counted apart from hit mismatches (`ImageDiff::internal_edges`), as
//! silhouettes are, and do not fail a comparison.

use super::diff::{on_silhouette, ImageDiff};
use crate::explain::rays::Camera;
use crate::reference::scene::{RefObject, SceneReference};
use crate::reference::shapes::RefShape;
use crate::render::{RenderOutput, NO_HIT_ID};
use crate::scene::Scene;
use glam::DVec3;

/// How near the shared edge, and how near each other, the ray's crossings of the two
/// triangles' planes must be: 64 f32 ULPs of the magnitudes involved (the ray's origin, the
/// edge's vertices, the distance). Two sets' camera rays differ by a few ULPs; a ray a pixel
/// away from the edge is thousands of ULPs away.
const EDGE_BAND: f64 = 64.0 * f32::EPSILON as f64;

/// Moves the hit mismatches of `diff` (of `a` against `b`, renders of `scene`) that lie on an
/// edge two triangles of one mesh share into `diff.internal_edges`.
pub fn set_apart(diff: &mut ImageDiff, scene: &Scene, a: &RenderOutput, b: &RenderOutput) {
    // Candidates: both hit one object, at different primitives.
    let candidates: Vec<(usize, u64, u64)> = (a.hit_ids.iter().zip(&b.hit_ids).enumerate())
        .filter(|&(_, (&ia, &ib))| ia != ib && ia != NO_HIT_ID && ib != NO_HIT_ID && ia >> 32 == ib >> 32)
        .map(|(i, (&ia, &ib))| (i, ia, ib))
        .collect();
    if candidates.is_empty() {
        return;
    }
    let Ok(reference) = SceneReference::new(scene) else { return };
    let camera = Camera::new(scene, (a.width, a.height));
    let width = a.width as usize;
    let mut found = 0;
    for (i, ia, ib) in candidates {
        let Some(object) = reference.objects.get((ia >> 32) as usize) else { continue };
        let ray = camera.sample(((i % width) as u32, (i / width) as u32), 0).ray;
        let (origin, direction) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
        if across_shared_edge(object, (ia as u32, ib as u32), origin, direction) {
            found += 1;
            diff.internal_edge_pixels.push(i);
            let (x, y, h) = (i % width, i / width, a.height as usize);
            if !on_silhouette(&a.hit_ids, width, h, x, y) && !on_silhouette(&b.hit_ids, width, h, x, y) {
                diff.hit_mismatches_off_silhouette -= 1;
            }
        }
    }
    diff.hit_mismatches -= found;
    diff.internal_edges = found;
}

/// Whether a world-space ray meets triangles `pa` and `pb` of `object` where they share an
/// edge: both planes at the same distance, on the edge, within [`EDGE_BAND`].
fn across_shared_edge(object: &RefObject, (pa, pb): (u32, u32), origin: DVec3, direction: DVec3) -> bool {
    let triangle = |k: u32| match object.shapes.get(k as usize) {
        Some(RefShape::Triangle { p }) => Some(p.map(|v| object.object_to_world.transform_point3(v))),
        _ => None,
    };
    let (Some(a), Some(b)) = (triangle(pa), triangle(pb)) else { return false };
    let shared: Vec<DVec3> = a.iter().filter(|p| b.contains(p)).copied().collect();
    let [e0, e1] = shared[..] else { return false };
    let (Some(ta), Some(tb)) = (plane_t(&a, origin, direction), plane_t(&b, origin, direction)) else { return false };
    let length = direction.length();
    let scale = origin.abs().max_element() + e0.abs().max_element().max(e1.abs().max_element()) + ta.abs() * length;
    let band = EDGE_BAND * scale;
    let point = origin + direction * ta;
    let edge = e1 - e0;
    let along = ((point - e0).dot(edge) / edge.length_squared()).clamp(0.0, 1.0);
    (ta - tb).abs() * length <= band && (point - (e0 + edge * along)).length() <= band
}

/// The ray parameter at which a ray crosses the plane of triangle `p`; `None` parallel to it.
fn plane_t(p: &[DVec3; 3], origin: DVec3, direction: DVec3) -> Option<f64> {
    let normal = (p[1] - p[0]).cross(p[2] - p[0]);
    let facing = normal.dot(direction);
    (facing != 0.0).then(|| normal.dot(p[0] - origin) / facing)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat4;

    fn quad() -> RefObject {
        let (p0, p1, p2, p3) = (DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y);
        RefObject {
            shapes: vec![RefShape::Triangle { p: [p0, p1, p2] }, RefShape::Triangle { p: [p0, p2, p3] }],
            world_to_object: DMat4::from_translation(DVec3::new(-3.0, 0.0, 0.0)),
            object_to_world: DMat4::from_translation(DVec3::new(3.0, 0.0, 0.0)),
            cutout: None,
            mask: 0xff,
            single_sided: false,
            vertex_alphas: Vec::new(),
        }
    }

    #[test]
    fn a_ray_on_the_shared_diagonal_is_on_an_internal_edge_and_one_beside_it_is_not() {
        let o = quad();
        let down = DVec3::new(0.0, 0.0, -1.0);
        let on = DVec3::new(3.5, 0.5, 5.0);
        assert!(across_shared_edge(&o, (0, 1), on, down));
        // 1e-9 off the diagonal: f32 rounding of a ray; 1e-3 off: a pixel away, a real mismatch.
        assert!(across_shared_edge(&o, (0, 1), on + DVec3::new(1e-9, 0.0, 0.0), down));
        assert!(!across_shared_edge(&o, (0, 1), on + DVec3::new(1e-3, 0.0, 0.0), down));
        // Past the end of the shared edge, in the plane: not on it.
        assert!(!across_shared_edge(&o, (0, 1), DVec3::new(4.5, 1.5, 5.0), down));
        // The same triangle twice shares three vertices, not an edge.
        assert!(!across_shared_edge(&o, (0, 0), on, down));
    }
}
