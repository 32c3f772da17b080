//! The scene's textures: one runtime array of combined image samplers, indexed per hit by the
//! material's slot (so non-uniformly: `cargo xtask shaders` decorates the accesses
//! `NonUniform`, which rust-gpu cannot yet; see the upstream note *non-uniform* of twinray's guide), sampled with
//! the explicit gradients of the ray cone's footprint (`twinray_shared::texture`).

use core::arch::asm;
use spirv_std::glam::{Vec2, Vec3, Vec4, Vec4Swizzles};
use spirv_std::image::SampledImage;
use spirv_std::{Image, RuntimeArray};
use twinray_shared::features::{Features, EMISSION, TEXTURES};
use twinray_shared::layout::{Material, Vertex};
use twinray_shared::texture::{self, TriangleHit};

/// One texture of the array: 2D, sampled as floats through its own sampler.
pub type Texture = SampledImage<Image!(2D, type = f32, sampled = true)>;

/// What the material's colour is multiplied by on a mesh: the vertex colour interpolated at the
/// hit, times the material's texture (if it has one, and the scene's `features` textures)
/// filtered over the cone's footprint.
pub fn surface_tint(
    textures: &RuntimeArray<Texture>,
    (material, features): (&Material, Features),
    v: &[Vertex; 3],
    hit: &TriangleHit,
) -> Vec3 {
    let b = hit.barycentrics;
    let color = texture::interpolate([v[0].color, v[1].color, v[2].color], b.x, b.y);
    if !features.has::<TEXTURES>() || material.texture.x == 0 {
        return color.xyz();
    }
    let uv = texture::triangle_uv(material, v, material.texture.y);
    color.xyz() * filtered(textures, material.texture.x, texture::footprint(hit, uv))
}

/// The radiance a mesh emits at the hit: the material's emission, times its emission texture
/// (if it has one) filtered over the cone's footprint; zero where the scene's `features` say
/// nothing emits.
pub fn surface_emission(
    textures: &RuntimeArray<Texture>,
    (material, features): (&Material, Features),
    v: &[Vertex; 3],
    hit: &TriangleHit,
) -> Vec3 {
    if !features.has::<EMISSION>() {
        return Vec3::ZERO;
    }
    let emission = material.emission.xyz();
    if !features.has::<TEXTURES>() || material.texture.z == 0 {
        return emission;
    }
    let uv = texture::triangle_uv(material, v, material.texture.w);
    emission * filtered(textures, material.texture.z, texture::footprint(hit, uv))
}

/// What a procedural shape's colour and emission are multiplied by: each texture of the
/// material (1 where it has none) filtered over `footprint`, the one its parametrisation
/// gives (`twinray_shared::texture::shape_footprint`; a shape has one set of coordinates).
pub fn shape_textures(
    textures: &RuntimeArray<Texture>,
    material: &Material,
    footprint: (Vec2, Vec2, Vec2),
) -> (Vec3, Vec3) {
    let color = if material.texture.x == 0 { Vec3::ONE } else { filtered(textures, material.texture.x, footprint) };
    let emission = if material.texture.z == 0 { Vec3::ONE } else { filtered(textures, material.texture.z, footprint) };
    (color, emission)
}

/// Texture `slot`'s colour over a cone's footprint `(at, dx, dy)`: the mean of its taps
/// (`twinray_shared::texture::taps`).
fn filtered(textures: &RuntimeArray<Texture>, slot: u32, (at, dx, dy): (Vec2, Vec2, Vec2)) -> Vec3 {
    let taps = texture::taps(at, dx, dy);
    // SAFETY: the host writes every slot of the array, and a material's slots lie within it.
    let image = unsafe { textures.index(slot as usize) };
    let mut sum = Vec4::ZERO;
    let mut i = 0;
    while i < taps.count {
        // SAFETY: as above.
        sum += unsafe { sample_grad(image, taps.first + taps.step * i as f32, taps.dx, taps.dy) };
        i += 1;
    }
    sum.xyz() / taps.count as f32
}

/// The alpha a mesh's vertex colours and texture (at level 0) give the surface at
/// barycentrics `b`, from its corners' texture coordinates `uv` and colours `color` (as
/// `hit::corner_attributes` reads them) and the material's texture `image` (indexed by the
/// caller): what alpha-tested cutouts (glTF's alpha mode MASK) test. The texture is read only
/// where the scene's `features` have textures.
pub fn surface_alpha(
    image: &Texture,
    (material, features): (&Material, Features),
    (uv, color): ([Vec4; 3], [Vec4; 3]),
    b: Vec2,
) -> f32 {
    let alpha = texture::interpolate(color, b.x, b.y).w;
    if !features.has::<TEXTURES>() || material.texture.x == 0 {
        return alpha;
    }
    let set = material.texture.y;
    let uv = [
        texture::material_uv(material, uv[0], set),
        texture::material_uv(material, uv[1], set),
        texture::material_uv(material, uv[2], set),
    ];
    // SAFETY: `image` is a written slot of the texture array.
    let texel = unsafe { sample_grad(image, texture::uv_at(uv, b), Vec2::ZERO, Vec2::ZERO) };
    alpha * texel.w
}

/// `texture` at `uv`, its level of detail from the gradients `dx` and `dy`
/// (`OpImageSampleExplicitLod` with `Grad`: spirv-std 0.11 offers it only for an image and a
/// separate sampler).
///
/// # Safety
/// `texture` is a bound, written descriptor.
unsafe fn sample_grad(texture: &Texture, uv: Vec2, dx: Vec2, dy: Vec2) -> Vec4 {
    let mut result = Vec4::ZERO;
    asm!(
        "%texture = OpLoad _ {texture}",
        "%uv = OpLoad _ {uv}",
        "%dx = OpLoad _ {dx}",
        "%dy = OpLoad _ {dy}",
        "%result = OpImageSampleExplicitLod typeof*{result} %texture %uv Grad %dx %dy",
        "OpStore {result} %result",
        texture = in(reg) texture,
        uv = in(reg) &uv,
        dx = in(reg) &dx,
        dy = in(reg) &dy,
        result = in(reg) &mut result,
    );
    result
}
