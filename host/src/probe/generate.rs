//! Ray generators of probe case files (docs/probe-format.md): camera rays through a
//! silhouette, secondary rays from a surface, grazing rays from far away, rays lying in
//! (or just beside) a face plane, and rays where a mesh's triangles meet (`edges`). Deterministic: the same keys give the same rays.

use crate::reference::scene::{RefObject, SceneReference};
use crate::reference::shapes::RefShape;
use crate::reference::surface;
use glam::{DVec3, Vec3};
use serde::Deserialize;
use twinray_shared::layout::ProbeRay;
use twinray_shared::offset::offset_ray;
use twinray_shared::random::random;

/// t_min of the textbook shadow ray: a fixed epsilon, from an origin on the surface.
pub const NAIVE_SHADOW_EPSILON: f32 = 1.0e-3;

/// The most rays one generator makes: 2^22, 256 MiB of rays and results between them.
pub const MAX_GENERATED_RAYS: u64 = 1 << 22;

/// t_max of rays that should see everything ahead.
pub(crate) fn far() -> f32 {
    1.0e30
}

pub(crate) fn ray(origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> ProbeRay {
    ProbeRay { origin: origin.extend(t_min), direction: direction.extend(t_max) }
}

fn band() -> f32 {
    1.2
}

fn grazing_angle() -> f32 {
    1.0
}

fn lift() -> f32 {
    1.0e-3
}

fn plane_offset() -> f32 {
    1.0e-4
}

fn plane_distance() -> f32 {
    2.0
}

/// A ray generator of a probe case, by `kind`.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Generator {
    /// `count` x `count` parallel rays from around `from` towards the centre of the object's
    /// bounding box, on a grid `band` times the extent of its projection wide and high (the
    /// grid's rows run along the projection's longest extent): through its silhouette.
    Silhouette {
        object: usize,
        from: [f32; 3],
        count: u32,
        #[serde(default = "band")]
        band: f32,
    },
    /// `count` secondary rays from points on the object's surface (drawn uniformly by area),
    /// offset as shadow rays are (Ray Tracing Gems ch. 6), in random directions of the outer
    /// hemisphere, with t_min 0.
    Surface {
        object: usize,
        count: u32,
        #[serde(default)]
        seed: u32,
    },
    /// `count` rays from `distance` away that arrive at points of the object's surface at
    /// most `angle` degrees from its tangent plane; every other one aims `lift` bounding
    /// radii above its point instead, so that it skims just over the surface.
    Grazing {
        object: usize,
        count: u32,
        distance: f32,
        #[serde(default = "grazing_angle")]
        angle: f32,
        #[serde(default = "lift")]
        lift: f32,
        #[serde(default)]
        seed: u32,
    },
    /// `count` rays lying in the planes of the object's flat faces (box faces, rectangles,
    /// disks, cylinder caps, the cone's base, mesh triangles), from `distance` bounding radii
    /// away across a random point of the face; of each three, one lies in the plane and two
    /// lie `offset` bounding radii inside and outside it.
    FacePlane {
        object: usize,
        count: u32,
        #[serde(default = "plane_offset")]
        offset: f32,
        #[serde(default = "plane_distance")]
        distance: f32,
        #[serde(default)]
        seed: u32,
    },
    /// `count` rays at the points where a mesh's triangles meet (every other one a vertex):
    /// each aimed across the surface at a point of an edge two triangles share, or at a vertex
    /// whose every edge is shared, from `distance` bounding radii away; a gap between the
    /// triangles lets it through (a watertight test).
    Edges {
        object: usize,
        count: u32,
        #[serde(default = "plane_distance")]
        distance: f32,
        #[serde(default)]
        seed: u32,
    },
}

impl Generator {
    /// The name of its kind, as case files write it.
    pub fn kind(&self) -> &'static str {
        match self {
            Generator::Silhouette { .. } => "silhouette",
            Generator::Surface { .. } => "surface",
            Generator::Grazing { .. } => "grazing",
            Generator::FacePlane { .. } => "face_plane",
            Generator::Edges { .. } => "edges",
        }
    }

    /// Its numbers: finite, and those that are sizes > 0 (`from` at most 1e9 away).
    fn check(&self) -> Result<(), String> {
        let positive = |name: &str, v: f32| {
            if v > 0.0 && v <= twinray_shared::shapes::spec::MAX_LENGTH {
                Ok(())
            } else {
                Err(format!("{name} must be in (0, 1e9] (got {v})"))
            }
        };
        match *self {
            Generator::Silhouette { from, band, .. } => {
                if !from.iter().all(|v| v.abs() <= twinray_shared::shapes::spec::MAX_LENGTH) {
                    return Err(format!("from must be finite, at most 1e9 in magnitude (got {from:?})"));
                }
                positive("band", band)
            }
            Generator::Surface { .. } => Ok(()),
            Generator::Grazing { distance, angle, lift, .. } => {
                positive("distance", distance)?;
                if !(0.0..=90.0).contains(&angle) {
                    return Err(format!("angle must be in [0, 90] degrees (got {angle})"));
                }
                if !(0.0..=1.0).contains(&lift) {
                    return Err(format!("lift must be in [0, 1] bounding radii (got {lift})"));
                }
                Ok(())
            }
            Generator::FacePlane { offset, distance, .. } => {
                if !(0.0..=1.0).contains(&offset) {
                    return Err(format!("offset must be in [0, 1] bounding radii (got {offset})"));
                }
                positive("distance", distance)
            }
            Generator::Edges { distance, .. } => positive("distance", distance),
        }
    }

    /// How many rays it is asked for.
    pub fn asked(&self) -> u64 {
        match *self {
            Generator::Silhouette { count, .. } => u64::from(count) * u64::from(count),
            Generator::Surface { count, .. }
            | Generator::Grazing { count, .. }
            | Generator::FacePlane { count, .. }
            | Generator::Edges { count, .. } => u64::from(count),
        }
    }
}

/// The generated rays, each as (robust, naive): they differ only for surface rays.
pub fn generate(generator: &Generator, reference: &SceneReference) -> Result<Vec<(ProbeRay, ProbeRay)>, String> {
    let asked = generator.asked();
    if asked == 0 || asked > MAX_GENERATED_RAYS {
        return Err(format!("makes {asked} rays; a generator makes 1..={MAX_GENERATED_RAYS}"));
    }
    generator.check()?;
    let same = |r: ProbeRay| (r, r);
    match *generator {
        Generator::Silhouette { object, from, count, band } => {
            let view = View::of(find(reference, object)?, Vec3::from(from).as_dvec3())?;
            let (half_u, half_v) = (view.half.0 * f64::from(band), view.half.1 * f64::from(band));
            let n = count;
            Ok((0..n * n)
                .map(|k| {
                    let (i, j) = (k % n, k / n);
                    let u = -half_u + 2.0 * half_u * (f64::from(i) + 0.5) / f64::from(n);
                    let v = -half_v + 2.0 * half_v * (f64::from(j) + 0.5) / f64::from(n);
                    let origin = view.from + view.right * u + view.up * v;
                    same(ray(origin.as_vec3(), view.forward.as_vec3(), 0.0, far()))
                })
                .collect())
        }
        Generator::Surface { object, count, seed } => Ok(surface_points(reference, object, count, seed)?
            .into_iter()
            .map(|(k, point, normal)| {
                let (point, n) = (point.as_vec3(), normal.as_vec3());
                let mut dir = unit(draw(seed, k, 2), draw(seed, k, 3)).as_vec3();
                if dir.dot(n) < 0.0 {
                    dir = -dir;
                }
                let robust = ray(offset_ray(point, n), dir, 0.0, far());
                (robust, ray(point, dir, NAIVE_SHADOW_EPSILON, far()))
            })
            .collect()),
        Generator::Grazing { object, count, distance, angle, lift, seed } => {
            let (_, radius) = bounds(reference, object)?;
            Ok(surface_points(reference, object, count, seed)?
                .into_iter()
                .enumerate()
                .map(|(i, (k, point, normal))| {
                    let (e1, e2) = tangents(normal);
                    let phi = std::f64::consts::TAU * draw(seed, k, 2);
                    let tilt = f64::from(angle).to_radians() * draw(seed, k, 3);
                    let d = (e1 * phi.cos() + e2 * phi.sin()) * tilt.cos() - normal * tilt.sin();
                    let aim = point + normal * (radius * f64::from(lift) * (i % 2) as f64);
                    same(ray((aim - d * f64::from(distance)).as_vec3(), d.as_vec3(), 0.0, far()))
                })
                .collect())
        }
        Generator::FacePlane { object, count, offset, distance, seed } => {
            face_plane_rays(reference, object, count, (offset, distance), seed)
        }
        Generator::Edges { object, count, distance, seed } => {
            let rays =
                super::edges::edge_rays(find(reference, object)?, object, count, distance, |k, d| draw(seed, k, d))?;
            Ok(rays.into_iter().map(|(o, d)| same(ray(o, d, 0.0, far()))).collect())
        }
    }
}

/// Centre and bounding radius of an object, in world space.
fn bounds(reference: &SceneReference, object: usize) -> Result<(DVec3, f64), String> {
    let o = find(reference, object)?;
    let center = o.object_to_world.transform_point3(DVec3::ZERO);
    let scale = o.object_to_world.transform_vector3(DVec3::ONE).length();
    let radius = o.shapes.iter().map(crate::reference::shapes::bounding_radius).fold(0.0, f64::max) * scale;
    Ok((center, radius.max(1e-6)))
}

fn find(reference: &SceneReference, object: usize) -> Result<&RefObject, String> {
    reference
        .objects
        .get(object)
        .ok_or_else(|| format!("no object {object} (the scene has {})", reference.objects.len()))
}

/// `count` points on the object's surface with their outward world normals, each with the
/// index `k` of its random stream: drawn uniformly by object-space area from the shapes' own
/// parametrisations (`reference::surface`), so every point asked for is made, however thin or
/// stretched the object.
fn surface_points(
    reference: &SceneReference,
    object: usize,
    count: u32,
    seed: u32,
) -> Result<Vec<(u32, DVec3, DVec3)>, String> {
    let o = find(reference, object)?;
    let by_distance = o.shapes.iter().find_map(|s| match s {
        RefShape::Traced { shape, .. } => Some(shape.name),
        RefShape::Own { shape, .. } => Some(shape.shape().name),
        _ => None,
    });
    if let Some(name) = by_distance {
        return Err(format!(
            "object {object} is a {name}, which the f64 reference knows by its distance alone: it has \
             no surface to draw points from; probe it with `silhouette` generators or [[rays]]"
        ));
    }
    let mut cumulative = Vec::with_capacity(o.shapes.len());
    let mut total = 0.0;
    for shape in &o.shapes {
        total += surface::area(shape);
        cumulative.push(total);
    }
    if !(total > 0.0 && total.is_finite()) {
        return Err(format!("object {object} has no surface area to draw points from (area {total})"));
    }
    let normal_to_world = o.world_to_object.transpose();
    Ok((0..count)
        .map(|k| {
            // Dimensions 0..16 of stream k are the generators' own; the surface draws above.
            let mut dimension = 16;
            let mut next = || {
                dimension += 1;
                draw(seed, k, dimension)
            };
            let pick = next() * total;
            let i = cumulative.partition_point(|&c| c <= pick).min(o.shapes.len() - 1);
            let (p, n) = surface::sample(&o.shapes[i], &mut next);
            let world_n = normal_to_world.transform_vector3(n).normalize();
            (k, o.object_to_world.transform_point3(p), world_n)
        })
        .collect())
}

/// How a silhouette grid sees an object: from `from` towards the centre of its bounding box,
/// with `right` along the longest projected axis of its bounding box, and the half extents of
/// the box's projection along `right` and `up` (so a needle or a strongly scaled object fills the grid).
struct View {
    from: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    half: (f64, f64),
}

impl View {
    fn of(o: &RefObject, from: DVec3) -> Result<View, String> {
        let (mut lo, mut hi) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
        for shape in &o.shapes {
            let (a, b) = surface::bounding_box(shape);
            (lo, hi) = (lo.min(a), hi.max(b));
        }
        let center = o.object_to_world.transform_point3((lo + hi) / 2.0);
        let forward = (center - from).normalize();
        if !forward.is_finite() {
            return Err(format!("`from` {from} is the object's centre: no direction to look in"));
        }
        // The box's half axes, in world space and projected across the view.
        let axes: Vec<DVec3> = (0..3)
            .map(|i| {
                let mut half = DVec3::ZERO;
                half[i] = (hi[i] - lo[i]) / 2.0;
                let a = o.object_to_world.transform_vector3(half);
                a - forward * a.dot(forward)
            })
            .collect();
        let longest = axes.iter().copied().fold(DVec3::ZERO, |a, b| if b.length() > a.length() { b } else { a });
        let right = if longest.length() > 0.0 { longest.normalize() } else { tangents(forward).0 };
        let up = forward.cross(right);
        let extent = |axis: DVec3| axes.iter().map(|a| a.dot(axis).abs()).sum::<f64>();
        let half_u = extent(right).max(1e-30);
        // Seen edge-on a flat shape has no height: keep the rows apart anyway.
        let half_v = extent(up).max(half_u * 1e-6);
        Ok(View { from, forward, right, up, half: (half_u, half_v) })
    }
}

/// See `Generator::FacePlane`.
fn face_plane_rays(
    reference: &SceneReference,
    object: usize,
    count: u32,
    (offset, distance): (f32, f32),
    seed: u32,
) -> Result<Vec<(ProbeRay, ProbeRay)>, String> {
    let o = find(reference, object)?;
    let faces: Vec<&RefShape> = o.shapes.iter().filter(|s| face_point(s, [0.5; 3]).is_some()).collect();
    if faces.is_empty() {
        return Err(format!("object {object} has no flat faces"));
    }
    // Object-space size: the offsets and the start distance scale with it.
    let size = o.shapes.iter().map(crate::reference::shapes::bounding_radius).fold(0.0, f64::max);
    Ok((0..count)
        .map(|k| {
            let r = |d: u32| draw(seed, k, d);
            let shape = faces[((r(0) * faces.len() as f64) as usize).min(faces.len() - 1)];
            let (point, normal) = face_point(shape, [r(1), r(2), r(3)]).expect("a flat face");
            let (e1, e2) = tangents(normal);
            let phi = std::f64::consts::TAU * r(4);
            let along = e1 * phi.cos() + e2 * phi.sin();
            let side = [0.0, 1.0, -1.0][(k % 3) as usize] * f64::from(offset) * size;
            let origin = point - along * f64::from(distance) * size + normal * side;
            let world_origin = o.object_to_world.transform_point3(origin);
            let world_dir = o.object_to_world.transform_vector3(along).normalize();
            let r = ray(world_origin.as_vec3(), world_dir.as_vec3(), 0.0, far());
            (r, r)
        })
        .collect())
}

/// A point of one of the shape's flat faces, chosen by three numbers in [0, 1), with the
/// face's normal; `None` for shapes without flat faces (spheres, tori).
fn face_point(shape: &RefShape, [a, b, c]: [f64; 3]) -> Option<(DVec3, DVec3)> {
    let span = |x: f64, half: f64| (2.0 * x - 1.0) * half;
    let in_disk = |radius: f64, y: f64| {
        let (rho, phi) = (radius * b.sqrt(), std::f64::consts::TAU * c);
        DVec3::new(rho * phi.cos(), y, rho * phi.sin())
    };
    match *shape {
        RefShape::Box { half } => {
            let face = ((a * 6.0) as usize).min(5);
            let (axis, sign) = (face % 3, if face < 3 { 1.0 } else { -1.0 });
            let mut p = DVec3::ZERO;
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            p[u] = span(b, half[u]);
            p[v] = span(c, half[v]);
            p[axis] = sign * half[axis];
            let mut n = DVec3::ZERO;
            n[axis] = sign;
            Some((p, n))
        }
        RefShape::Rectangle { half_x, half_z } => Some((DVec3::new(span(b, half_x), 0.0, span(c, half_z)), DVec3::Y)),
        RefShape::Disk { radius } => Some((in_disk(radius, 0.0), DVec3::Y)),
        RefShape::Cylinder { radius, half_height } => {
            let sign = if a < 0.5 { 1.0 } else { -1.0 };
            Some((in_disk(radius, sign * half_height), DVec3::Y * sign))
        }
        RefShape::Cone { radius, half_height } => Some((in_disk(radius, -half_height), -DVec3::Y)),
        RefShape::Triangle { p } => {
            let (u, v) = if b + c > 1.0 { (1.0 - b, 1.0 - c) } else { (b, c) };
            let point = p[0] + (p[1] - p[0]) * u + (p[2] - p[0]) * v;
            Some((point, (p[1] - p[0]).cross(p[2] - p[0]).normalize()))
        }
        RefShape::Sphere { .. } | RefShape::Torus { .. } | RefShape::Traced { .. } | RefShape::Own { .. } => None,
    }
}

/// Random number `d` of stream `k` for `seed`, in [0, 1).
fn draw(seed: u32, k: u32, d: u32) -> f64 {
    f64::from(random(seed, k, 0, d))
}

/// Two unit vectors perpendicular to `n` and to each other.
fn tangents(n: DVec3) -> (DVec3, DVec3) {
    let e1 = n.any_orthonormal_vector();
    (e1, n.cross(e1))
}

/// A unit vector from two numbers in [0, 1), uniform on the sphere.
fn unit(a: f64, b: f64) -> DVec3 {
    let z = 2.0 * a - 1.0;
    let phi = std::f64::consts::TAU * b;
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}
