//! Random probe cases of the kind the local origin must not get wrong (`twinray stability
//! --random`, and the property test in `tests/origin.rs`): two to four groups of objects far
//! apart, at distances from the world origin spread over several orders of magnitude (one
//! group, often, at the world origin itself), thin shapes among them, each group probed from
//! close by: camera rays across a silhouette, secondary rays leaving a surface, rays in and
//! beside flat faces' planes and grazing rays; about half of the objects from afar too (a
//! silhouette or grazing rays from 100 to 3,000 sizes away), so that rays near an object and rays
//! far from it start within a few of their own distances of each other. Each case is the text of
//! a case file, so a case that fails can be written out and probed as any other.

use glam::Vec3;
use std::fmt::Write;
use twinray_shared::random::SplitMix64;

/// Most groups a case has; it has at least two.
const MAX_GROUPS: u64 = 4;

/// The text of random case `seed`: the same seed gives the same case everywhere.
pub fn origin_case(seed: u64) -> String {
    let mut rng = Rng(SplitMix64(seed ^ 0x0075_0075_0075_0075));
    let groups = 2 + rng.below(MAX_GROUPS - 1);
    let mut text = format!(
        "name = \"random-{seed}\"\ndescription = \"{groups} groups of objects far apart, each probed from close by \
         (random case {seed})\"\n\n[scene.materials.m]\nkind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\n"
    );
    let mut centres: Vec<Vec3> = Vec::new();
    let mut objects = String::new();
    let mut generators = String::new();
    let mut index = 0;
    for g in 0..groups {
        let centre = rng.centre(&centres);
        centres.push(centre);
        for _ in 0..1 + rng.below(2) {
            let shape = rng.shape();
            let size = 10f32.powf(rng.between(-1.0, 0.7));
            let name = format!("s{index}");
            let _ = write!(text, "\n[scene.shapes.{name}]\n{}", shape.keys(size, &mut rng));
            let at = centre + rng.direction() * size * rng.between(0.0, 3.0);
            let _ = write!(
                objects,
                "\n[[scene.objects]]\nshape = \"{name}\"\nmaterial = \"m\"\ntranslate = {}\nrotate = {}\n{}",
                array(at),
                array(Vec3::new(rng.between(0.0, 360.0), rng.between(0.0, 360.0), rng.between(0.0, 360.0))),
                shape.scale(&mut rng),
            );
            generators += &rng.generators(index, at, size, shape, g);
            index += 1;
        }
    }
    text + &objects + &generators
}

/// A shape kind a case may draw; the thin ones are what rounding most easily gets wrong.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Sphere,
    Cylinder,
    Cone,
    ThinTorus,
    ThinBox,
    Disk,
    Mesh,
}

const KINDS: [Kind; 7] =
    [Kind::Sphere, Kind::Cylinder, Kind::Cone, Kind::ThinTorus, Kind::ThinBox, Kind::Disk, Kind::Mesh];

impl Kind {
    /// The shape table's keys for a shape about `size` across.
    fn keys(self, size: f32, rng: &mut Rng) -> String {
        let r = 0.5 * size;
        match self {
            Kind::Sphere => format!("kind = \"sphere\"\nradius = {r:?}\n"),
            Kind::Cylinder => format!("kind = \"cylinder\"\nradius = {r:?}\nheight = {size:?}\n"),
            Kind::Cone => format!("kind = \"cone\"\nradius = {r:?}\nheight = {size:?}\n"),
            Kind::ThinTorus => {
                let minor = r * 10f32.powf(rng.between(-2.0, -0.5));
                format!("kind = \"torus\"\nmajor_radius = {r:?}\nminor_radius = {minor:?}\n")
            }
            Kind::ThinBox => {
                let thin = size * 10f32.powf(rng.between(-4.0, -2.0));
                format!("kind = \"box\"\nsize = [{size:?}, {thin:?}, {:?}]\n", size * rng.between(0.3, 1.0))
            }
            Kind::Disk => format!("kind = \"disk\"\nradius = {r:?}\n"),
            Kind::Mesh => "kind = \"mesh\"\nbuiltin = \"icosahedron\"\n".to_string(),
        }
    }

    /// An object's `scale`: the mesh is scaled to its size; a third of the others are
    /// squashed along one axis.
    fn scale(self, rng: &mut Rng) -> String {
        if self == Kind::Mesh || rng.below(3) == 0 {
            let axis = rng.below(3) as usize;
            let mut s = Vec3::ONE;
            s[axis] = 10f32.powf(rng.between(-2.0, -0.5));
            format!("scale = {}\n", array(s))
        } else {
            String::new()
        }
    }

    /// Whether the face-plane generator takes it (it has a flat face).
    fn flat(self) -> bool {
        !matches!(self, Kind::Sphere | Kind::ThinTorus)
    }
}

struct Rng(SplitMix64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0.next_u64() % n
    }

    fn between(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.0.unit()
    }

    /// A unit vector, uniform over the sphere.
    fn direction(&mut self) -> Vec3 {
        let z = self.between(-1.0, 1.0);
        let phi = self.between(0.0, std::f32::consts::TAU);
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(s * phi.cos(), s * phi.sin(), z)
    }

    /// A group's centre: the world origin for about one group in four, else 10 to 5e4 from
    /// it, at least 200 units from every other group's (objects are at most 5 across).
    fn centre(&mut self, others: &[Vec3]) -> Vec3 {
        loop {
            let c = if self.below(4) == 0 { Vec3::ZERO } else { self.direction() * 10f32.powf(self.between(1.0, 4.7)) };
            if others.iter().all(|o| o.distance(c) > 200.0) {
                return c;
            }
        }
    }

    fn shape(&mut self) -> Kind {
        KINDS[self.below(KINDS.len() as u64) as usize]
    }

    /// The generators of object `index` at `at`, about `size` across: a silhouette from 5 to
    /// 100 sizes away and one more kind of ray, drawn by `seed`; for about half, rays from afar.
    fn generators(&mut self, index: usize, at: Vec3, size: f32, kind: Kind, seed: u64) -> String {
        let from = at + self.direction() * size * 10f32.powf(self.between(0.7, 2.0));
        let mut s =
            format!("\n[[generators]]\nkind = \"silhouette\"\nobject = {index}\nfrom = {}\ncount = 16\n", array(from));
        let seed = 100 * seed + index as u64;
        let _ = match self.below(3) {
            0 => write!(s, "\n[[generators]]\nkind = \"surface\"\nobject = {index}\ncount = 128\nseed = {seed}\n"),
            1 if kind.flat() => write!(
                s,
                "\n[[generators]]\nkind = \"face_plane\"\nobject = {index}\ncount = 129\ndistance = {:?}\nseed = {seed}\n",
                self.between(2.0, 30.0)
            ),
            _ => write!(
                s,
                "\n[[generators]]\nkind = \"grazing\"\nobject = {index}\ncount = 128\ndistance = {:?}\nseed = {seed}\n",
                size * self.between(2.0, 50.0)
            ),
        };
        s + &self.rays_from_afar(index, at, size, seed)
    }

    /// For about half of the objects, rays from 100 to 3,000 sizes away: a silhouette or
    /// grazing rays.
    fn rays_from_afar(&mut self, index: usize, at: Vec3, size: f32, seed: u64) -> String {
        let distance = size * 10f32.powf(self.between(2.0, 3.5));
        match self.below(4) {
            0 => {
                let from = array(at + self.direction() * distance);
                format!("\n[[generators]]\nkind = \"silhouette\"\nobject = {index}\nfrom = {from}\ncount = 12\n")
            }
            1 => format!(
                "\n[[generators]]\nkind = \"grazing\"\nobject = {index}\ncount = 64\ndistance = {distance:?}\nseed = {}\n",
                seed + 7
            ),
            _ => String::new(),
        }
    }
}

/// `[x, y, z]` as TOML, each f32 written so that it reads back as the same f32.
fn array(v: Vec3) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::probe::case::ProbeCase;

    #[test]
    fn every_case_loads_and_the_same_seed_gives_the_same_case() {
        for seed in 0..200 {
            let text = origin_case(seed);
            assert_eq!(text, origin_case(seed));
            let case = ProbeCase::parse(&text, &format!("random-{seed}"), std::env::temp_dir())
                .unwrap_or_else(|e| panic!("case {seed}: {e}\n{text}"));
            assert!(case.file.generators.len() >= 4, "case {seed} has too few generators");
        }
        assert_ne!(origin_case(1), origin_case(2));
    }
}
