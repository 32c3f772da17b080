//! Tests of `watertight`, through `RefObject::first_shape`, which calls it.

use super::scene::RefObject;
use super::shapes::{RefRay, RefShape};
use glam::{DMat4, DVec3};

fn object(triangles: &[[[f64; 3]; 3]]) -> RefObject {
    RefObject {
        shapes: triangles.iter().map(|t| RefShape::Triangle { p: t.map(DVec3::from) }).collect(),
        world_to_object: DMat4::IDENTITY,
        object_to_world: DMat4::IDENTITY,
        cutout: None,
        mask: 1,
        single_sided: false,
        corners: Vec::new(),
    }
}

fn answer(o: &RefObject, origin: [f64; 3], target: [f64; 3]) -> Option<Option<usize>> {
    let (origin, target) = (DVec3::from(origin), DVec3::from(target));
    let ray = RefRay { origin, direction: target - origin, t_min: 0.0, t_max: 1e30, noise_floor: 0.0 };
    o.first_shape(&ray, super::scene::Faces::Both).map(|h| h.map(|(k, ..)| k))
}

/// A unit square of two triangles meeting along its diagonal: a ray through the diagonal
/// hits; one through its outer edge or corner, where nothing continues the surface, stays
/// ambiguous. Folded along the diagonal into a ridge, a ray from above through the ridge
/// hits; one across it from the side, front of one half and back of the other, grazes the
/// ridge and stays ambiguous.
#[test]
fn shared_edges_are_decided_and_open_ones_are_not() {
    let square = object(&[
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
        [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ]);
    let from = |x: f64, y: f64| [x + 0.3, y - 0.2, 2.0];
    let through_diagonal = answer(&square, from(0.37, 0.37), [0.37, 0.37, 0.0]);
    assert!(matches!(through_diagonal, Some(Some(_))), "{through_diagonal:?}");
    assert_eq!(answer(&square, from(1.0, 0.5), [1.0, 0.5, 0.0]), None, "the outer edge");
    assert_eq!(answer(&square, from(1.0, 1.0), [1.0, 1.0, 0.0]), None, "the outer corner");
    assert_eq!(answer(&square, from(0.6, 0.2), [0.6, 0.2, 0.0]), Some(Some(0)), "well inside");
    let folded = object(&[
        [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0]],
        [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]],
    ]);
    assert!(matches!(answer(&folded, [0.5, 0.5, 3.0], [0.5, 0.5, 0.0]), Some(Some(_))), "from above");
    assert_eq!(answer(&folded, [-2.5, 3.5, 0.0], [0.5, 0.5, 0.0]), None, "across the ridge");
}
