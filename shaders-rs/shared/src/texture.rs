//! Textures on meshes and procedural shapes: the vertex attributes a hit interpolates, the
//! coordinates of a shape's parametrisation (`shapes::uv`), the material's texture
//! coordinate transform, and the texture-space footprint of the ray's cone, which picks the
//! texture's level of detail in stages that have no derivatives.
//!
//! Level of detail follows ray cones (Akenine-Möller et al., "Texture Level of Detail
//! Strategies for Real-Time Ray Tracing", Ray Tracing Gems ch. 20, 2019) with the anisotropic
//! footprint of "Improved Shader and Texture Level of Detail Using Ray Cones" (Akenine-Möller,
//! Crassin, Boksansky, Belcour, Panteleev, Wright, JCGT 10(1), 2021): the cone's ellipse on the
//! triangle's plane, its two axes carried to texture space through the triangle's
//! barycentrics. A floor seen at a grazing angle so gets a long, thin footprint (sharp across,
//! filtered along) rather than one level for both. The footprint is filtered by up to
//! [`MAX_TAPS`] samples along its long axis, each at the level of its short one ([`taps`]),
//! rather than by the sampler's anisotropic filtering, which devices implement differently
//! (lavapipe 22.3 offers it and ignores it): every device then filters alike.

use crate::layout::{Material, Vertex};
use crate::shapes::ShapeUv;
use glam::{Mat3, Vec2, Vec3, Vec4, Vec4Swizzles};
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

/// `a[0]`, `a[1]`, `a[2]` weighted by the barycentrics `(u, v)` of vertices 1 and 2, as
/// `a0 + (a1 - a0) u + (a2 - a0) v`: where the three agree (a vertex colour's alpha of 1 on every
/// vertex) the differences are exactly 0 and the result is exactly `a0`, however a compiler
/// fuses or orders the rest. The weighted sum `a0 (1 - u - v) + ...` rounds the weights, and gave
/// 0.99999994 in one set and 1 in the other: an alpha of 0.5 times that fell on either side of a
/// cutoff of 0.5 (twinray's guide, *Numerics*, "Alpha at the cutoff").
pub fn interpolate(a: [Vec4; 3], u: f32, v: f32) -> Vec4 {
    a[0] + (a[1] - a[0]) * u + (a[2] - a[0]) * v
}

/// The texture coordinates a texture of `material` reads at vertex `v` from its `set` (0 or
/// 1: `texture.y` for the base colour, `texture.w` for emission), through the material's
/// transform.
pub fn vertex_uv(material: &Material, v: &Vertex, set: u32) -> Vec2 {
    material_uv(material, v.uv, set)
}

/// The texture coordinates a texture of `material` reads of a vertex's `uv` (both sets) from
/// its `set`.
pub fn material_uv(material: &Material, uv: Vec4, set: u32) -> Vec2 {
    transform_uv(material, if set == 1 { uv.zw() } else { uv.xy() })
}

/// `uv` through the material's texture coordinate transform.
pub fn transform_uv(material: &Material, uv: Vec2) -> Vec2 {
    Vec2::new(material.uv_u.xy().dot(uv) + material.uv_u.z, material.uv_v.xy().dot(uv) + material.uv_v.z)
}

/// A change `g` of texture coordinates through the linear part of the material's transform.
pub fn transform_gradient(material: &Material, g: Vec2) -> Vec2 {
    Vec2::new(material.uv_u.xy().dot(g), material.uv_v.xy().dot(g))
}

/// The texture coordinates of a triangle's vertices `v` in `set`, as [`vertex_uv`] reads them.
pub fn triangle_uv(material: &Material, v: &[Vertex; 3], set: u32) -> [Vec2; 3] {
    [vertex_uv(material, &v[0], set), vertex_uv(material, &v[1], set), vertex_uv(material, &v[2], set)]
}

/// The texture coordinates at barycentrics `b` of a triangle whose vertices have `uv`.
pub fn uv_at(uv: [Vec2; 3], b: Vec2) -> Vec2 {
    uv[0] * (1.0 - b.x - b.y) + uv[1] * b.x + uv[2] * b.y
}

/// Where a ray met a textured triangle, in world space: what the footprint needs.
#[derive(Clone, Copy)]
pub struct TriangleHit {
    /// The object-to-world transform's 3x3 part.
    pub object_to_world: Mat3,
    /// The triangle's object-space vertex positions.
    pub positions: [Vec3; 3],
    /// The hit's barycentrics of vertices 1 and 2.
    pub barycentrics: Vec2,
    /// The world-space unit ray direction.
    pub direction: Vec3,
    /// The cone's width at the hit: its spread angle times the distance travelled.
    pub width: f32,
}

/// The texture coordinates at the hit and their gradients across the cone's footprint:
/// `(uv, dx, dy)` for an explicit-gradient sample (zero gradients, level 0, for a cone of
/// width 0). The footprint's two axes are those of the ellipse the cone cuts from the
/// triangle's plane, each of the length a pixel's worth of the cone covers there, as a
/// rasteriser's derivatives across one pixel would be.
pub fn footprint(hit: &TriangleHit, uv: [Vec2; 3]) -> (Vec2, Vec2, Vec2) {
    let at = uv_at(uv, hit.barycentrics);
    if hit.width <= 0.0 {
        return (at, Vec2::ZERO, Vec2::ZERO);
    }
    let m = hit.object_to_world;
    let e1 = m * (hit.positions[1] - hit.positions[0]);
    let e2 = m * (hit.positions[2] - hit.positions[0]);
    let cross = e1.cross(e2);
    let twice_area = cross.length();
    if twice_area <= 0.0 {
        return (at, Vec2::ZERO, Vec2::ZERO);
    }
    let n = cross / twice_area;
    let (a0, a1) = cone_axes(n, hit.direction, hit.width);
    // Barycentrics of a point `p` away from the hit, along the plane, by areas; the uv there
    // less the hit's is the gradient.
    let gradient = |p: Vec3| {
        let u = n.dot(p.cross(e2)) / twice_area;
        let v = n.dot(e1.cross(p)) / twice_area;
        (uv[1] - uv[0]) * u + (uv[2] - uv[0]) * v
    };
    (at, gradient(a0), gradient(a1))
}

/// The two axes, in world space, of the ellipse a cone of `width` along the unit direction `d`
/// cuts from the plane of unit normal `n` through its apex's hit: each as long as a pixel's
/// worth of the cone covers on the plane along it.
pub fn cone_axes(n: Vec3, d: Vec3, width: f32) -> (Vec3, Vec3) {
    // The ellipse's major axis: the ray projected on the plane (any direction in it for a ray
    // head-on, where the projection vanishes and the ellipse is a circle), stretched so that
    // its part across the ray is the cone's width.
    let a0 = d - n * n.dot(d);
    let a0 = if a0.dot(a0) > 1.0e-8 { a0 } else { n.cross(if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y }) };
    let a0 = a0 * (width / (a0 - d * d.dot(a0)).length().max(1.0e-4));
    let a1 = n.cross(a0);
    let a1 = a1 * (width / (a1 - d * d.dot(a1)).length().max(1.0e-4));
    (a0, a1)
}

/// The texture coordinates a material reads on a procedural shape at the hit, through its
/// transform, and their gradients across the cone's footprint, as [`footprint`] gives them on
/// a triangle: the shape's coordinates `s` there (`shapes::shape_uv`, from the object-space
/// normal `normal` its intersection reported), the hit's `world_to_object` transform, the
/// world-space unit ray `direction` and the cone's `width` (0: level 0).
pub fn shape_footprint(
    material: &Material,
    s: &ShapeUv,
    (normal, world_to_object): (Vec3, Mat3),
    direction: Vec3,
    width: f32,
) -> (Vec2, Vec2, Vec2) {
    let at = transform_uv(material, s.uv);
    // Normals go to world space through the inverse transpose of object-to-world.
    let n = world_to_object.transpose() * normal;
    let length = n.length();
    if width <= 0.0 || length <= 0.0 {
        return (at, Vec2::ZERO, Vec2::ZERO);
    }
    let (a0, a1) = cone_axes(n / length, direction, width);
    let gradient = |a: Vec3| {
        let o = world_to_object * a;
        transform_gradient(material, Vec2::new(s.du.dot(o), s.dv.dot(o)))
    };
    (at, gradient(a0), gradient(a1))
}

/// Most samples a footprint is filtered with: footprints longer than this many times their
/// width are filtered at a coarser level.
pub const MAX_TAPS: u32 = 8;

/// Where and how a footprint is sampled: `count` samples at `first + step * i`, each with the
/// explicit gradients `dx` and `dy`, averaged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Taps {
    /// How many samples.
    pub count: u32,
    /// The first sample's texture coordinates.
    pub first: Vec2,
    /// From one sample to the next.
    pub step: Vec2,
    /// The gradient of the coordinates along the image's x.
    pub dx: Vec2,
    /// The gradient along y.
    pub dy: Vec2,
}

/// The taps of the footprint at `at` with axes `dx` and `dy` (as [`footprint`] gives them): as
/// many as the long axis is times the short one (up to [`MAX_TAPS`]), spread evenly along the
/// long axis, each with gradients of one tap's share of it and of the short axis, so each is
/// filtered at the level the short axis asks for (or coarser, past `MAX_TAPS`).
pub fn taps(at: Vec2, dx: Vec2, dy: Vec2) -> Taps {
    let (major, minor) = if dx.length_squared() >= dy.length_squared() { (dx, dy) } else { (dy, dx) };
    let (long, short) = (major.length(), minor.length());
    let ratio = if short > 0.0 {
        long / short
    } else if long > 0.0 {
        MAX_TAPS as f32
    } else {
        1.0
    };
    let count = (ratio.ceil() as u32).clamp(1, MAX_TAPS);
    let step = major / count as f32;
    Taps { count, first: at - major * 0.5 + step * 0.5, step, dx: step, dy: minor }
}

/// The spread angle of a primary ray's cone: the angle of one of `samples_per_side` sub-pixel
/// strata at the centre of an image `height` pixels high under a vertical field of view of
/// `fov_y` radians. What `FrameUniform::cone` holds.
#[cfg(not(target_arch = "spirv"))]
pub fn spread_angle(fov_y: f32, height: u32, samples_per_side: u32) -> f32 {
    (2.0 * (fov_y / 2.0).tan() / (height.max(1) * samples_per_side.max(1)) as f32).atan()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn floor_hit(direction: Vec3, width: f32) -> TriangleHit {
        TriangleHit {
            object_to_world: Mat3::IDENTITY,
            positions: [Vec3::ZERO, Vec3::X, Vec3::Z],
            barycentrics: Vec2::new(0.25, 0.25),
            direction: direction.normalize(),
            width,
        }
    }

    /// A floor whose uv is its x and z: seen from straight above, the footprint is the cone's
    /// width both ways; at a grazing angle one axis stays that width (nothing blurs across
    /// the view) and the other grows as 1 / cos (filtered along it, so nothing aliases).
    #[test]
    fn the_footprint_is_round_head_on_and_long_at_a_grazing_angle() {
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        let (at, dx, dy) = footprint(&floor_hit(-Vec3::Y, 0.01), uv);
        assert!((at - Vec2::new(0.25, 0.25)).length() < 1e-6);
        assert!((dx.length() - 0.01).abs() < 1e-5 && (dy.length() - 0.01).abs() < 1e-5, "{dx} {dy}");
        let grazing = Vec3::new(1.0, -0.1, 0.0);
        let cos = grazing.normalize().dot(Vec3::Y).abs();
        let (_, dx, dy) = footprint(&floor_hit(grazing, 0.01), uv);
        let (long, short) = (dx.length().max(dy.length()), dx.length().min(dy.length()));
        assert!((short - 0.01).abs() < 1e-5, "{short}");
        assert!((long - 0.01 / cos).abs() < 1e-4 * long, "{long} against {}", 0.01 / cos);
    }

    /// A cone of width 0 (LOD 0 chosen) samples level 0; a scaled object scales the footprint.
    #[test]
    fn zero_width_is_level_zero_and_scale_counts() {
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        assert_eq!(footprint(&floor_hit(-Vec3::Y, 0.0), uv).1, Vec2::ZERO);
        let mut hit = floor_hit(-Vec3::Y, 0.01);
        hit.object_to_world = Mat3::from_diagonal(Vec3::splat(2.0));
        let (_, dx, _) = footprint(&hit, uv);
        assert!((dx.length() - 0.005).abs() < 1e-6, "{dx}");
    }

    /// A round footprint is one sample; a long one as many as it is times its width, along it,
    /// each filtered at its width; past `MAX_TAPS`, coarser.
    #[test]
    fn taps_spread_along_the_long_axis() {
        let at = Vec2::new(0.5, 0.5);
        let round = taps(at, Vec2::new(0.01, 0.0), Vec2::new(0.0, 0.01));
        assert_eq!((round.count, round.first, round.dx, round.dy), (1, at, Vec2::new(0.01, 0.0), Vec2::new(0.0, 0.01)));
        let long = taps(at, Vec2::new(0.0, 0.001), Vec2::new(0.004, 0.0));
        assert_eq!(long.count, 4);
        assert!((long.step - Vec2::new(0.001, 0.0)).length() < 1e-9);
        assert!((long.first - Vec2::new(0.4985, 0.5)).length() < 1e-6, "{}", long.first);
        let mid = long.first + long.step * 1.5;
        assert!((mid - at).length() < 1e-6, "centred on the hit");
        let very = taps(at, Vec2::new(0.1, 0.0), Vec2::new(0.0, 0.001));
        assert_eq!(very.count, MAX_TAPS);
        assert!(very.dx.length() > very.dy.length(), "each tap coarser than the width");
        assert_eq!(taps(at, Vec2::ZERO, Vec2::ZERO).count, 1, "level 0: one sample");
    }

    #[test]
    fn vertex_uv_reads_its_set_through_the_transform() {
        let v = Vertex { position: Vec4::W, normal: Vec4::Y, uv: Vec4::new(0.5, 0.25, 0.1, 0.2), color: Vec4::ONE };
        let mut m = Material::default();
        assert_eq!(vertex_uv(&m, &v, 0), Vec2::new(0.5, 0.25));
        m.uv_u = Vec4::new(2.0, 0.0, 1.0, 0.0);
        assert_eq!(vertex_uv(&m, &v, 1), Vec2::new(1.2, 0.2));
        assert_eq!(vertex_uv(&m, &v, 0), Vec2::new(2.0, 0.25), "one transform for both sets");
    }

    #[test]
    fn a_pixel_of_a_60_degree_view_480_high() {
        let a = spread_angle(60f32.to_radians(), 480, 1);
        assert!((a - (2.0 * 30f32.to_radians().tan() / 480.0)).abs() < 1e-7);
        assert!((spread_angle(60f32.to_radians(), 480, 4) - a / 4.0).abs() < 1e-6);
    }
}
