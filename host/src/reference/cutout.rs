//! Cutouts in the f64 reference: the alpha pattern of a cutout material evaluated in f64, and
//! whether a hit is in a hole, solid, or within float noise of a hole's edge.

use glam::{DVec2, DVec3};
use twinray_shared::bindings::{CUTOUT_CHECKER, CUTOUT_DISCS, CUTOUT_TEXTURE, MATERIAL_CUTOUT};
use twinray_shared::layout::Material;

/// A cutout's pattern, in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefCutout {
    pattern: u32,
    scale: f64,
    threshold: f64,
}

/// What a cutout makes of a hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coverage {
    Solid,
    Hole,
    /// Within float noise of a hole's edge: either is right.
    Edge,
}

impl RefCutout {
    /// The cutout of a material, or `None` for a material without holes.
    pub fn of(material: &Material) -> Option<RefCutout> {
        (material.kind == MATERIAL_CUTOUT).then(|| RefCutout {
            pattern: material.cutout_pattern,
            scale: f64::from(material.cutout_scale),
            threshold: f64::from(material.cutout_threshold),
        })
    }

    /// Alpha at an object-space point (the pattern over x and z; see
    /// `twinray_shared::shading::cutout_alpha`).
    fn alpha(&self, p: DVec3) -> f64 {
        let q = DVec2::new(p.x, p.z) * self.scale;
        let cell = q.floor();
        match self.pattern {
            CUTOUT_CHECKER => {
                if (cell.x + cell.y).rem_euclid(2.0) == 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
            CUTOUT_DISCS => ((q - cell - DVec2::splat(0.5)) * 2.0).length().min(1.0),
            _ => 1.0,
        }
    }

    fn solid(&self, p: DVec3) -> bool {
        self.alpha(p) >= self.threshold
    }

    /// The coverage at object-space point `p`, where the f32 stages' hit point may lie
    /// anywhere within `band` of it along the surface: an edge when any point that far away
    /// in x or z answers otherwise.
    /// A surface's own alpha (`CUTOUT_TEXTURE`: its texture and vertex colours) is not
    /// modelled here: every hit on it is an edge, either answer right.
    pub fn coverage(&self, p: DVec3, band: f64) -> Coverage {
        if self.pattern == CUTOUT_TEXTURE {
            return Coverage::Edge;
        }
        let here = self.solid(p);
        let nudges = [DVec3::X * band, -DVec3::X * band, DVec3::Z * band, -DVec3::Z * band];
        if nudges.iter().any(|d| self.solid(p + *d) != here) {
            Coverage::Edge
        } else if here {
            Coverage::Solid
        } else {
            Coverage::Hole
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material(pattern: u32, scale: f32, threshold: f32) -> Material {
        Material::cutout(pattern, scale, threshold)
    }

    /// The f64 pattern agrees with the shaders' f32 one away from edges, and points on an edge
    /// are edges.
    #[test]
    fn agrees_with_the_shaders_pattern() {
        for (pattern, threshold) in [(CUTOUT_CHECKER, 0.5), (CUTOUT_DISCS, 0.6)] {
            let m = material(pattern, 3.0, threshold);
            let cutout = RefCutout::of(&m).unwrap();
            for i in 0..400 {
                let p = DVec3::new(-2.0 + 0.0137 * f64::from(i), 0.3, 1.0 - 0.0091 * f64::from(i));
                let shaders = twinray_shared::shading::cutout_solid(&m, p.as_vec3());
                match cutout.coverage(p, 1e-4) {
                    Coverage::Solid => assert!(shaders, "{p}"),
                    Coverage::Hole => assert!(!shaders, "{p}"),
                    Coverage::Edge => {}
                }
            }
        }
        let checker = RefCutout::of(&material(CUTOUT_CHECKER, 1.0, 0.5)).unwrap();
        assert_eq!(checker.coverage(DVec3::new(1.0, 0.0, 0.5), 1e-6), Coverage::Edge);
        assert_eq!(checker.coverage(DVec3::new(0.5, 0.0, 0.5), 1e-6), Coverage::Solid);
        assert_eq!(checker.coverage(DVec3::new(1.5, 0.0, 0.5), 1e-6), Coverage::Hole);
        assert!(RefCutout::of(&Material { kind: 0, ..material(CUTOUT_DISCS, 1.0, 0.5) }).is_none());
    }
}
