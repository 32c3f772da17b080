//! The `edges` generator: rays at the points where a mesh's triangles meet, a watertight test.
//! Each ray is aimed at a point of an edge two triangles share, or at a vertex every edge of
//! whose fan is shared, from outside and across the surface (every triangle there faces it),
//! so it must hit the mesh there or before: a gap between the triangles lets it through. The
//! f64 reference decides such rays where the mesh is closed (`reference::watertight`).

use crate::reference::scene::RefObject;
use crate::reference::shapes::RefShape;
use glam::{DVec3, Vec3};
use std::collections::HashMap;

/// Smallest cosine between a ray and the normal of every triangle at its point.
const FACING: f64 = 0.1;
/// Largest tilt of a ray from the mean normal of the triangles at its point, in radians.
const TILT: f64 = std::f64::consts::FRAC_PI_4;

/// A point where triangles meet, and their unit normals.
struct Meeting {
    /// An edge's two corners (the point is drawn between them), or a vertex twice.
    ends: [DVec3; 2],
    normals: Vec<DVec3>,
}

/// The object's interior edges and vertices: those its triangles share all round.
fn meetings(triangles: &[[DVec3; 3]]) -> (Vec<Meeting>, Vec<Meeting>) {
    let key = |a: DVec3, b: DVec3| {
        let (a, b) = (a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits));
        if a <= b {
            (a, b)
        } else {
            (b, a)
        }
    };
    let normal = |p: &[DVec3; 3]| (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
    let mut edges: HashMap<_, Vec<usize>> = HashMap::new();
    for (i, p) in triangles.iter().enumerate() {
        for j in 0..3 {
            edges.entry(key(p[j], p[(j + 1) % 3])).or_default().push(i);
        }
    }
    let shared = |a: DVec3, b: DVec3| edges.get(&key(a, b)).is_some_and(|t| t.len() == 2);
    let mut interior = Vec::new();
    let mut fans: HashMap<[u64; 3], (DVec3, Vec<usize>, bool)> = HashMap::new();
    for (i, p) in triangles.iter().enumerate() {
        for j in 0..3 {
            let (a, b) = (p[j], p[(j + 1) % 3]);
            let fan = fans.entry(a.to_array().map(f64::to_bits)).or_insert((a, Vec::new(), true));
            fan.1.push(i);
            fan.2 &= shared(a, b) && shared(a, p[(j + 2) % 3]);
            let owners = &edges[&key(a, b)];
            // Each shared edge once, from its first triangle.
            if owners.len() == 2 && owners[0] == i {
                interior
                    .push(Meeting { ends: [a, b], normals: owners.iter().map(|&t| normal(&triangles[t])).collect() });
            }
        }
    }
    let vertices = fans
        .into_values()
        .filter(|(_, _, closed)| *closed)
        .map(|(v, fan, _)| Meeting { ends: [v, v], normals: fan.iter().map(|&t| normal(&triangles[t])).collect() })
        .collect();
    (interior, vertices)
}

/// `count` rays at object `object`'s meetings (every other one a vertex, where there are any),
/// from `distance` bounding radii away, as world-space origins and unit directions; `draw(k,
/// d)` is random number `d` of ray `k`.
pub(super) fn edge_rays(
    o: &RefObject,
    object: usize,
    count: u32,
    distance: f32,
    draw: impl Fn(u32, u32) -> f64,
) -> Result<Vec<(Vec3, Vec3)>, String> {
    let triangles: Vec<[DVec3; 3]> = o
        .shapes
        .iter()
        .map(|s| match *s {
            RefShape::Triangle { p } => Some(p),
            _ => None,
        })
        .collect::<Option<_>>()
        .ok_or_else(|| format!("object {object} is not a mesh: `edges` probes where a mesh's triangles meet"))?;
    let (mut edges, mut vertices) = meetings(&triangles);
    // Meetings no ray can cross from outside (a fold back on itself) are left out.
    let crossable = |m: &Meeting| mean(&m.normals).is_some_and(|n| m.normals.iter().all(|x| x.dot(n) >= FACING));
    edges.retain(crossable);
    vertices.retain(crossable);
    if edges.is_empty() {
        return Err(format!("object {object} has no edge that two of its triangles share"));
    }
    let size = o.shapes.iter().map(crate::reference::shapes::bounding_radius).fold(0.0, f64::max);
    Ok((0..count)
        .map(|k| {
            let r = |d: u32| draw(k, d);
            let pool = if k % 2 == 1 && !vertices.is_empty() { &vertices } else { &edges };
            let m = &pool[((r(0) * pool.len() as f64) as usize).min(pool.len() - 1)];
            let point = m.ends[0] + (m.ends[1] - m.ends[0]) * (0.1 + 0.8 * r(1));
            let across = direction(&m.normals, r(2), r(3));
            let origin = point - across * f64::from(distance) * size;
            let world_origin = o.object_to_world.transform_point3(origin);
            let world_dir = o.object_to_world.transform_vector3(across).normalize();
            (world_origin.as_vec3(), world_dir.as_vec3())
        })
        .collect())
}

fn mean(normals: &[DVec3]) -> Option<DVec3> {
    normals.iter().sum::<DVec3>().try_normalize()
}

/// Into the surface whose normals are `normals`: against their mean, tilted by up to `TILT`
/// (by the numbers `a` and `b`) where every triangle still faces the ray.
fn direction(normals: &[DVec3], a: f64, b: f64) -> DVec3 {
    let n = mean(normals).unwrap_or(DVec3::Y);
    let e1 = n.any_orthonormal_vector();
    let sideways = e1 * (std::f64::consts::TAU * b).cos() + n.cross(e1) * (std::f64::consts::TAU * b).sin();
    let tilt = TILT * a;
    let tilted = -(n * tilt.cos() + sideways * tilt.sin());
    if normals.iter().all(|x| -x.dot(tilted) >= FACING) {
        tilted
    } else {
        -n
    }
}
