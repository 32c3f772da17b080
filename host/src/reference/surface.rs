//! Points on a shape's surface, drawn uniformly by area from the shape's own parametrisation,
//! so that a generator makes every point it is asked for however thin, long or small the shape
//! is (tracing towards it from random directions finds almost nothing on a needle).

use super::shapes::RefShape;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// A source of numbers in [0, 1): each call gives the next one of a deterministic stream.
pub type Draw<'a> = &'a mut dyn FnMut() -> f64;

/// Surface area of the shape, in object space.
pub fn area(shape: &RefShape) -> f64 {
    let pieces = pieces(shape);
    pieces.iter().map(|p| p.0).sum()
}

/// A point of the shape's surface drawn uniformly by area, with its outward unit normal (for
/// flat one-sided pieces: rectangles, disks and triangles, the normal's side is drawn too).
pub fn sample(shape: &RefShape, draw: Draw) -> (DVec3, DVec3) {
    let pieces = pieces(shape);
    let total: f64 = pieces.iter().map(|p| p.0).sum();
    let mut pick = draw() * total;
    let mut chosen = pieces.len() - 1;
    for (i, (a, _)) in pieces.iter().enumerate() {
        if pick < *a {
            chosen = i;
            break;
        }
        pick -= a;
    }
    point(shape, pieces[chosen].1, draw)
}

/// The shape's axis-aligned bounding box in object space, as (min, max).
pub fn bounding_box(shape: &RefShape) -> (DVec3, DVec3) {
    let half = match *shape {
        RefShape::Sphere { center, radius } => return (center - radius, center + radius),
        RefShape::Triangle { p } => return (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2])),
        RefShape::Rectangle { half_x, half_z } => DVec3::new(half_x, 0.0, half_z),
        RefShape::Disk { radius } => DVec3::new(radius, 0.0, radius),
        RefShape::Box { half } => half,
        RefShape::Cylinder { radius, half_height } | RefShape::Cone { radius, half_height } => {
            DVec3::new(radius, half_height, radius)
        }
        RefShape::Torus { major, minor } => DVec3::new(major + minor, minor, major + minor),
        RefShape::Traced { shape, a } => (shape.half_extent)(a),
        RefShape::Own { bounds, .. } => return bounds,
    };
    (-half, half)
}

/// Which part of a shape a point lies on.
#[derive(Clone, Copy)]
enum Piece {
    Whole,
    /// A box face: axis and sign.
    Face(usize, f64),
    Side,
    /// A cap of a cylinder (y sign) or the cone's base (-1).
    Cap(f64),
}

/// The shape's parts with their areas.
fn pieces(shape: &RefShape) -> Vec<(f64, Piece)> {
    match *shape {
        RefShape::Box { half } => (0..6)
            .map(|f| {
                let (axis, sign) = (f % 3, if f < 3 { 1.0 } else { -1.0 });
                (4.0 * half[(axis + 1) % 3] * half[(axis + 2) % 3], Piece::Face(axis, sign))
            })
            .collect(),
        RefShape::Cylinder { radius, half_height } => vec![
            (TAU * radius * 2.0 * half_height, Piece::Side),
            (PI * radius * radius, Piece::Cap(1.0)),
            (PI * radius * radius, Piece::Cap(-1.0)),
        ],
        RefShape::Cone { radius, half_height } => {
            vec![(PI * radius * radius.hypot(2.0 * half_height), Piece::Side), (PI * radius * radius, Piece::Cap(-1.0))]
        }
        RefShape::Sphere { radius, .. } => vec![(4.0 * PI * radius * radius, Piece::Whole)],
        RefShape::Rectangle { half_x, half_z } => vec![(4.0 * half_x * half_z, Piece::Whole)],
        RefShape::Disk { radius } => vec![(PI * radius * radius, Piece::Whole)],
        RefShape::Torus { major, minor } => vec![(4.0 * PI * PI * major * minor, Piece::Whole)],
        RefShape::Triangle { p } => vec![(0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length(), Piece::Whole)],
        // Known by its distance alone: no parametrisation to draw points from (area 0).
        RefShape::Traced { .. } | RefShape::Own { .. } => Vec::new(),
    }
}

/// Either side of a flat one-sided piece, by a draw.
fn side(normal: DVec3, draw: Draw) -> DVec3 {
    if draw() < 0.5 {
        normal
    } else {
        -normal
    }
}

/// A point of a disk of `radius` in the plane y, uniform by area.
fn in_disk(radius: f64, y: f64, draw: Draw) -> DVec3 {
    let (rho, phi) = (radius * draw().sqrt(), TAU * draw());
    DVec3::new(rho * phi.cos(), y, rho * phi.sin())
}

fn point(shape: &RefShape, piece: Piece, draw: Draw) -> (DVec3, DVec3) {
    let span = |half: f64, draw: Draw| (2.0 * draw() - 1.0) * half;
    match (*shape, piece) {
        (RefShape::Box { half }, Piece::Face(axis, sign)) => {
            let (mut p, mut n) = (DVec3::ZERO, DVec3::ZERO);
            p[(axis + 1) % 3] = span(half[(axis + 1) % 3], draw);
            p[(axis + 2) % 3] = span(half[(axis + 2) % 3], draw);
            p[axis] = sign * half[axis];
            n[axis] = sign;
            (p, n)
        }
        (RefShape::Cylinder { radius, half_height }, Piece::Side) => {
            let (y, phi) = (span(half_height, draw), TAU * draw());
            let n = DVec3::new(phi.cos(), 0.0, phi.sin());
            (n * radius + DVec3::Y * y, n)
        }
        (RefShape::Cylinder { radius, half_height }, Piece::Cap(sign)) => {
            (in_disk(radius, sign * half_height, draw), DVec3::Y * sign)
        }
        (RefShape::Cone { radius, half_height }, Piece::Side) => {
            // Area grows linearly with the distance from the apex: that distance goes as sqrt.
            let (s, phi) = (draw().sqrt(), TAU * draw());
            let ring = DVec3::new(phi.cos(), 0.0, phi.sin());
            let p = ring * (radius * s) + DVec3::Y * (half_height - 2.0 * half_height * s);
            (p, (ring * 2.0 * half_height + DVec3::Y * radius).normalize())
        }
        (RefShape::Cone { radius, half_height }, _) => (in_disk(radius, -half_height, draw), -DVec3::Y),
        (RefShape::Sphere { center, radius }, _) => {
            let z = 2.0 * draw() - 1.0;
            let phi = TAU * draw();
            let r = (1.0 - z * z).max(0.0).sqrt();
            let n = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            (center + n * radius, n)
        }
        (RefShape::Rectangle { half_x, half_z }, _) => {
            (DVec3::new(span(half_x, draw), 0.0, span(half_z, draw)), side(DVec3::Y, draw))
        }
        (RefShape::Disk { radius }, _) => (in_disk(radius, 0.0, draw), side(DVec3::Y, draw)),
        (RefShape::Torus { major, minor }, _) => torus_point(major, minor, draw),
        (RefShape::Triangle { p }, _) => {
            let (a, b) = (draw(), draw());
            let (u, v) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
            let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
            (p[0] + (p[1] - p[0]) * u + (p[2] - p[0]) * v, side(n, draw))
        }
        (_, _) => unreachable!("pieces() gives each shape only its own pieces"),
    }
}

/// Tries of the torus's rejection step: each is accepted with probability at least
/// (R - r) / (R + r), so failing all of them is astronomically unlikely for r < R; the last
/// try is kept if it happens (the shape checks reject r >= R).
const TORUS_TRIES: u32 = 256;

/// The area element of the tube at angle v is proportional to R + r cos v: rejection on it.
fn torus_point(major: f64, minor: f64, draw: Draw) -> (DVec3, DVec3) {
    let mut v = 0.0;
    for _ in 0..TORUS_TRIES {
        v = TAU * draw();
        if draw() * (major + minor) <= major + minor * v.cos() {
            break;
        }
    }
    let u = TAU * draw();
    let ring = DVec3::new(u.cos(), 0.0, u.sin());
    let n = ring * v.cos() + DVec3::Y * v.sin();
    (ring * major + n * minor, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::ray::{RefRay, Verdict};
    use crate::reference::shapes::{intersect, RefShape};

    fn stream(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Every point lies on the surface: a ray from just outside along -normal hits it right there.
    #[test]
    fn points_lie_on_the_surface_with_outward_normals() {
        let shapes = [
            RefShape::Sphere { center: DVec3::new(0.5, 0.0, 0.0), radius: 2.0 },
            RefShape::Box { half: DVec3::new(1e-2, 1.0, 10.0) },
            RefShape::Cylinder { radius: 1e-3, half_height: 500.0 },
            RefShape::Cone { radius: 1.0, half_height: 3.0 },
            RefShape::Torus { major: 1.0, minor: 1e-3 },
            RefShape::Disk { radius: 2.0 },
        ];
        let mut draw = stream(7);
        for shape in &shapes {
            let mut ambiguous = 0;
            for k in 0..500 {
                let (p, n) = sample(shape, &mut draw);
                let back = 1e-4 * super::super::shapes::bounding_radius(shape);
                let ray = RefRay { origin: p + n * back, direction: -n, t_min: 0.0, t_max: 1e30, noise_floor: 0.0 };
                match intersect(shape, &ray) {
                    Verdict::Hit { t, normal } => {
                        assert!((t - back).abs() < 1e-3 * back, "{shape:?} point {k}: hit at {t}, not {back}");
                        // Flat pieces are one-sided: either side may be drawn.
                        let flat = matches!(shape, RefShape::Disk { .. });
                        let agree = if flat { normal.dot(n).abs() } else { normal.dot(n) };
                        assert!(agree > 0.999, "{shape:?} point {k}: normal {normal}, drawn {n}");
                    }
                    // Points within float noise of an edge or rim.
                    Verdict::Ambiguous => ambiguous += 1,
                    Verdict::Miss => panic!("{shape:?} point {k} at {p}, normal {n}: missed"),
                }
            }
            assert!(ambiguous < 10, "{shape:?}: {ambiguous} of 500 points ambiguous");
        }
    }

    /// Uniform by area: the thin torus's outer half (cos v > 0) holds (1 + 2r/(pi R)) / 2 of it.
    #[test]
    fn torus_points_follow_the_area() {
        let mut draw = stream(3);
        let (major, minor) = (1.0, 0.8);
        let outer = (0..20000)
            .filter(|_| {
                let (p, _) = sample(&RefShape::Torus { major, minor }, &mut draw);
                p.x.hypot(p.z) > major
            })
            .count() as f64
            / 20000.0;
        let expected = 0.5 + minor / (PI * major);
        assert!((outer - expected).abs() < 0.015, "outer share {outer}, expected {expected}");
    }
}
