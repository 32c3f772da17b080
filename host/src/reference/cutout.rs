//! Cutouts in the f64 reference: the alpha pattern of a cutout material evaluated in f64, and
//! whether a hit is in a hole, solid, or within float noise of a hole's edge.

use super::texel::RefTexture;
use glam::{DVec2, DVec3};
use std::sync::Arc;
use twinray_shared::bindings::{CUTOUT_CHECKER, CUTOUT_DISCS, CUTOUT_TEXTURE, MATERIAL_CUTOUT};
use twinray_shared::layout::Material;

/// A cutout's pattern, in f64.
#[derive(Clone, Debug, PartialEq)]
pub struct RefCutout {
    pattern: u32,
    scale: f64,
    threshold: f64,
    /// A surface's own alpha (`CUTOUT_TEXTURE`): its opacity, whether a texture's alpha
    /// multiplies it, and that texture (without it: `Coverage::Unmodelled`).
    opacity: f64,
    textured: bool,
    texture: Option<Arc<RefTexture>>,
}

/// What a triangle's corners give a surface's own alpha: their alphas (COLOR_0's) and the
/// texture coordinates its texture reads, through the material's transform.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Corners {
    pub alpha: [f64; 3],
    pub uv: [DVec2; 3],
}

/// How near the cutoff, in units of f32's epsilon times the larger of the two, a surface's
/// alpha is a tie that rounding may decide either way: the stages multiply the opacity, the
/// interpolated vertex alpha and a texel's in f32, a few roundings.
const TIE_ULPS: f64 = 8.0;

/// How far, in units of f32's epsilon times the largest texture coordinate (at least 1), the
/// stages' texture coordinates may be from the exact ones: three corners' coordinates
/// transformed and interpolated in f32, with the texel scaling the sampler does.
const UV_ULPS: f64 = 16.0;

/// What a cutout makes of a hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coverage {
    Solid,
    Hole,
    /// Within float noise of a hole's edge: either is right.
    Edge,
    /// Alpha the reference does not compute (a texture's): either is right for the reference,
    /// but it is no evidence that a set which kept or dropped the hit is right.
    Unmodelled,
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
            texture: None,
        })
    }

    /// The cutout with `texture`, the reference of the texture whose alpha multiplies its
    /// surface's (the material's base colour texture).
    pub fn with_texture(self, texture: Option<RefTexture>) -> RefCutout {
        RefCutout { texture: texture.filter(|_| self.textured).map(Arc::new), ..self }
    }

    /// Whether the cutout's alpha is the surface's own (`CUTOUT_TEXTURE`): the reference needs
    /// the triangles' corners' alphas and texture coordinates then.
    pub fn reads_corners(&self) -> bool {
        self.pattern == CUTOUT_TEXTURE
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
    fn surface_coverage(&self, p: DVec3, band: f64, corners: &[DVec3; 3], attributes: &Corners) -> Coverage {
        let [a, b, c] = *corners;
        let (e1, e2) = (b - a, c - a);
        let normal = e1.cross(e2);
        let area2 = normal.length_squared();
        if area2 == 0.0 {
            return Coverage::Edge;
        }
        let (alphas, uvs) = (attributes.alpha, attributes.uv);
        // Whether the surface is there at a point of the triangle's plane (barycentrics by
        // areas) with its texture coordinates moved by `shift`; `None` within rounding of
        // the cutoff (a tie, or the texture's sampling).
        let decided = |q: DVec3, shift: DVec2| {
            let (u, v) = ((q - a).cross(e2).dot(normal) / area2, e1.cross(q - a).dot(normal) / area2);
            let vertex = self.opacity * (alphas[0] + (alphas[1] - alphas[0]) * u + (alphas[2] - alphas[0]) * v);
            let (alpha, sampling) = match &self.texture {
                Some(texture) => {
                    let (texel, error) = texture.alpha(uvs[0] + (uvs[1] - uvs[0]) * u + (uvs[2] - uvs[0]) * v + shift);
                    (vertex * texel, vertex.abs() * error)
                }
                None => (vertex, 0.0),
            };
            let tie = TIE_ULPS * f64::from(f32::EPSILON) * alpha.abs().max(self.threshold.abs()) + sampling;
            ((alpha - self.threshold).abs() > tie).then_some(alpha >= self.threshold)
        };
        let Some(solid) = decided(p, DVec2::ZERO) else { return Coverage::Edge };
        // The hit point's noise along the surface, and the f32 texture coordinates' own.
        let (d1, d2) = (e1.normalize() * band, normal.cross(e1).normalize() * band);
        let largest = uvs.iter().map(|uv| uv.abs().max_element()).fold(1.0, f64::max);
        let s = UV_ULPS * f64::from(f32::EPSILON) * largest;
        let moved = [(d1, DVec2::ZERO), (-d1, DVec2::ZERO), (d2, DVec2::ZERO), (-d2, DVec2::ZERO)];
        let shifted = [DVec2::X * s, -DVec2::X * s, DVec2::Y * s, -DVec2::Y * s].map(|shift| (DVec3::ZERO, shift));
        if moved.iter().chain(&shifted).any(|(d, shift)| decided(p + *d, *shift) != Some(solid)) {
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
    /// interpolated over `triangle` (object-space corners, their attributes), times its
    /// texture's alpha there if it has one, decided the same way and also an edge within
    /// `TIE_ULPS` f32 epsilons of the cutoff (and the texture's sampling error), or where the
    /// texture coordinates' own rounding crosses it; without the triangle, or with a texture
    /// the reference was not given, it is not modelled.
    pub fn coverage(&self, p: DVec3, band: f64, triangle: Option<(&[DVec3; 3], &Corners)>) -> Coverage {
        if self.pattern == CUTOUT_TEXTURE {
            return match triangle.filter(|_| self.textured == self.texture.is_some()) {
                Some((corners, attributes)) => self.surface_coverage(p, band, corners, attributes),
                None => Coverage::Unmodelled,
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
    use crate::scene::texture::{Filter, SamplerDesc, TextureImage, Wrap};

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
                    Coverage::Unmodelled => panic!("a pattern is modelled: {p}"),
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
    /// where a gradient crosses it; with a texture, no hit is modelled.
    #[test]
    fn a_surface_alpha_is_decided_from_its_vertices() {
        let mut m = material(CUTOUT_TEXTURE, 1.0, 0.5);
        m.color_a.w = 0.5;
        let cutout = RefCutout::of(&m).unwrap();
        assert!(cutout.reads_corners());
        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let with = |alpha: [f64; 3]| Corners { alpha, uv: [DVec2::ZERO; 3] };
        let at = |x: f64, y: f64, alphas: [f64; 3]| {
            cutout.coverage(DVec3::new(x, y, 0.0), 1e-6, Some((&corners, &with(alphas))))
        };
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
            cutout.coverage(p, band, Some((&corners, &with(gradient))))
        };
        assert_eq!(past(1e-6), Coverage::Solid);
        assert_eq!(past(1e-5), Coverage::Edge);
        // A texture the reference was not given is not modelled.
        let mut textured = m;
        textured.texture.x = 1;
        let t = RefCutout::of(&textured).unwrap();
        assert_eq!(
            t.coverage(DVec3::new(0.4, 0.4, 0.0), 1e-6, Some((&corners, &with([4.0; 3])))),
            Coverage::Unmodelled
        );
    }

    /// A texture's alpha times the vertex alpha: a 2 x 1 texture, its left texel clear and its
    /// right one opaque, across a triangle whose texture coordinates are its x and y. Nearest:
    /// decided on either side, an edge at the texels' border. Bilinear: the alpha rises from
    /// 0 to 1 between the texel centres; an edge only within the sampling's rounding of the
    /// cutoff.
    #[test]
    fn a_textured_alpha_is_decided_from_its_texels() {
        let image =
            TextureImage { name: "half".into(), width: 2, height: 1, rgba: vec![0, 0, 0, 0, 0, 0, 0, 255], srgb: true };
        let mut m = material(CUTOUT_TEXTURE, 1.0, 0.5);
        m.texture.x = 1;
        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let attributes = Corners { alpha: [1.0; 3], uv: [DVec2::ZERO, DVec2::X, DVec2::Y] };
        let cutout = |mag: Filter| {
            let sampler = SamplerDesc { wrap: [Wrap::Clamp; 2], mag, ..SamplerDesc::DEFAULT };
            RefCutout::of(&m).unwrap().with_texture(Some(RefTexture::of(&image, &sampler)))
        };
        let at = |c: &RefCutout, x: f64| c.coverage(DVec3::new(x, 0.1, 0.0), 1e-6, Some((&corners, &attributes)));
        let nearest = cutout(Filter::Nearest);
        assert_eq!(at(&nearest, 0.3), Coverage::Hole);
        assert_eq!(at(&nearest, 0.7), Coverage::Solid);
        assert_eq!(at(&nearest, 0.5), Coverage::Edge, "the texels' border");
        assert_eq!(at(&nearest, 0.5 + 1e-3), Coverage::Solid);
        let linear = cutout(Filter::Linear);
        // Alpha 2x - 0.5 between the centres at 0.25 and 0.75: the cutoff at x = 0.5, and the
        // device's rounding allows 1/256 + 1/255 of alpha, about 0.004 of x.
        assert_eq!(at(&linear, 0.45), Coverage::Hole);
        assert_eq!(at(&linear, 0.55), Coverage::Solid);
        assert_eq!(at(&linear, 0.503), Coverage::Edge);
        assert_eq!(at(&linear, 0.51), Coverage::Solid);
    }
}
