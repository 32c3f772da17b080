//! The f64 reference's ambiguous band: measured sideways from the ray, so it is wide for
//! grazing hits, covers rays nearly along a face or through a shallow graze, and grows with
//! the world-space magnitude a ray had before an instance transform.

use glam::DVec3;
use twinray_host::reference::shapes::{intersect, RefRay, RefShape, Verdict};

fn ray(o: [f64; 3], d: [f64; 3]) -> RefRay {
    RefRay { origin: DVec3::from(o), direction: DVec3::from(d), t_min: 0.0, t_max: 1e30, noise_floor: 0.0 }
}

/// 16 f32 ULPs at magnitude 5: the band of the rays below, which start 5 from the shape.
const NOISE_AT_5: f64 = 16.0 * 5.0 / 16_777_216.0;

#[test]
fn box_rays_nearly_along_a_face_are_ambiguous_within_noise_of_its_plane() {
    let b = RefShape::Box { half: DVec3::ONE };
    // Along the top face, tilted by 1e-9: the slab test alone sees a clean hit or miss.
    for (height, expected) in [
        (1.0 + 0.5 * NOISE_AT_5, Verdict::Ambiguous),
        (1.0 - 0.5 * NOISE_AT_5, Verdict::Ambiguous),
        (1.0 + 4.0 * NOISE_AT_5, Verdict::Miss),
    ] {
        assert_eq!(intersect(&b, &ray([-5.0, height, 0.3], [1.0, 1e-9, 0.0])), expected, "height {height}");
    }
    assert!(matches!(intersect(&b, &ray([-5.0, 1.0 - 4.0 * NOISE_AT_5, 0.3], [1.0, 1e-9, 0.0])), Verdict::Hit { .. }));
}

#[test]
fn a_rim_band_widens_for_grazing_hits() {
    let disk = RefShape::Disk { radius: 1.0 };
    // Hitting 2 noise-widths inside the rim: decided head-on, ambiguous at a 1e-2 cosine.
    let inside = 1.0 - 2.0 * NOISE_AT_5;
    let head_on = ray([inside, 5.0, 0.0], [0.0, -1.0, 0.0]);
    assert!(matches!(intersect(&disk, &head_on), Verdict::Hit { .. }));
    let d = DVec3::new(-1.0, -0.01, 0.0).normalize();
    let grazing = ray((DVec3::new(inside, 0.0, 0.0) - d * 5.0).into(), d.into());
    assert_eq!(intersect(&disk, &grazing), Verdict::Ambiguous);
}

#[test]
fn cone_tangency_is_measured_as_a_distance_not_a_chord() {
    let k = RefShape::Cone { radius: 1.0, half_height: 1.0 };
    // Apex (0, 1, 0), radius 0.5 at y = 0. A ray along z in the plane x = 0.5 - depth dips
    // `depth` into the cone there, with a chord of 2 sqrt(depth) far longer than the noise.
    let noise = 16.0 * 5.0 / 16_777_216.0;
    let inside = |depth: f64| intersect(&k, &ray([0.5 - depth, 0.0, -5.0], [0.0, 0.0, 1.0]));
    assert_eq!(inside(0.1 * noise), Verdict::Ambiguous);
    assert!(matches!(inside(20.0 * noise), Verdict::Hit { .. }));
}

#[test]
fn torus_grazes_through_the_tube_are_ambiguous() {
    let t = RefShape::Torus { major: 1.0, minor: 0.25 };
    // Along x at height y: the tube's top is at y = 0.25; dipping below it by a fraction of
    // the noise crosses the surface twice, within noise.
    let at = |y: f64| intersect(&t, &ray([-5.0, y, 0.0], [1.0, 0.0, 0.0]));
    assert_eq!(at(0.25 - 0.2 * NOISE_AT_5), Verdict::Ambiguous);
    assert!(matches!(at(0.25 - 50.0 * NOISE_AT_5), Verdict::Hit { .. }));
}

#[test]
fn a_ray_parallel_to_a_triangle_beside_its_plane_misses_it() {
    let tri = RefShape::Triangle { p: [DVec3::ZERO, DVec3::X, DVec3::Y] };
    assert_eq!(intersect(&tri, &ray([-5.0, 0.2, 1e-3], [1.0, 0.0, 0.0])), Verdict::Miss);
    assert_eq!(intersect(&tri, &ray([-5.0, 0.2, 0.0], [1.0, 0.0, 0.0])), Verdict::Ambiguous);
}

#[test]
fn the_noise_floor_of_an_instance_widens_the_band() {
    let s = RefShape::Sphere { center: DVec3::ZERO, radius: 1.0 };
    // Passing 1e-5 above the top: decided near the origin, noise 1e3 away (16 ULPs = 1e-3).
    let mut r = ray([-5.0, 1.0 + 1e-5, 0.0], [1.0, 0.0, 0.0]);
    assert_eq!(intersect(&s, &r), Verdict::Miss);
    r.noise_floor = 1e3;
    assert_eq!(intersect(&s, &r), Verdict::Ambiguous);
}
