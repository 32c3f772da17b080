//! The closest-hit stages, as macros the crate root invokes (an entry point's name is its path,
//! and the module names are the catalog's). They only describe the surface in the payload; each
//! comes in two forms: with the material's colour computed inline, and (`_callable`) computed
//! by the callable its kind selects in the SBT's callable region (`material_shading =
//! "callable"`).

use crate::texture::Texture;
use core::arch::asm;
use spirv_std::glam::{Mat3, UVec4, Vec2, Vec3, Vec4, Vec4Swizzles};
use spirv_std::RuntimeArray;
use twinray_shared::features::{Features, EMISSION, TEXTURES};
use twinray_shared::layout::{HitPayload, Material, MaterialCall, ObjectData, Primitive, Vertex};
use twinray_shared::texture::{self as shared_texture, TriangleHit};
use twinray_shared::{shading, shapes, transform};

/// Defines a closest-hit entry point for every procedural shape, `$name`: the surface from the
/// reported object-space normal, its colour `$color` of the material `$m`, object-space point
/// `$p` and normal `$n` (the entry also declares `$params`).
///
/// Expands to one `#[spirv(closest_hit)] pub fn $name(..)` taking the hit's built-ins, the
/// object, primitive and material buffers and the payload; twinray's guide, *Rust stages* shows
/// `procedural_closest_hit_flat` expanded.
macro_rules! procedural_closest_hit {
    ($(#[$doc:meta])* $name:ident, [$($params:tt)*], |$m:ident, $p:ident, $n:ident| $color:expr) => {
$(#[$doc])*
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn $name(
    #[spirv(instance_id)] object: u32,
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(hit_attribute)] normal: &Vec3,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    // The scene's features (twinray_shared::features; 31 is `ALL`, for a host that sets none).
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
    $($params)*
) {
    let rays = ((origin, direction), (object_origin, object_direction));
    let surface = hit::SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    // Copies, as GLSL's twin makes: the driver issues their loads at once, where through
    // references each load waited for the branch that used it. On the H200 at 16 spp, Rust/GLSL
    // went from 1.011 to 0.994 on cylinder, 1.005 to 0.995 on box and 1.004 to 0.999 on cutout,
    // and from 0.993 to 0.998 on sphere (twinray's nvidia-code bench report). References had been
    // faster before the features were specialisation constants, when every field was live.
    // Not bounds-checked, as GLSL's twin is not (nor the intersection stages' primitive read,
    // twinray's guide, *Rust stages*): the instance id, the object's material and the custom index are
    // the host's, made from the lists it uploads. The three checks cost Rust 1.7% to 3.6% at
    // 1 spp on the H100 (twinray's nvidia-code bench report).
    // SAFETY: see above; robust access reads zeros where a stage from disk strays.
    let material = &unsafe { *materials.get_unchecked(objects.get_unchecked(object as usize).material as usize) };
    let primitive = &unsafe { *primitives.get_unchecked((primitive_base + primitive_id) as usize) };
    let cone = (frame.cone.x, Features::new(features));
    let (tint, emission) = hit::procedural_tint(textures, (material, primitive), &surface, *normal, cone);
    let ($m, $p, $n) = (material, surface.object_point(), *normal);
    let color = $color * tint;
    hit::describe_surface(payload, &surface, material.kind, *normal, *normal, (color, emission));
}
    };
}

/// Defines a closest-hit entry point for triangle meshes, `$name`: normals from the triangle's
/// vertices (interpolated with the barycentrics), the colour as for `procedural_closest_hit!`.
///
/// Expands to one `#[spirv(closest_hit)] pub fn $name(..)` like `procedural_closest_hit!`'s,
/// with the barycentrics as hit attribute and the vertex and index buffers in place of the
/// primitives.
macro_rules! triangle_closest_hit {
    ($(#[$doc:meta])* $name:ident, [$($params:tt)*], |$m:ident, $p:ident, $n:ident| $color:expr) => {
$(#[$doc])*
#[spirv(closest_hit)]
#[allow(clippy::too_many_arguments)]
pub fn $name(
    #[spirv(instance_id)] object: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(hit_kind)] hit_kind: u32,
    #[spirv(world_ray_origin)] origin: Vec3,
    #[spirv(world_ray_direction)] direction: Vec3,
    #[spirv(object_ray_origin)] object_origin: Vec3,
    #[spirv(object_ray_direction)] object_direction: Vec3,
    #[spirv(ray_tmax)] t: f32,
    #[spirv(world_to_object)] world_to_object: Matrix4x3,
    #[spirv(object_to_world)] object_to_world: Matrix4x3,
    #[spirv(hit_attribute)] barycentrics: &Vec2,
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
    #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
    $($params)*
) {
    let features = Features::new(features);
    // Not bounds-checked, as the procedural closest hit and GLSL's twin are not: the eight
    // checks cost Rust 2.5% to 5.1% on a textured model at 1 spp on the H200
    // (twinray's nvidia-code bench report).
    // SAFETY: the instance id and the object's material are the host's, from the lists it
    // uploads; robust access reads zeros where a stage from disk strays.
    let data = unsafe { *objects.get_unchecked(object as usize) };
    let material = unsafe { *materials.get_unchecked(data.material as usize) };
    let v = hit::triangle_vertices(&data, primitive_id, vertices, indices);
    let rays = ((origin, direction), (object_origin, object_direction));
    let placed = (object_to_world.w_axis, world_to_object.to_mat3());
    let t = hit::triangle_t(features, rays.0, placed, &v, t);
    let surface = hit::SurfaceHit::new(object, primitive_id, hit_kind, rays, t, world_to_object.to_mat3());
    let (geometric, shading_normal) = hit::triangle_normals(&v, *barycentrics);
    let ($m, $p, $n) = (&material, surface.object_point(), geometric);
    let cone = hit::cone(&surface, object_to_world.to_mat3(), &v, *barycentrics, frame.cone.x);
    let color = $color * texture::surface_tint(textures, (&material, features), &v, &cone);
    let emission = texture::surface_emission(textures, (&material, features), &v, &cone);
    hit::describe_surface(payload, &surface, material.kind, geometric, shading_normal, (color, emission));
}
    };
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
    /// The instance id (the object's index).
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
    let (color, light) = crate::texture::shape_textures(textures, material, at);
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
