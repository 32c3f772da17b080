//! Every struct that crosses the CPU/GPU line, defined once. `#[repr(C)]`, built from scalars,
//! `Vec4`, `UVec4` and `Mat4` only, so std140/std430 and Rust agree; sizes are asserted at
//! compile time, and `glsl.rs` generates the GLSL mirror from the same fields.

use glam::{Mat4, UVec4, Vec3, Vec4};

/// Uniform buffer at [`crate::bindings::BINDING_FRAME`].
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct FrameUniform {
    /// Camera-to-world transform.
    pub view_inverse: Mat4,
    /// Clip-to-camera transform.
    pub proj_inverse: Mat4,
    /// rgb: colour of rays that hit nothing; w: unused.
    pub background: Vec4,
    /// How far rays reach, worked out from the scene's bounds and the camera (never a constant
    /// in scene units, so a scene's unit does not change its picture): x, the t_max of primary
    /// rays (past the scene's farthest point from the camera); y, the t_max of directional
    /// lights' shadow rays (across the whole scene); z, the t_min of primary rays (a fixed
    /// fraction of x); w: unused. Shadow rays start at 0 from an origin offset off the surface.
    pub reach: Vec4,
    /// Number of lights in the light buffer.
    pub light_count: u32,
    /// Seed of the per-pixel, per-sample random sequence.
    pub seed: u32,
    /// Image width and height in pixels: the compute renderer's launch size, which compute
    /// stages have no built-in for (ray generation reads `launch_size`).
    pub width: u32,
    /// Image height in pixels (see `width`).
    pub height: u32,
    /// Texture level of detail by ray cones ([`crate::texture`]): x, the spread angle of a
    /// primary ray's cone in radians (a pixel's angle at the image centre, over the samples per
    /// side), or 0 for level 0 everywhere (`textures.lod = "zero"`, and orthographic cameras);
    /// y, 1 for an orthographic camera (parallel rays from the camera's plane, which
    /// `proj_inverse` maps the image onto: [`crate::camera::primary_ray`]), 0 for a perspective
    /// one; zw: unused.
    pub cone: Vec4,
}
const _: () = assert!(core::mem::size_of::<FrameUniform>() == 192);

/// Per object, indexed by the object: its TLAS instance's index, plus the geometry index of a
/// hit on a mesh ([`crate::bindings::mesh_object`]).
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct ObjectData {
    /// Index into the material buffer.
    pub material: u32,
    /// Index of this object's vertex 0 in the vertex buffer (meshes).
    pub vertex_base: u32,
    /// Index of this object's first index in the index buffer (meshes).
    pub index_base: u32,
    /// The intersection routine of its procedural shape: the shape's hit kind, plus
    /// `shapes::SHAPE_NAIVE` for the naive variant; 0 for meshes. Read where primitives are
    /// intersected without the pipeline's intersection stages (ray queries).
    pub shape: u32,
}
const _: () = assert!(core::mem::size_of::<ObjectData>() == 16);

/// One procedural primitive in object space. Sphere: `a` = centre and radius.
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Primitive {
    /// The shape's first parameters: a sphere's centre and radius; other shapes', as their
    /// module says.
    pub a: Vec4,
    /// The shape's further parameters, as its module says.
    pub b: Vec4,
    /// rgb: multiplies the material's colour (a sphere field's per-sphere colour); w: unused.
    pub tint: Vec4,
}
const _: () = assert!(core::mem::size_of::<Primitive>() == 48);

/// One mesh vertex, in object space. Flat-shaded meshes repeat vertices per face, with the
/// face normal, so the shaders always interpolate `normal`. Position first: the BLAS builds
/// read it with the struct's size as stride.
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Vertex {
    /// xyz: position; w: 1.
    pub position: Vec4,
    /// xyz: unit normal; w: 0.
    pub normal: Vec4,
    /// xy: texture coordinate set 0; zw: set 1 (glTF's TEXCOORD_0 and TEXCOORD_1; 0 where absent).
    pub uv: Vec4,
    /// Linear RGBA the material's colour is multiplied by (glTF's COLOR_0; 1 where absent).
    pub color: Vec4,
}
const _: () = assert!(core::mem::size_of::<Vertex>() == 64);

#[cfg(not(target_arch = "spirv"))]
impl Vertex {
    /// A vertex at `position` with no normal, texture coordinates 0 and a white colour.
    pub fn at(position: glam::Vec3) -> Vertex {
        Vertex { position: position.extend(1.0), normal: Vec4::ZERO, uv: Vec4::ZERO, color: Vec4::ONE }
    }
}

/// A material. Diffuse: `color_a` is the albedo. Emissive: `color_a` is the emitted radiance.
/// Checker: `color_a` and `color_b` alternate in cubes of side `1 / color_b.w` in object space.
/// Cutout: albedo `color_a`, with holes where the alpha pattern `cutout_pattern` is below
/// `cutout_threshold` (see [`crate::shading::cutout_alpha`]).
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Material {
    /// `bindings::MATERIAL_*`: which of the materials above this is.
    pub kind: u32,
    /// `CUTOUT_NONE`, `CUTOUT_CHECKER` or `CUTOUT_DISCS`.
    pub cutout_pattern: u32,
    /// Pattern cells per object-space unit.
    pub cutout_scale: f32,
    /// The surface is a hole where the pattern's alpha is below this.
    pub cutout_threshold: f32,
    /// rgb: the albedo (checker: the first colour); w: unused.
    pub color_a: Vec4,
    /// rgb: the checker's second colour; w: the checker's cells per object-space unit.
    pub color_b: Vec4,
    /// The base colour texture, which multiplies `color_a` on meshes: x, its slot in the
    /// texture array ([`crate::bindings::BINDING_TEXTURES`]), 0 for none; y, the vertex
    /// texture coordinate set it reads (0 or 1). The emission texture, which multiplies
    /// `emission` on meshes: z, its slot (0 for none); w, its set.
    pub texture: UVec4,
    /// The texture coordinates' transform (glTF's KHR_texture_transform), rows of a 2x3
    /// matrix: u' = dot(uv_u.xy, uv) + uv_u.z, v' = dot(uv_v.xy, uv) + uv_v.z; w: 0.
    /// Both textures read coordinates through it.
    pub uv_u: Vec4,
    /// The second row of the texture coordinates' transform (see `uv_u`).
    pub uv_v: Vec4,
    /// rgb: the radiance the surface emits (glTF's emissive factor), added to the light it
    /// reflects; w: 0. Emissive materials (`MATERIAL_EMISSIVE`) show `color_a` instead.
    pub emission: Vec4,
}
const _: () = assert!(core::mem::size_of::<Material>() == 112);

#[cfg(not(target_arch = "spirv"))]
impl Material {
    /// A white cutout material with `pattern` (`CUTOUT_*`) in cells of side `1 / scale` and
    /// holes where its alpha is below `threshold`.
    pub fn cutout(pattern: u32, scale: f32, threshold: f32) -> Material {
        Material {
            kind: crate::bindings::MATERIAL_CUTOUT,
            cutout_pattern: pattern,
            cutout_scale: scale,
            cutout_threshold: threshold,
            color_a: Vec4::ONE,
            color_b: Vec4::ZERO,
            ..Material::default()
        }
    }
}

#[cfg(not(target_arch = "spirv"))]
impl Default for Material {
    /// A white diffuse material with no texture and the identity texture transform.
    fn default() -> Material {
        Material {
            kind: crate::bindings::MATERIAL_DIFFUSE,
            cutout_pattern: crate::bindings::CUTOUT_NONE,
            cutout_scale: 1.0,
            cutout_threshold: 0.0,
            color_a: Vec4::ONE,
            color_b: Vec4::ZERO,
            texture: UVec4::ZERO,
            uv_u: Vec4::X,
            uv_v: Vec4::Y,
            emission: Vec4::ZERO,
        }
    }
}

/// A light. Directional: `position` holds the unit direction towards the light. Point: the
/// position, with its range and cone (a spot light) in `position.w`, `u` and `v`. Rect: the
/// centre, with edge vectors `u` and `v`, sampled `samples` x `samples`.
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Light {
    /// `bindings::LIGHT_*`: which of the lights above this is.
    pub kind: u32,
    /// Shadow samples per side (rect lights).
    pub samples: u32,
    /// 1 when the light casts shadows.
    pub shadows: u32,
    /// Padding to the 16-byte alignment of `position`.
    pub _pad0: u32,
    /// xyz: the position (point light, rect light's centre), or the unit direction towards a
    /// directional light; w: a point light's 1 / range, 0 for none ([`crate::lighting`]).
    pub position: Vec4,
    /// rgb: colour times intensity.
    pub radiance: Vec4,
    /// xyz: a rect light's first edge vector, or a point light's unit axis (the way a spot
    /// light shines; zero for none); w: unused.
    pub u: Vec4,
    /// xyz: a rect light's second edge vector; for a point light, x and y scale and offset
    /// the cosine to its axis into its cone's falloff (0 and 1 for no cone); w: unused.
    pub v: Vec4,
}
const _: () = assert!(core::mem::size_of::<Light>() == 80);

/// The payload of primary rays: what the closest-hit stage found, for ray generation to shade.
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct HitPayload {
    /// xyz: world-space hit point; w: the ray parameter t. (Recomputing it in ray generation
    /// from the ray measured 0.8% slower for the Rust set on an H200: the ray stays live
    /// across the trace.)
    pub position: Vec4,
    /// xyz: world-space unit normal for shading, facing the ray's origin; w: the red of the
    /// emitted radiance.
    pub shading_normal: Vec4,
    /// xyz: world-space unit geometric normal, facing the ray's origin (for ray offsets); w:
    /// the green of the emitted radiance.
    pub geometric_normal: Vec4,
    /// rgb: albedo, or emitted radiance for emissive materials, or the background on a miss.
    /// w: the blue of the radiance the surface emits besides (see [`HitPayload::emission`]).
    pub color: Vec4,
    /// x: object, y: primitive, z: material kind, w: hit kind, or `NO_HIT` on a miss.
    pub ids: UVec4,
}

impl HitPayload {
    /// The radiance a hit surface emits on top of what it reflects (a material's `emission`,
    /// times its emission texture), kept in the three vectors' spare w components: a field of
    /// its own would grow the payload every trace call carries from 80 to 96 bytes. 0 on a
    /// miss and for emissive materials (their `color` is their radiance).
    pub fn emission(&self) -> Vec3 {
        Vec3::new(self.shading_normal.w, self.geometric_normal.w, self.color.w)
    }

    /// Fills the words [`HitPayload::unwritten`] reads with [`crate::bindings::UNWRITTEN`]:
    /// what ray generation does before each trace, so that a hit or miss stage that writes
    /// nothing is seen, instead of the last ray's payload, or whatever the driver's memory
    /// held, being judged. Only those six words: filling all twenty cost the GLSL set 3.7% on
    /// showcase on an H100 (1920x1080, 12 placements), the six at most 0.5% on any scene.
    pub fn poison(&mut self) {
        let f = f32::from_bits(crate::bindings::UNWRITTEN);
        self.ids.w = crate::bindings::UNWRITTEN;
        self.color.x = f;
        self.position.x = f;
        self.position.w = f;
        self.shading_normal.x = f;
        self.geometric_normal.x = f;
    }

    /// Whether the stage that took the ray left what its reader needs of the poison
    /// ([`HitPayload::poison`]).
    /// Every hit and miss stage writes `ids` (a miss `NO_HIT` in `ids.w`) and `color`; a hit
    /// also the point, t and both normals. `all` asks for every field (ray generation shades
    /// with them); without it, only what the probe reads: `ids`, and on a hit `position.w`
    /// and `shading_normal` (all that the probe's witness closest-hit stage writes). One word
    /// of each vector stands for it: stages write vectors whole.
    pub fn unwritten(&self, all: bool) -> bool {
        let poisoned = |x: f32| x.to_bits() == crate::bindings::UNWRITTEN;
        // `|` and `&`, not `||` and `&&`: every operand is a comparison, and rust-gpu writes
        // each short circuit as a branch with a phi after the trace.
        let hit = self.ids.w != crate::bindings::NO_HIT;
        let seen_by_all =
            poisoned(self.color.x) | (hit & (poisoned(self.position.x) | poisoned(self.geometric_normal.x)));
        let seen_by_probe = hit & (poisoned(self.position.w) | poisoned(self.shading_normal.x));
        (self.ids.w == crate::bindings::UNWRITTEN) | (all & seen_by_all) | seen_by_probe
    }

    /// All zeros: the compute stages' payload before their ray query describes a hit into it.
    pub const NONE: HitPayload = HitPayload {
        position: Vec4::ZERO,
        shading_normal: Vec4::ZERO,
        geometric_normal: Vec4::ZERO,
        color: Vec4::ZERO,
        ids: UVec4::ZERO,
    };
}

/// The callable data of material callables (`material_shading = "callable"`): the closest-hit
/// stage fills in the material and the object-space point and normal, and the callable
/// chosen by the material's kind writes `color`.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct MaterialCall {
    /// The hit surface's material.
    pub material: Material,
    /// xyz: object-space point; w: 1.
    pub point: Vec4,
    /// xyz: object-space normal (any length); w: 0.
    pub normal: Vec4,
    /// rgb: the albedo (or emitted radiance) the callable computed.
    pub color: Vec4,
}
const _: () = assert!(core::mem::size_of::<MaterialCall>() == 160);

/// The payload of shadow rays: 1 until the shadow miss stage clears it.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct ShadowPayload {
    /// 1 when something lies between the point and the light.
    pub occluded: u32,
}

/// One probe ray (`twinray probe`): origin and t_min, direction and t_max.
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct ProbeRay {
    /// xyz: world-space origin; w: t_min.
    pub origin: Vec4,
    /// xyz: world-space direction (any length); w: t_max.
    pub direction: Vec4,
}
const _: () = assert!(core::mem::size_of::<ProbeRay>() == 32);

/// What a probe ray hit, as the closest-hit stage described it.
///
/// The probe's witness pass (the `probe_witness` closest-hit stage in place of each hit
/// group's own) fills the same fields with what the GPU handed the hit group's stages:
/// `normal_t` xyz: the object-space ray origin, w: the t they reported (on the world ray);
/// `ids` xyz: the bits of the object-space ray direction, w: the bits of how far along the
/// world ray that origin lies (`transform::StageRay::shift`, a finite f32 never equal to
/// `NO_HIT`, which a miss writes there).
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct ProbeResult {
    /// xyz: world-space shading normal facing the ray's origin; w: t.
    pub normal_t: Vec4,
    /// x: object, y: primitive, z: material kind, w: hit kind, or `NO_HIT` on a miss.
    pub ids: UVec4,
}
const _: () = assert!(core::mem::size_of::<ProbeResult>() == 32);

/// One ray of `twinray explain`, traced as the renderer traces rays of its `kind`: a primary
/// ray (`EXPLAIN_PRIMARY`, over the camera's reach) or a shadow ray (`EXPLAIN_SHADOW`, from 0
/// to `direction.w`).
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct ExplainRay {
    /// xyz: world-space origin; w: 0.
    pub origin: Vec4,
    /// xyz: world-space direction; w: a shadow ray's length (0 for a primary ray).
    pub direction: Vec4,
    /// x: `EXPLAIN_PRIMARY` or `EXPLAIN_SHADOW`; yzw: 0.
    pub kind: UVec4,
}
const _: () = assert!(core::mem::size_of::<ExplainRay>() == 48);

/// What an explain ray found: of a primary ray, the payload the hit or miss stage left (and
/// `occluded` all zero); of a shadow ray, `occluded.x` 1 if something cast a shadow, else 0
/// (and `hit` all zero).
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(Debug, PartialEq))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct ExplainResult {
    /// A primary ray's payload, as its hit or miss stage left it.
    pub hit: HitPayload,
    /// x: of a shadow ray, 1 when something cast a shadow; y, z, w: 0.
    pub occluded: UVec4,
}
const _: () = assert!(core::mem::size_of::<ExplainResult>() == 96);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bindings::{NO_HIT, UNWRITTEN};

    /// A stage that wrote nothing, a miss, a hit, and a hit missing each word the readers
    /// check: what ray generation (`all`) and the probe see.
    #[test]
    fn unwritten_sees_each_poisoned_word_its_reader_needs() {
        let mut poisoned = HitPayload::NONE;
        poisoned.poison();
        assert!(poisoned.unwritten(true) && poisoned.unwritten(false));
        let mut miss = poisoned;
        miss.ids = UVec4::new(0, 0, 0, NO_HIT);
        assert!(miss.unwritten(true), "a miss that leaves its colour poisoned");
        assert!(!miss.unwritten(false), "the probe reads no colour");
        miss.color = Vec4::ONE;
        assert!(!miss.unwritten(true));
        let written = HitPayload {
            position: Vec4::ONE,
            shading_normal: Vec4::Y,
            geometric_normal: Vec4::Y,
            color: Vec4::ONE,
            ids: UVec4::new(1, 2, 0, 3),
        };
        assert!(!written.unwritten(true) && !written.unwritten(false));
        let f = f32::from_bits(UNWRITTEN);
        type Poison = fn(&mut HitPayload, f32);
        let cases: [(Poison, bool); 5] = [
            (|p, f| p.color.x = f, false),
            (|p, f| p.position.x = f, false),
            (|p, f| p.geometric_normal.x = f, false),
            (|p, f| p.position.w = f, true),
            (|p, f| p.shading_normal.x = f, true),
        ];
        for (i, (poison, probe_sees)) in cases.iter().enumerate() {
            let mut p = written;
            poison(&mut p, f);
            assert!(p.unwritten(true), "case {i}");
            assert_eq!(p.unwritten(false), *probe_sees, "case {i}");
        }
    }
}
