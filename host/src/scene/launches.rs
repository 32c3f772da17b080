//! Where a probe's launches are centred: each ray is launched with the GPU's coordinates centred
//! where it meets what it can hit, so that the driver's transform (and every subtraction of a
//! position the stages make) rounds at the ray's own distance from the instance, not at the
//! world's coordinates nor at the distance of other rays that happen to start nearby.
//!
//! For a ray from `o` meeting an instance whose translation is `T`, launched at an origin `c`,
//! the driver computes the object-space origin as `M⁻¹ (o - c) + M⁻¹ (c - T)` in f32: each
//! component is rounded at about `|o_k - c_k| + |T_k - c_k|`. Launched alone, at its own start,
//! that is `|o_k - T_k|`; at the instance's own translation too; and anywhere between the two.
//! A ray is *served* by an origin where that sum is at most [`SLACK`] times its largest
//! `|o_k - T_k|`, and where `o - c` and the translation less `c` of every instance it can hit are
//! exact in f32 (the GPU then sees the very ray and instances, moved). The
//! instance that counts is the one it can hit whose translation lies nearest its start
//! ([`key`]): nearer instances set tighter bounds, and an origin that serves the nearest serves
//! the others within `1 + 2 SLACK`.
//!
//! Launches are chosen greedily: the rays the world origin serves stay there; of the rest, the
//! one with the tightest bound seeds a launch at the origin (its instance's translation, or its
//! own start) that serves the most of those left, and every ray it serves joins. Rays that
//! start together (a camera) share one launch at their start; rays that meet one instance from
//! all around share one at its translation; rays near one instance never share a launch with
//! rays far from it that would round them at their own distance.

use glam::{DVec3, Vec3};
use std::collections::HashMap;
use twinray_shared::shapes::spec::Aabb;

/// A ray as launches are chosen for it: where it starts, where it goes, its range of t.
#[derive(Clone, Copy, Debug)]
pub struct LaunchRay {
    pub origin: Vec3,
    pub direction: Vec3,
    pub t_min: f32,
    pub t_max: f32,
}

/// An instance as launches are chosen for it: its world box and its translation.
#[derive(Clone, Copy, Debug)]
pub struct Placed {
    pub bounds: Aabb,
    pub translation: Vec3,
}

/// Rays launched at one origin: the indices of their rays, and where the GPU's coordinates are
/// centred for them.
#[derive(Clone, Debug, PartialEq)]
pub struct Launch {
    pub origin: Vec3,
    pub rays: Vec<usize>,
}

/// How much larger a ray's rounding may be at its launch's origin than at its own start: the
/// largest `|o_k - c_k| + |T_k - c_k|` over its largest `|o_k - T_k|` (see the module).
pub const SLACK: f64 = 1.5;

/// Most launches a probe makes, the world origin's among them; the rays no launch serves
/// within them go to the launch that rounds them least.
pub const MAX_LAUNCHES: usize = 32;

/// What one ray asks of its launch's origin.
#[derive(Clone)]
struct Need {
    origin: Vec3,
    /// The translation of the instance it is centred for (see [`key`]).
    target: Vec3,
    /// The translations of every instance it can hit, which must move exactly too: the stages
    /// bring a ray far from its primitive near it without rounding at the distance
    /// (`twinray_shared::exact`), and a translation rounded on the way would undo that.
    targets: Vec<Vec3>,
    /// The largest rounding magnitude it accepts; infinite for a ray that meets no instance.
    limit: f64,
}

impl Need {
    fn new(ray: &LaunchRay, placed: &[Placed]) -> Need {
        let met: Vec<usize> = (0..placed.len()).filter(|&i| meets(ray, &placed[i].bounds)).collect();
        let targets: Vec<Vec3> = met.iter().map(|&i| placed[i].translation).collect();
        match key(ray, placed) {
            Some(i) => {
                let target = placed[i].translation;
                let limit = SLACK * (ray.origin.as_dvec3() - target.as_dvec3()).abs().max_element();
                Need { origin: ray.origin, target, targets, limit }
            }
            None => Need { origin: ray.origin, target: ray.origin, targets, limit: f64::INFINITY },
        }
    }

    /// The magnitude this ray's object-space origin is rounded at with the GPU's coordinates
    /// centred at `c`: the largest `|o_k - c_k| + |T_k - c_k|`.
    fn rounding_at(&self, c: Vec3) -> f64 {
        let c = c.as_dvec3();
        ((self.origin.as_dvec3() - c).abs() + (self.target.as_dvec3() - c).abs()).max_element()
    }

    /// Whether centring at `c` moves the ray and every instance it can hit exactly.
    fn exact_at(&self, c: Vec3) -> bool {
        exact(self.origin, c) && self.targets.iter().all(|&t| exact(t, c))
    }

    fn served_by(&self, c: Vec3) -> bool {
        self.exact_at(c) && self.rounding_at(c) <= self.limit
    }

    /// An origin that moves this ray and what it can hit exactly: along each axis the
    /// instance's translation where every one of them moves there exactly, else 0 (where one
    /// does not, the two differ by more than a factor 2 or in sign, so that neither is more than
    /// about twice their difference: the world's rounding on that axis is about theirs).
    fn own_origin(&self) -> Vec3 {
        Vec3::from_array(std::array::from_fn(|k| {
            let t = self.target[k];
            let exact = |x: f32| exact_difference(x, t);
            if exact(self.origin[k]) && self.targets.iter().all(|other| exact(other[k])) {
                t
            } else {
                0.0
            }
        }))
    }
}

/// Whether `a - b` is an f32 number (no rounding).
fn exact_difference(a: f32, b: f32) -> bool {
    let d = f64::from(a) - f64::from(b);
    f64::from(d as f32) == d
}

/// Whether a ray starting at `o` moves exactly when the GPU's coordinates are centred at `c`.
pub fn exact(o: Vec3, c: Vec3) -> bool {
    (0..3).all(|k| exact_difference(o[k], c[k]))
}

/// The instance a ray is centred for: of those whose world box (grown by a thousandth of its
/// size, so that rounding cannot make a ray meet one it is not counted for) its segment meets,
/// the one whose translation lies nearest its start, largest coordinate difference first.
/// `None` where it meets none.
pub fn key(ray: &LaunchRay, placed: &[Placed]) -> Option<usize> {
    let o = ray.origin.as_dvec3();
    let reach = |p: &Placed| (o - p.translation.as_dvec3()).abs().max_element();
    placed
        .iter()
        .enumerate()
        .filter(|(_, p)| meets(ray, &p.bounds))
        .min_by(|(_, a), (_, b)| reach(a).total_cmp(&reach(b)))
        .map(|(i, _)| i)
}

/// Whether the ray's segment meets box `b`, grown by a thousandth of its size and of its
/// magnitude's f32 ulp: a slab test in f64.
fn meets(ray: &LaunchRay, b: &Aabb) -> bool {
    let (min, max) = (b.min.as_dvec3(), b.max.as_dvec3());
    let grow = 1e-3 * (max - min).length() + 1e-6 * min.abs().max(max.abs()).max_element();
    let (min, max) = (min - DVec3::splat(grow), max + DVec3::splat(grow));
    let (o, d) = (ray.origin.as_dvec3(), ray.direction.as_dvec3());
    let (mut near, mut far) = (f64::from(ray.t_min), f64::from(ray.t_max));
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k] < min[k] || o[k] > max[k] {
                return false;
            }
            continue;
        }
        let (a, b) = ((min[k] - o[k]) / d[k], (max[k] - o[k]) / d[k]);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    near <= far
}

/// The launches of `rays` among instances `placed` (world coordinates): every ray in exactly
/// one, each launch's origin serving its rays (see the module) but where more than
/// [`MAX_LAUNCHES`] would be needed; the largest first, the world origin's last where it has
/// rays.
pub fn launches(rays: &[LaunchRay], placed: &[Placed]) -> Vec<Launch> {
    // A probe timed over its rays repeated (`stability --timing-rays`) holds each many times:
    // each distinct ray is placed once, and its copies go where it goes.
    let mut distinct: HashMap<[u32; 8], usize> = HashMap::new();
    let mut unique = Vec::new();
    let of: Vec<usize> = rays
        .iter()
        .map(|r| {
            let [ox, oy, oz] = r.origin.to_array().map(f32::to_bits);
            let [dx, dy, dz] = r.direction.to_array().map(f32::to_bits);
            *distinct.entry([ox, oy, oz, dx, dy, dz, r.t_min.to_bits(), r.t_max.to_bits()]).or_insert_with(|| {
                unique.push(*r);
                unique.len() - 1
            })
        })
        .collect();
    let chosen = choose(&unique, placed);
    let mut launch_of = vec![0; unique.len()];
    for (k, launch) in chosen.iter().enumerate() {
        for &u in &launch.rays {
            launch_of[u] = k;
        }
    }
    let mut out: Vec<Launch> = chosen.iter().map(|l| Launch { origin: l.origin, rays: Vec::new() }).collect();
    for (i, &u) in of.iter().enumerate() {
        out[launch_of[u]].rays.push(i);
    }
    out
}

/// [`launches`] of distinct rays. Placing a ray tests its segment against every instance's box,
/// and each launch looks at every ray not yet placed.
fn choose(rays: &[LaunchRay], placed: &[Placed]) -> Vec<Launch> {
    let needs: Vec<Need> = rays.iter().map(|r| Need::new(r, placed)).collect();
    let (mut world, mut left): (Vec<usize>, Vec<usize>) =
        (0..rays.len()).partition(|&i| needs[i].served_by(Vec3::ZERO));
    // Tightest first: a seed's bound is the hardest to meet, and looser rays join it.
    left.sort_by(|&a, &b| needs[a].limit.total_cmp(&needs[b].limit));
    let mut launches: Vec<Launch> = Vec::new();
    let mut unserved = Vec::new();
    while let Some(&seed) = left.first() {
        if launches.len() + 1 >= MAX_LAUNCHES {
            unserved.append(&mut left);
            break;
        }
        // The candidate that serves more rays; of two that serve as many, the one that rounds
        // them less (their starts' own rounding is the least there is).
        let score = |c: Vec3| {
            let served = left.iter().map(|&i| &needs[i]).filter(|n| n.served_by(c));
            served.fold((0usize, 0.0f64), |(n, sum), need| {
                (n + 1, sum - need.rounding_at(c) / need.limit.max(f64::MIN_POSITIVE))
            })
        };
        let (own, start) = (needs[seed].own_origin(), needs[seed].origin);
        let origin = if score(start) >= score(own) { start } else { own };
        let (served, rest): (Vec<usize>, Vec<usize>) = left.iter().partition(|&&i| needs[i].served_by(origin));
        left = rest;
        if served.is_empty() {
            // No exact origin serves the seed within its bound: it goes where it is rounded least.
            left.retain(|&i| i != seed);
            unserved.push(seed);
        } else if origin == Vec3::ZERO {
            world.extend(served);
        } else {
            launches.push(Launch { origin, rays: served });
        }
    }
    // Each ray no launch serves goes where it is rounded least, among the origins that move it
    // and what it can hit exactly (the world origin always does).
    for i in unserved {
        let need = &needs[i];
        let best = launches
            .iter_mut()
            .filter(|l| need.exact_at(l.origin))
            .min_by(|a, b| need.rounding_at(a.origin).total_cmp(&need.rounding_at(b.origin)));
        match best {
            Some(l) if need.rounding_at(l.origin) < need.rounding_at(Vec3::ZERO) => l.rays.push(i),
            _ => world.push(i),
        }
    }
    launches.sort_by_key(|l| std::cmp::Reverse(l.rays.len()));
    for l in &mut launches {
        l.rays.sort_unstable();
    }
    if !world.is_empty() {
        world.sort_unstable();
        launches.push(Launch { origin: Vec3::ZERO, rays: world });
    }
    launches
}

#[cfg(test)]
#[path = "launches_tests.rs"]
mod tests;
