//! Hit mismatches where either answer is right, counted apart from the others (as
//! silhouettes are) and not failing a comparison:
//! - **Edges inside one surface.** Where two sets' first samples hit two triangles of one mesh
//!   instance that share an edge, at the same distance, on that edge: the driver intersects
//!   triangles for both sets, and their camera rays differ by a few ULPs, so a ray on a shared
//!   diagonal goes to one triangle in one set and to the other in the other
//!   (`ImageDiff::internal_edges`).
//! - **Alpha at its cutoff.** Where one set kept a cutout's hit that the f64 reference finds
//!   within rounding of the cutoff (a tie, or a gradient's contour within the hit point's
//!   noise), and the other set's hit lies behind it or it missed: the two sets' barycentrics
//!   differ by a few ULPs there (`ImageDiff::alpha_edges`). Alpha the reference does not
//!   compute (a texture's) is not set apart.

use super::diff::{color_diff_except, diff, on_silhouette, ImageDiff};
use crate::explain::rays::Camera;
use crate::reference::cutout::Coverage;
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

/// The differences of two renders `a` and `b` of `scene`, with the hit mismatches where either
/// answer is right set apart: what `compare`, `bench` and the tests judge.
pub fn scene_diff(scene: &Scene, a: &RenderOutput, b: &RenderOutput) -> ImageDiff {
    let mut d = diff(a, b, scene.file.parity.pixel_threshold);
    set_apart(&mut d, scene, a, b);
    d
}

/// Moves the hit mismatches of `diff` (of `a` against `b`, renders of `scene`) where either
/// answer is right into `diff.internal_edges` and `diff.alpha_edges`.
pub fn set_apart(diff: &mut ImageDiff, scene: &Scene, a: &RenderOutput, b: &RenderOutput) {
    if diff.hit_mismatches == 0 {
        return;
    }
    let Ok(reference) = SceneReference::new(scene) else { return };
    let camera = Camera::new(scene, (a.width, a.height));
    let (width, height) = (a.width as usize, a.height as usize);
    for (i, (&ia, &ib)) in a.hit_ids.iter().zip(&b.hit_ids).enumerate().filter(|(_, (ia, ib))| ia != ib) {
        let ray = camera.sample(((i % width) as u32, (i / width) as u32), 0).ray;
        let (origin, direction) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
        let reach = (f64::from(ray.origin.w), f64::from(ray.direction.w));
        let apart = if internal_edge(&reference, (ia, ib), origin, direction) {
            &mut diff.internal_edge_pixels
        } else if alpha_edge(&reference, (ia, ib), (origin, direction), reach)
            || alpha_edge(&reference, (ib, ia), (origin, direction), reach)
        {
            &mut diff.alpha_edge_pixels
        } else {
            continue;
        };
        apart.push(i);
        diff.hit_mismatches -= 1;
        let (x, y) = (i % width, i / width);
        if !on_silhouette(&a.hit_ids, width, height, x, y) && !on_silhouette(&b.hit_ids, width, height, x, y) {
            diff.hit_mismatches_off_silhouette -= 1;
        }
    }
    diff.internal_edges = diff.internal_edge_pixels.len() as u64;
    diff.alpha_edges = diff.alpha_edge_pixels.len() as u64;
    if diff.alpha_edges > 0 {
        let threshold = scene.file.parity.pixel_threshold;
        diff.color = color_diff_except(&a.rgba, &b.rgba, threshold, &diff.alpha_edge_pixels);
    }
}

/// Whether hits `ia` and `ib` are two triangles of one object that the ray meets on the edge
/// they share.
fn internal_edge(reference: &SceneReference, (ia, ib): (u64, u64), origin: DVec3, direction: DVec3) -> bool {
    if ia == NO_HIT_ID || ib == NO_HIT_ID || ia >> 32 != ib >> 32 {
        return false;
    }
    let Some(object) = reference.objects.get((ia >> 32) as usize) else { return false };
    across_shared_edge(object, (ia as u32, ib as u32), origin, direction)
}

/// Whether hit `kept` is on a cutout where the reference finds the alpha at its cutoff, and
/// hit `other` (or a miss) lies behind it: the set that kept the hit and the set that let the
/// ray through are both right.
fn alpha_edge(reference: &SceneReference, (kept, other): (u64, u64), ray: (DVec3, DVec3), reach: (f64, f64)) -> bool {
    let crossing = |id: u64| {
        let object = reference.objects.get((id >> 32) as usize)?;
        object.crossing(id as u32 as usize, ray.0, ray.1, reach)
    };
    if kept == NO_HIT_ID {
        return false;
    }
    let Some((t, Coverage::Edge)) = crossing(kept) else { return false };
    if other == NO_HIT_ID {
        return true;
    }
    // Behind by more than rounding: the other set let the ray through the cutout.
    crossing(other).is_some_and(|(t_other, _)| t_other > t)
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
    use crate::reference::cutout::{Corners, RefCutout};
    use glam::DMat4;
    use twinray_shared::bindings::CUTOUT_TEXTURE;
    use twinray_shared::layout::Material;

    fn quad() -> RefObject {
        let (p0, p1, p2, p3) = (DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y);
        RefObject {
            shapes: vec![RefShape::Triangle { p: [p0, p1, p2] }, RefShape::Triangle { p: [p0, p2, p3] }],
            world_to_object: DMat4::from_translation(DVec3::new(-3.0, 0.0, 0.0)),
            object_to_world: DMat4::from_translation(DVec3::new(3.0, 0.0, 0.0)),
            cutout: None,
            mask: 0xff,
            single_sided: false,
            corners: Vec::new(),
        }
    }

    /// The quad with alpha x over it (vertex alphas 0 at x = 0, 1 at x = 1) cut at 0.5, in front
    /// of a plain triangle at z = -1 (object 1).
    fn gradient_before_backdrop() -> SceneReference {
        let gradient = RefObject {
            cutout: RefCutout::of(&Material::cutout(CUTOUT_TEXTURE, 1.0, 0.5)),
            corners: [[0.0, 1.0, 1.0], [0.0, 1.0, 0.0]].map(|alpha| Corners { alpha, ..Corners::default() }).to_vec(),
            ..quad()
        };
        let corners = [DVec3::new(-10.0, -10.0, -1.0), DVec3::new(10.0, -10.0, -1.0), DVec3::new(0.0, 10.0, -1.0)];
        let backdrop = RefObject {
            shapes: vec![RefShape::Triangle { p: corners }],
            world_to_object: DMat4::IDENTITY,
            object_to_world: DMat4::IDENTITY,
            ..quad()
        };
        SceneReference { objects: vec![gradient, backdrop] }
    }

    #[test]
    fn a_hit_kept_at_the_alpha_cutoff_is_either_right_and_one_away_from_it_is_not() {
        let scene = gradient_before_backdrop();
        let down = (DVec3::new(0.0, 0.0, -1.0), (0.0, 100.0));
        let at = |x: f64| DVec3::new(x, 0.25, 5.0);
        let (quad_hit, backdrop_hit) = (0u64, 1u64 << 32);
        let edge = |x: f64, kept: u64, other: u64| alpha_edge(&scene, (kept, other), (at(x), down.0), down.1);
        // On the contour (world x = 3.5), and within rounding of it: kept there, or let
        // through to the backdrop or a miss, both right.
        assert!(edge(3.5, quad_hit, backdrop_hit));
        assert!(edge(3.5 + 1e-9, quad_hit, NO_HIT_ID));
        // A hundredth away, the alpha is decided: 0.51 solid, 0.49 a hole.
        assert!(!edge(3.51, quad_hit, backdrop_hit));
        assert!(!edge(3.49, quad_hit, backdrop_hit));
        // The backdrop has no cutout, and the quad lies in front of it, not behind.
        assert!(!edge(3.5, backdrop_hit, quad_hit));
        // The other set's hit must lie behind the kept one: the quad is not behind the backdrop.
        let behind_first =
            |kept, other| alpha_edge(&scene, (kept, other), (DVec3::new(3.5, 0.25, -5.0), -down.0), down.1);
        assert!(!behind_first(quad_hit, backdrop_hit));
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
