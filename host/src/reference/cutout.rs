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
    /// A surface's own alpha (`CUTOUT_TEXTURE`): its opacity, and whether a texture's alpha
    /// multiplies it (which the reference does not sample: every hit on it is an edge).
    opacity: f64,
    textured: bool,
}

/// How near the cutoff, in units of f32's epsilon times the larger of the two, a surface's
/// alpha is a tie that rounding may decide either way: the stages multiply the opacity, the
/// interpolated vertex alpha and a texel's in f32, a few roundings.
const TIE_ULPS: f64 = 8.0;

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
            opacity: f64::from(material.color_a.w),
            textured: material.texture.x != 0,
        })
    }

    /// Whether the cutout's alpha is the surface's own (`CUTOUT_TEXTURE`), known from its
    /// vertices where no texture multiplies it: the reference needs the triangles' vertex
    /// alphas then.
    pub fn reads_vertex_alpha(&self) -> bool {
        self.pattern == CUTOUT_TEXTURE && !self.textured
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

    /// [`RefCutout::coverage`] of a surface's own alpha over one triangle.
    fn surface_coverage(&self, p: DVec3, band: f64, corners: &[DVec3; 3], alphas: [f64; 3]) -> Coverage {
        let [a, b, c] = *corners;
        let (e1, e2) = (b - a, c - a);
        let normal = e1.cross(e2);
        let area2 = normal.length_squared();
        if area2 == 0.0 {
            return Coverage::Edge;
        }
        // The interpolated alpha at a point of the triangle's plane (barycentrics by areas).
        let alpha = |q: DVec3| {
            let (u, v) = ((q - a).cross(e2).dot(normal) / area2, e1.cross(q - a).dot(normal) / area2);
            self.opacity * (alphas[0] + (alphas[1] - alphas[0]) * u + (alphas[2] - alphas[0]) * v)
        };
        let here = alpha(p);
        if (here - self.threshold).abs() <= TIE_ULPS * f64::from(f32::EPSILON) * here.abs().max(self.threshold.abs()) {
            return Coverage::Edge;
        }
        let solid = here >= self.threshold;
        let (d1, d2) = (e1.normalize() * band, normal.cross(e1).normalize() * band);
        if [d1, -d1, d2, -d2].iter().any(|d| (alpha(p + *d) >= self.threshold) != solid) {
            Coverage::Edge
        } else if solid {
            Coverage::Solid
        } else {
            Coverage::Hole
        }
    }

    /// The coverage at object-space point `p`, where the f32 stages' hit point may lie
    /// anywhere within `band` of it along the surface: an edge when any point that far away
    /// in x or z answers otherwise.
    /// A surface's own alpha (`CUTOUT_TEXTURE`) is its opacity times the vertex alpha
    /// interpolated over `triangle` (object-space corners, their alphas), decided the same way
    /// and also an edge within `TIE_ULPS` f32 epsilons of the cutoff; with a texture, or
    /// without the triangle, it is not modelled: every hit on it is an edge, either answer right.
    pub fn coverage(&self, p: DVec3, band: f64, triangle: Option<(&[DVec3; 3], [f64; 3])>) -> Coverage {
        if self.pattern == CUTOUT_TEXTURE {
            return match triangle.filter(|_| !self.textured) {
                Some((corners, alphas)) => self.surface_coverage(p, band, corners, alphas),
                None => Coverage::Edge,
            };
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
                match cutout.coverage(p, 1e-4, None) {
                    Coverage::Solid => assert!(shaders, "{p}"),
                    Coverage::Hole => assert!(!shaders, "{p}"),
                    Coverage::Edge => {}
                }
            }
        }
        let checker = RefCutout::of(&material(CUTOUT_CHECKER, 1.0, 0.5)).unwrap();
        assert_eq!(checker.coverage(DVec3::new(1.0, 0.0, 0.5), 1e-6, None), Coverage::Edge);
        assert_eq!(checker.coverage(DVec3::new(0.5, 0.0, 0.5), 1e-6, None), Coverage::Solid);
        assert_eq!(checker.coverage(DVec3::new(1.5, 0.0, 0.5), 1e-6, None), Coverage::Hole);
        assert!(RefCutout::of(&Material { kind: 0, ..material(CUTOUT_DISCS, 1.0, 0.5) }).is_none());
    }

    /// A surface's own alpha without a texture: its opacity times the vertex alpha, decided
    /// away from the cutoff, an edge at a tie and within the hit point's noise of the contour
    /// where a gradient crosses it; with a texture, every hit is an edge.
    #[test]
    fn a_surface_alpha_is_decided_from_its_vertices() {
        let mut m = material(CUTOUT_TEXTURE, 1.0, 0.5);
        m.color_a.w = 0.5;
        let cutout = RefCutout::of(&m).unwrap();
        assert!(cutout.reads_vertex_alpha());
        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let at =
            |x: f64, y: f64, alphas: [f64; 3]| cutout.coverage(DVec3::new(x, y, 0.0), 1e-6, Some((&corners, alphas)));
        // Opacity 0.5 times 1 everywhere: exactly the cutoff, a tie.
        assert_eq!(at(0.2, 0.2, [1.0; 3]), Coverage::Edge);
        // Vertex alphas 0, 2, 2 times 0.5: alpha u + v, the contour at u + v = 0.5.
        let gradient = [0.0, 2.0, 2.0];
        assert_eq!(at(0.1, 0.1, gradient), Coverage::Hole);
        assert_eq!(at(0.45, 0.45, gradient), Coverage::Solid);
        assert_eq!(at(0.25, 0.25, gradient), Coverage::Edge, "on the contour");
        // Just past the contour (alpha 0.5 + 6e-6): solid where the hit point is sure to
        // 1e-6, an edge where it may be 1e-5 off.
        let past = |band: f64| {
            let p = DVec3::new(0.25 + 3e-6, 0.25 + 3e-6, 0.0);
            cutout.coverage(p, band, Some((&corners, gradient)))
        };
        assert_eq!(past(1e-6), Coverage::Solid);
        assert_eq!(past(1e-5), Coverage::Edge);
        let steep = [0.0, 4.0, 4.0];
        let mut textured = m;
        textured.texture.x = 1;
        let t = RefCutout::of(&textured).unwrap();
        assert!(!t.reads_vertex_alpha());
        assert_eq!(t.coverage(DVec3::new(0.4, 0.4, 0.0), 1e-6, Some((&corners, steep))), Coverage::Edge);
    }
}
