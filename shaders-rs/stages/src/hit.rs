//! What the closest-hit stages (closest_hit.rs) and the compute renderer's ray queries
//! (query.rs) share: the surface a ray met, described in the payload for ray generation to
//! shade. Each closest hit gets the material's colour in one of three ways (`MaterialColor`).

use crate::texture::{self, Texture};
use core::arch::asm;
use spirv_std::glam::{Mat3, UVec4, Vec2, Vec3, Vec4, Vec4Swizzles};
use spirv_std::matrix::Matrix4x3;
use spirv_std::RuntimeArray;
use twinray_shared::features::{Features, EMISSION, TEXTURES};
use twinray_shared::layout::{FrameUniform, HitPayload, Material, MaterialCall, ObjectData, Primitive, Vertex};
use twinray_shared::texture::{self as shared_texture, TriangleHit};
use twinray_shared::{shading, shapes, transform};

/// How a closest hit gets the colour of a material at an object-space point and normal.
pub trait MaterialColor {
    /// The colour of `material` at the object-space `point` and `normal`.
    fn of(self, material: &Material, point: Vec3, normal: Vec3) -> Vec3;
}

/// Computed in the closest hit, whatever the material's kind (`twinray_shared::shading`).
pub struct Computed;

impl MaterialColor for Computed {
    #[inline(always)]
    fn of(self, material: &Material, point: Vec3, normal: Vec3) -> Vec3 {
        shading::material_color(material, point, normal)
    }
}

/// The material's one colour, with no branch on its kind: for hit groups of diffuse, emissive
/// and cutout materials only (`hit_groups = "per-material"`).
pub struct Flat;

impl MaterialColor for Flat {
    #[inline(always)]
    fn of(self, material: &Material, _point: Vec3, _normal: Vec3) -> Vec3 {
        material.color_a.xyz()
    }
}

/// From the callable its kind selects (`material_shading = "callable"`), through the stage's
/// callable data.
impl MaterialColor for &mut MaterialCall {
    #[inline(always)]
    fn of(self, material: &Material, point: Vec3, normal: Vec3) -> Vec3 {
        call_material(self, material, point, normal)
    }
}

/// What every procedural closest hit writes: the surface at `hit`, whose intersection stage
/// reported the object-space `normal`, of the object's material (its colour by
/// `material_color`, times its primitive's tint and texture) with the radiance it emits. The
/// primitive is `primitive_base + hit.primitive_id`.
#[allow(clippy::too_many_arguments)]
pub fn procedural_surface(
    hit: &SurfaceHit,
    primitive_base: u32,
    normal: Vec3,
    frame: &FrameUniform,
    objects: &[ObjectData],
    primitives: &[Primitive],
    materials: &[Material],
    textures: &RuntimeArray<Texture>,
    features: Features,
    material_color: impl MaterialColor,
    payload: &mut HitPayload,
) {
    // Each buffer a parameter of its own, not in a tuple: rust-gpu may build a tuple of
    // references as a struct of pointers, with which NVIDIA's driver 580 crashes (the upstream
    // note *nvidia-pointer-struct* of twinray's guide).
    // Copies, as GLSL's twin makes: the driver issues their loads at once, where through
    // references each load waited for the branch that used it (up to 1.1% on the H200).
    // Not bounds-checked, as GLSL's twin is not: the instance id, the object's material and the
    // custom index are the host's, made from the lists it uploads. The three checks cost Rust
    // 1.7% to 3.6% at 1 spp on the H100.
    // SAFETY: see above; robust access reads zeros where a stage from disk strays.
    let material = &unsafe { *materials.get_unchecked(objects.get_unchecked(hit.object as usize).material as usize) };
    let primitive = &unsafe { *primitives.get_unchecked((primitive_base + hit.primitive_id) as usize) };
    let (tint, emission) = procedural_tint(textures, (material, primitive), hit, normal, (frame.cone.x, features));
    let color = material_color.of(material, hit.object_point(), normal) * tint;
    describe_surface(payload, hit, material.kind, normal, normal, (color, emission));
}

/// What every triangle closest hit writes: the surface at `hit` (t measured again where the
/// scene has far instances), its normals interpolated from the triangle's vertices at
/// `barycentrics`, of the object's material (its colour by `material_color`, times the vertex
/// colours and texture) with the radiance it emits.
#[allow(clippy::too_many_arguments)]
pub fn triangle_surface(
    mut hit: SurfaceHit,
    barycentrics: Vec2,
    object_to_world: Matrix4x3,
    frame: &FrameUniform,
    objects: &[ObjectData],
    materials: &[Material],
    vertices: &[Vertex],
    indices: &[u32],
    textures: &RuntimeArray<Texture>,
    features: Features,
    material_color: impl MaterialColor,
    payload: &mut HitPayload,
) {
    // Not bounds-checked, as the procedural closest hit and GLSL's twin are not: the eight
    // checks cost Rust 2.5% to 5.1% on a textured model at 1 spp on the H200.
    // SAFETY: the object (instance id plus geometry index) and its material are the host's,
    // from the lists it uploads; robust access reads zeros where a stage from disk strays.
    let data = unsafe { *objects.get_unchecked(hit.object as usize) };
    let material = unsafe { *materials.get_unchecked(data.material as usize) };
    let v = triangle_vertices(&data, hit.primitive_id, vertices, indices);
    let placed = (object_to_world.w_axis, hit.world_to_object);
    hit.t = triangle_t(features, (hit.origin, hit.direction), placed, &v, hit.t);
    let (geometric, shading_normal) = triangle_normals(&v, barycentrics);
    let cone = cone(&hit, object_to_world.to_mat3(), &v, barycentrics, frame.cone.x);
    let tint = texture::surface_tint(textures, (&material, features), &v, &cone);
    let color = material_color.of(&material, hit.object_point(), geometric) * tint;
    let emission = texture::surface_emission(textures, (&material, features), &v, &cone);
    describe_surface(payload, &hit, material.kind, geometric, shading_normal, (color, emission));
}

/// The colour of `material` at an object-space point and normal, from the callable of the
/// SBT's callable region that the material's kind selects (one record per kind).
pub fn call_material(call: &mut MaterialCall, material: &Material, point: Vec3, normal: Vec3) -> Vec3 {
    call.material = *material;
    call.point = point.extend(1.0);
    call.normal = normal.extend(0.0);
    // Poisoned, so that a callable that writes no colour leaves a NaN in the image.
    call.color = Vec4::splat(f32::from_bits(twinray_shared::bindings::UNWRITTEN));
    // SAFETY: `call` is this stage's callable data; the host gives the callable region a record
    // for every material kind. `spirv_std::arch::execute_callable` takes only a constant index.
    unsafe {
        asm!("OpExecuteCallableKHR {id} {data}", id = in(reg) material.kind, data = in(reg) call);
    }
    call.color.xyz()
}

/// Where a ray met a surface: what a closest-hit stage reads from its built-ins, and the
/// compute renderer from its ray query's committed intersection.
#[derive(Clone, Copy)]
pub struct SurfaceHit {
    /// The object's index: the instance id, plus the geometry index on a mesh
    /// (`twinray_shared::bindings::mesh_object`).
    pub object: u32,
    pub primitive_id: u32,
    pub hit_kind: u32,
    /// The world-space ray.
    pub origin: Vec3,
    pub direction: Vec3,
    /// The object-space ray.
    pub object_origin: Vec3,
    pub object_direction: Vec3,
    pub t: f32,
    pub world_to_object: Mat3,
}

impl SurfaceHit {
    /// The hit at `t` along `rays`: (world origin, direction) and (object origin, direction).
    pub fn new(
        object: u32,
        primitive_id: u32,
        hit_kind: u32,
        ((origin, direction), (object_origin, object_direction)): ((Vec3, Vec3), (Vec3, Vec3)),
        t: f32,
        world_to_object: Mat3,
    ) -> Self {
        SurfaceHit {
            object,
            primitive_id,
            hit_kind,
            origin,
            direction,
            object_origin,
            object_direction,
            t,
            world_to_object,
        }
    }

    /// The hit point in object space.
    pub fn object_point(&self) -> Vec3 {
        self.object_origin + self.object_direction * self.t
    }
}

/// The vertices of triangle `primitive_id` of a mesh object, read without bounds checks. Each
/// read written out, not through a closure: rust-gpu builds a closure's captures as a struct of
/// pointers, and NVIDIA's driver 580 crashes creating a pipeline with one
/// (the upstream note *nvidia-pointer-struct* of twinray's guide).
pub fn triangle_vertices(data: &ObjectData, primitive_id: u32, vertices: &[Vertex], indices: &[u32]) -> [Vertex; 3] {
    let first = (data.index_base + 3 * primitive_id) as usize;
    // SAFETY: the object's first index and first vertex are the host's, and its indices lie
    // within its mesh's vertices (checked when the mesh is loaded).
    unsafe {
        let (i0, i1, i2) =
            (*indices.get_unchecked(first), *indices.get_unchecked(first + 1), *indices.get_unchecked(first + 2));
        let v0 = *vertices.get_unchecked((data.vertex_base + i0) as usize);
        let v1 = *vertices.get_unchecked((data.vertex_base + i1) as usize);
        let v2 = *vertices.get_unchecked((data.vertex_base + i2) as usize);
        [v0, v1, v2]
    }
}

/// The texture coordinates and colours of the corners of triangle `primitive_id` of a mesh
/// object: all the alpha test reads of them, each field read from the buffer on its own and
/// without bounds checks, as `triangle_vertices` reads.
pub fn corner_attributes(
    data: &ObjectData,
    primitive_id: u32,
    vertices: &[Vertex],
    indices: &[u32],
) -> ([Vec4; 3], [Vec4; 3]) {
    let first = (data.index_base + 3 * primitive_id) as usize;
    // SAFETY: as in `triangle_vertices`.
    unsafe {
        let a = vertices.get_unchecked((data.vertex_base + *indices.get_unchecked(first)) as usize);
        let b = vertices.get_unchecked((data.vertex_base + *indices.get_unchecked(first + 1)) as usize);
        let c = vertices.get_unchecked((data.vertex_base + *indices.get_unchecked(first + 2)) as usize);
        ([a.uv, b.uv, c.uv], [a.color, b.color, c.color])
    }
}

/// The t of a hit the driver found on the triangle of vertices `v`, measured again where the
/// scene has far instances (`transform::triangle_t`): the world ray, and the instance's
/// translation and world-to-object 3x3 part.
#[inline(always)]
pub fn triangle_t(features: Features, ray: (Vec3, Vec3), placed: (Vec3, Mat3), v: &[Vertex; 3], t: f32) -> f32 {
    let p = [v[0].position.xyz(), v[1].position.xyz(), v[2].position.xyz()];
    transform::triangle_t(features, ray, placed, p, t)
}

/// Object-space geometric and shading normals of a triangle at `barycentrics`.
pub fn triangle_normals(v: &[Vertex; 3], barycentrics: Vec2) -> (Vec3, Vec3) {
    let p = [v[0].position.xyz(), v[1].position.xyz(), v[2].position.xyz()];
    let n = [v[0].normal.xyz(), v[1].normal.xyz(), v[2].normal.xyz()];
    shading::triangle_normals(p, n, barycentrics.x, barycentrics.y)
}

/// The ray's cone where `hit` met a triangle of vertices `v`: `spread` (radians; 0 for texture
/// level 0) times the distance travelled is its width.
pub fn cone(hit: &SurfaceHit, object_to_world: Mat3, v: &[Vertex; 3], barycentrics: Vec2, spread: f32) -> TriangleHit {
    TriangleHit {
        object_to_world,
        positions: [v[0].position.xyz(), v[1].position.xyz(), v[2].position.xyz()],
        barycentrics,
        direction: hit.direction,
        width: spread * hit.t,
    }
}

/// What the colour of a procedural shape's `material` is multiplied by at `hit` (its
/// primitive's tint, times the material's texture through the shape's parametrisation) and
/// the radiance it emits there, its intersection having reported the object-space `normal`;
/// the ray's cone spreads by `spread` radians (0: texture level 0). Of the scene's `features`,
/// reads textures and emission only where it uses them.
pub fn procedural_tint(
    textures: &RuntimeArray<Texture>,
    (material, primitive): (&Material, &Primitive),
    hit: &SurfaceHit,
    normal: Vec3,
    (spread, features): (f32, Features),
) -> (Vec3, Vec3) {
    let tint = primitive.tint.xyz();
    let emission = if features.has::<EMISSION>() { material.emission.xyz() } else { Vec3::ZERO };
    if !features.has::<TEXTURES>() || (material.texture.x == 0 && material.texture.z == 0) {
        return (tint, emission);
    }
    let uv = shapes::shape_uv(hit.hit_kind, primitive, hit.object_point(), normal);
    let at =
        shared_texture::shape_footprint(material, &uv, (normal, hit.world_to_object), hit.direction, spread * hit.t);
    let (color, light) = texture::shape_textures(textures, material, at);
    (tint * color, emission * light)
}

/// The payload of `hit` on a material of kind `kind`: world normals from the object-space
/// `geometric` and `shading` normals, the surface's `color` and the radiance it `emission`s.
pub fn describe_surface(
    payload: &mut HitPayload,
    hit: &SurfaceHit,
    kind: u32,
    geometric: Vec3,
    shading: Vec3,
    (color, emission): (Vec3, Vec3),
) {
    let (world_geometric, world_shading) =
        shading::surface_normals(hit.world_to_object, geometric, shading, hit.direction);
    payload.position = (hit.origin + hit.direction * hit.t).extend(hit.t);
    // The emission in the spare w components: see `HitPayload::emission`.
    payload.shading_normal = world_shading.extend(emission.x);
    payload.geometric_normal = world_geometric.extend(emission.y);
    payload.color = color.extend(emission.z);
    payload.ids = UVec4::new(hit.object, hit.primitive_id, kind, hit.hit_kind);
}
