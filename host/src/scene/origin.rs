//! The local origin: where the GPU's world coordinates are centred. The driver transforms each
//! ray into an instance's space in f32, and a triangle's hit is found in that space: for a ray
//! that starts 1e4 from the world origin and hits an object 10 units away, that transform
//! rounds at the magnitude of 1e4, and t comes back with a relative error of about 3e-4
//! (`probes/far-mesh.toml`, docs/numerics.md). Centred on the camera, the same ray starts near 0
//! and the object lies 10 units out: the driver's rounding is that of 10.
//!
//! Only the GPU's copy moves: objects' translations, the camera and the lights, each
//! `p - origin` computed in f64 and rounded once; rays handed to a probe or `explain` are moved
//! the same way, and hit points moved back. The f64 reference, the scene's checks and every
//! report work in the scene's own coordinates. Where the origin is a point of f32 near what
//! moves, the subtraction is exact (Sterbenz), so the GPU sees the very scene, translated.
//!
//! One origin helps only the rays that start near it: rays 1e4 from it are rounded at 1e4,
//! however near the world origin they start. A render's rays start at the eye, so it is
//! centred there; a probe's rays may start anywhere, so they are grouped by where they start
//! and each group is launched at an origin of its own ([`launches`]), which moves each of its
//! rays exactly and to at most a quarter of its distance from the world origin.

use super::file::{LightDesc, SceneFile};
use super::reach::FAR_FACTOR;
use glam::{DVec3, Vec3};
use std::collections::BTreeMap;
use twinray_shared::shapes::spec::Aabb;

/// `p - origin`, in f64, rounded once.
pub fn to_local(p: Vec3, origin: Vec3) -> Vec3 {
    (p.as_dvec3() - origin.as_dvec3()).as_vec3()
}

/// `p + origin`, in f64, rounded once: a point the GPU reported, in the scene's coordinates.
pub fn to_world(p: Vec3, origin: Vec3) -> Vec3 {
    (p.as_dvec3() + origin.as_dvec3()).as_vec3()
}

/// The point of f32 nearest the mean of `points`; `None` for none.
pub fn mean(points: impl IntoIterator<Item = Vec3>) -> Option<Vec3> {
    let (sum, n) = points.into_iter().fold((DVec3::ZERO, 0u64), |(s, n), p| (s + p.as_dvec3(), n + 1));
    (n > 0).then(|| (sum / n as f64).as_vec3())
}

/// `file` as the GPU sees it with its world origin at `origin`: objects, camera and lights
/// moved by `-origin`. Shapes, materials and directions are unchanged.
pub fn rebase(file: &mut SceneFile, origin: Vec3) {
    let local = |p: &mut [f32; 3]| *p = to_local(Vec3::from(*p), origin).into();
    for object in &mut file.objects {
        local(&mut object.translate);
    }
    local(&mut file.camera.eye);
    local(&mut file.camera.target);
    for light in &mut file.lights {
        match light {
            LightDesc::Point { position, .. } => local(position),
            LightDesc::Rect { center, .. } => local(center),
            LightDesc::Directional { .. } => {}
        }
    }
}

/// Rays launched at one origin: the indices of their rays, and where the GPU's coordinates are
/// centred for them.
#[derive(Clone, Debug, PartialEq)]
pub struct Launch {
    pub origin: Vec3,
    pub rays: Vec<usize>,
}

/// Most launches a probe makes: each uploads the scene and makes the pipeline again. The rays
/// of the groups beyond it are launched at the world origin, as world coordinates would have
/// them.
pub const MAX_LAUNCHES: usize = 8;

/// The fineness of the cells rays are first grouped in: a ray whose largest coordinate lies in
/// [2^e, 2^(e+1)) falls in a cell 2^(e - CELL_BITS) wide along each axis.
const CELL_BITS: i32 = 3;

/// Whether a ray starting at `o` may be launched at `origin`: the subtraction moves it exactly
/// (each `o_i - origin_i` an f32 number: Sterbenz's lemma, or a zero component of `origin`),
/// and it leaves the ray at most a quarter of its world magnitude (its largest coordinate), so
/// that what the ray meets near its start is rounded at a smaller magnitude than in world
/// coordinates.
pub fn fits(o: Vec3, origin: Vec3) -> bool {
    let exact = (0..3).all(|i| {
        let d = f64::from(o[i]) - f64::from(origin[i]);
        f64::from(d as f32) == d
    });
    exact && (o - origin).abs().max_element() <= 0.25 * o.abs().max_element()
}

/// Groups rays by where they start (`origins`), each group with the origin it is launched at,
/// for a scene whose objects have the world boxes `boxes`. Every ray fits its group's origin
/// ([`fits`]), or is launched at the world origin; launches are at most [`MAX_LAUNCHES`], the
/// largest groups first, and every ray is in exactly one.
///
/// Rays are put in cells first: a cell is a binade of the ray's largest coordinate and, along
/// each axis, a slot 2^-CELL_BITS of that binade wide, so a cell's rays are at most an eighth
/// of their magnitude apart. A cell's origin is `group_origin` of its rays. A cell with no
/// object near its origin that is far from the world origin for its size (`worth_moving`)
/// stays at the world origin: its rays see only what lies about as far from them as from the
/// world origin, or what is large enough to set its own rounding, where moving gains little
/// and costs a launch. The cells are then merged (`merge`).
pub fn launches(origins: &[Vec3], boxes: &[Aabb]) -> Vec<Launch> {
    let mut cells: BTreeMap<(i32, [i64; 3]), Vec<usize>> = BTreeMap::new();
    let mut world = Launch { origin: Vec3::ZERO, rays: Vec::new() };
    for (i, o) in origins.iter().enumerate() {
        match cell(*o) {
            Some(key) => cells.entry(key).or_default().push(i),
            None => world.rays.push(i),
        }
    }
    let mut groups = Vec::new();
    for rays in cells.into_values() {
        let origin = group_origin(origins, &rays);
        if boxes.iter().any(|b| worth_moving(b, origin)) {
            groups.push(Launch { origin, rays });
        } else {
            world.rays.extend(rays);
        }
    }
    finish(world, merge(groups, origins))
}

/// Merges each group into a larger one that it touches (their origins no farther apart than
/// twice their spreads added up) and whose origin every ray of it fits: a tight group of rays
/// that a cell's border splits is launched once, and two clusters apart keep an origin each,
/// among their own rays.
fn merge(mut groups: Vec<Launch>, origins: &[Vec3]) -> Vec<Launch> {
    // Largest first, so that a small group joins a large one and not the other way round; the
    // sort is stable, so equal sizes keep the cells' order.
    groups.sort_by_key(|g| std::cmp::Reverse(g.rays.len()));
    let spread = |g: &Launch| g.rays.iter().map(|&i| (origins[i] - g.origin).abs().max_element()).fold(0.0, f32::max);
    let mut merged: Vec<(Launch, f32)> = Vec::new();
    for g in groups {
        let s = spread(&g);
        let touches = |m: &Launch, ms: f32| (g.origin - m.origin).abs().max_element() <= 2.0 * (ms + s);
        let fit = |m: &Launch| g.rays.iter().all(|&i| fits(origins[i], m.origin));
        match merged.iter_mut().find(|(m, ms)| touches(m, *ms) && fit(m)) {
            Some((m, ms)) => {
                m.rays.extend(g.rays);
                *ms = spread(m);
            }
            None => merged.push((g, s)),
        }
    }
    merged.into_iter().map(|(m, _)| m).collect()
}

/// The launches, largest first, at most [`MAX_LAUNCHES`] with the world origin's (last, and
/// only where it has rays), which takes the rays of those beyond.
fn finish(mut world: Launch, mut merged: Vec<Launch>) -> Vec<Launch> {
    merged.sort_by_key(|g| std::cmp::Reverse(g.rays.len()));
    if merged.len() + usize::from(!world.rays.is_empty()) > MAX_LAUNCHES {
        for extra in merged.drain(MAX_LAUNCHES - 1..) {
            world.rays.extend(extra.rays);
        }
    }
    if !world.rays.is_empty() {
        world.rays.sort_unstable();
        merged.push(world);
    }
    merged
}

/// A ray's cell: the binade of its largest coordinate and its slot along each axis, counted
/// away from zero. `None` for a ray at (or subnormally near) the world origin.
fn cell(o: Vec3) -> Option<(i32, [i64; 3])> {
    let m = o.abs().max_element();
    if m.is_nan() || m < f32::MIN_POSITIVE {
        return None;
    }
    // The binade from the bits: log2 rounded in f32 can land on the wrong side of a power of 2.
    let e = ((m.to_bits() >> 23) & 0xff) as i32 - 127;
    let width = 2f64.powi(e - CELL_BITS);
    let slot = |x: f32| {
        let k = (f64::from(x.abs()) / width).floor() as i64;
        if x < 0.0 {
            -k
        } else {
            k
        }
    };
    Some((e, [slot(o.x), slot(o.y), slot(o.z)]))
}

/// Whether rays launched at `origin` gain from it on the object in world box `b`: the box lies
/// near the origin (within a quarter of its magnitude) and is far from the world origin for
/// its size (as `reach::far_instances` judges an object), so that what rounds at the world's
/// magnitude there now rounds at the rays' distance from it.
fn worth_moving(b: &Aabb, origin: Vec3) -> bool {
    let magnitude = origin.abs().max_element();
    let size = 0.5 * (b.max - b.min).length();
    gap(b, origin) <= 0.25 * magnitude && FAR_FACTOR * size < magnitude
}

/// How far `p` lies outside `b` along the axis where it lies farthest out (0 inside).
fn gap(b: &Aabb, p: Vec3) -> f32 {
    (b.min - p).max(p - b.max).max(Vec3::ZERO).max_element()
}

/// The origin of a group of rays: along each axis, their mean (in f64, rounded once) where every
/// ray's coordinate is within a factor 2 of it, so that each moves exactly (Sterbenz), else 0.
/// An axis left at 0 has coordinates that straddle 0 or span more than a factor 2, so none is
/// larger than twice their spread: every ray of the group lands within twice the group's spread
/// of its origin along every axis.
fn group_origin(origins: &[Vec3], rays: &[usize]) -> Vec3 {
    let mean = mean(rays.iter().map(|&i| origins[i])).unwrap_or(Vec3::ZERO);
    let sterbenz = |k: usize| {
        let c = mean[k];
        rays.iter().all(|&i| {
            let x = origins[i][k];
            c != 0.0 && x.signum() == c.signum() && x.abs() <= 2.0 * c.abs() && c.abs() <= 2.0 * x.abs()
        })
    };
    Vec3::from_array(std::array::from_fn(|k| if sterbenz(k) { mean[k] } else { 0.0 }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_points_move_exactly_and_come_back() {
        let origin = Vec3::new(10000.0, -10000.0, 9990.0);
        let p = Vec3::new(10000.3, -10000.7, 10000.1);
        let local = to_local(p, origin);
        // Sterbenz: the difference of two f32 within a factor of 2 of each other is exact.
        assert_eq!(local.as_dvec3(), p.as_dvec3() - origin.as_dvec3());
        assert_eq!(to_world(local, origin), p);
    }

    #[test]
    fn the_mean_is_of_f32_and_none_of_nothing() {
        assert_eq!(mean([Vec3::X, Vec3::Y]), Some(Vec3::new(0.5, 0.5, 0.0)));
        assert_eq!(mean(std::iter::empty()), None);
    }
    fn unit_box(centre: Vec3) -> Aabb {
        Aabb { min: centre - 0.5, max: centre + 0.5 }
    }

    /// Where each ray is launched, by ray.
    fn launched_at(origins: &[Vec3], boxes: &[Aabb]) -> Vec<Vec3> {
        let launches = launches(origins, boxes);
        assert!(launches.len() <= MAX_LAUNCHES && launches.iter().all(|l| !l.rays.is_empty()));
        let mut at = vec![None; origins.len()];
        for l in &launches {
            for &i in &l.rays {
                assert!(at[i].replace(l.origin).is_none(), "ray {i} is in two launches");
            }
        }
        at.into_iter().enumerate().map(|(i, o)| o.unwrap_or_else(|| panic!("ray {i} is in no launch"))).collect()
    }

    #[test]
    fn two_groups_far_apart_are_launched_apart_each_near_its_rays() {
        let near: Vec<Vec3> = (0..50).map(|i| Vec3::new(100.0, 0.01 * i as f32, 3.0)).collect();
        let far: Vec<Vec3> = (0..50).map(|i| Vec3::new(7000.0 + 0.02 * i as f32, -5000.0, 6490.0)).collect();
        let origins: Vec<Vec3> = near.iter().chain(&far).copied().collect();
        let boxes = [unit_box(Vec3::new(95.0, 0.0, 3.0)), unit_box(Vec3::new(7000.0, -5000.0, 6500.0))];
        let at = launched_at(&origins, &boxes);
        assert_ne!(at[0], at[50]);
        for (o, c) in origins.iter().zip(&at) {
            assert!(fits(*o, *c), "{o} at {c}");
            // Each group is launched within its own spread of its rays.
            assert!((*o - *c).abs().max_element() <= 1.0, "{o} at {c}");
        }
    }

    #[test]
    fn a_tight_group_split_by_a_cells_border_is_launched_once() {
        // 8192 is a power of 2: the rays' largest coordinates straddle a binade.
        let origins: Vec<Vec3> = (0..20).map(|i| Vec3::new(8191.5 + 0.05 * i as f32, 10.0, -20.0)).collect();
        assert_eq!(launches(&origins, &[unit_box(Vec3::new(8200.0, 10.0, -20.0))]).len(), 1);
    }

    #[test]
    fn rays_at_the_world_origin_stay_there_and_every_ray_is_launched_once() {
        let origins = [Vec3::ZERO, Vec3::new(1e-40, 0.0, 0.0), Vec3::new(500.0, 0.0, 0.0)];
        let at = launched_at(&origins, &[unit_box(Vec3::new(495.0, 0.0, 0.0))]);
        assert_eq!((at[0], at[1]), (Vec3::ZERO, Vec3::ZERO));
        assert_eq!(at[2], origins[2]);
    }

    #[test]
    fn rays_beside_an_object_too_large_to_be_far_stay_at_the_world_origin() {
        // A box 10 across, 50 from the world origin: within 16 times its size, so its own
        // extent sets its rounding, and moving the rays there gains little.
        let origins: Vec<Vec3> = (0..8).map(|i| Vec3::new(60.0 + i as f32, 0.0, 0.0)).collect();
        let wide = Aabb { min: Vec3::new(45.0, -5.0, -5.0), max: Vec3::new(55.0, 5.0, 5.0) };
        assert!(launched_at(&origins, &[wide]).iter().all(|&c| c == Vec3::ZERO));
    }

    #[test]
    fn rays_with_nothing_near_them_stay_at_the_world_origin() {
        // Rays 100 units around a sheet at the world origin, looking at it: moving them to
        // where they start would move the sheet as far out as they are.
        let origins: Vec<Vec3> =
            (0..64).map(|i| 100.0 * Vec3::new((i as f32 * 0.1).cos(), 0.0, (i as f32 * 0.1).sin())).collect();
        let at = launched_at(&origins, &[unit_box(Vec3::ZERO)]);
        assert!(at.iter().all(|&c| c == Vec3::ZERO), "{at:?}");
    }

    #[test]
    fn random_rays_over_many_magnitudes_fit_their_launch_or_stay_at_the_world_origin() {
        let mut rng = twinray_shared::random::SplitMix64(75);
        for _ in 0..50 {
            let groups = 1 + (rng.next_u64() % 12) as usize;
            let (mut origins, mut boxes) = (Vec::new(), Vec::new());
            for _ in 0..groups {
                let scale = 10f32.powf(rng.unit() * 8.0 - 3.0);
                let centre = Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5) * 2.0 * scale;
                let spread = scale * 10f32.powf(-rng.unit() * 6.0);
                boxes.push(unit_box(centre + Vec3::splat(spread)));
                for _ in 0..(1 + rng.next_u64() % 40) {
                    let jitter = Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5) * spread;
                    origins.push(centre + jitter);
                }
            }
            for (o, c) in origins.iter().zip(launched_at(&origins, &boxes)) {
                assert!(c == Vec3::ZERO || fits(*o, c), "{o} launched at {c}");
            }
        }
    }
}
