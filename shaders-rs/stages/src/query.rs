//! Tracing inline with ray queries (`VK_KHR_ray_query`): shadow rays from ray generation
//! (`shadow_method = "query"`), and primary rays of the compute renderer (`renderer =
//! "compute"`). No shader of the pipeline runs, so what its stages would decide is decided
//! here, with the same shared code: a procedural candidate by its shape's routine, a cutout's
//! holes by its pattern, and the committed hit described as its closest-hit stage would.
//! Loops follow the NVIDIA rules of trace.rs: nested `if`s, indices checked rather than
//! bounds-checked.

use crate::hit::{self, SurfaceHit};
use crate::texture::{self, Texture};
use core::arch::asm;
use spirv_std::glam::{UVec4, Vec2, Vec3, Vec4};
use spirv_std::matrix::Matrix4x3;
use spirv_std::ray_tracing::{AccelerationStructure, CandidateIntersection, CommittedIntersection, RayFlags, RayQuery};
use spirv_std::RuntimeArray;
use twinray_shared::bindings::mesh_object;
use twinray_shared::bindings::{
    CUTOUT_TEXTURE, HIT_KIND_TRIANGLE_BACK, HIT_KIND_TRIANGLE_FRONT, MASK_OCCLUDER, NO_HIT,
};
use twinray_shared::camera::Ray;
use twinray_shared::features::{Features, ALPHA_MASKS};
use twinray_shared::layout::{FrameUniform, HitPayload, Material, ObjectData, Primitive, Vertex};
use twinray_shared::shapes::{self, SHAPE_NAIVE};
use twinray_shared::{shading, transform};

/// The ray parameter of the query's candidate if it is a hit, decided as the pipeline's stages
/// would, else -1: a triangle at its t (up to `t_max`), a procedural primitive by its shape's
/// routine between `t_min` and `t_max`, and for cutouts (the only instances not forced opaque)
/// not in a hole: of their pattern, or on meshes of their own alpha (its opacity, its vertex
/// colours' and its texture's at level 0, read from the `mesh` buffers and `textures`), as
/// `triangle_cutout_any_hit` decides. With it, a procedural hit's object-space normal.
///
/// # Safety
/// `query` has a current candidate: `proceed` returned true.
unsafe fn candidate_hit(
    query: &RayQuery,
    (objects, primitives, materials): (&[ObjectData], &[Primitive], &[Material]),
    (vertices, indices): Mesh,
    textures: &RuntimeArray<Texture>,
    (t_min, t_max): (f32, f32),
    features: Features,
) -> (f32, Vec3) {
    let instance = query.get_candidate_intersection_instance_id();
    let object = mesh_object(instance, query.get_candidate_intersection_geometry_index()) as usize;
    let primitive_id = query.get_candidate_intersection_primitive_index();
    let primitive = (query.get_candidate_intersection_instance_custom_index() + primitive_id) as usize;
    let (mut t, mut normal) = (-1.0, Vec3::ZERO);
    if object < objects.len() {
        let data = *objects.get_unchecked(object);
        let o = query.get_candidate_intersection_object_ray_origin();
        let d = query.get_candidate_intersection_object_ray_direction();
        let triangle = query.get_candidate_intersection_type() == CandidateIntersection::Triangle;
        if triangle {
            let candidate = query.get_candidate_intersection_t();
            if candidate <= t_max {
                t = candidate;
            }
        } else if primitive < primitives.len() {
            let p = *primitives.get_unchecked(primitive);
            // The shape sees the object-space ray its intersection stage would
            // (twinray_shared::transform); the cutout's pattern below, the driver's.
            let ray = transform::stage_ray(
                features,
                (o, d),
                (query.get_world_ray_origin(), query.get_world_ray_direction()),
                (query.get_candidate_intersection_object_to_world().w_axis, candidate_world_to_object(query).to_mat3()),
                shapes::shape_bound(data.shape, &p),
            );
            let (near, far) = ray.range(t_min, t_max);
            if let Some(hit) = shapes::intersect_shape(data.shape, ray.origin, ray.direction, &p, near, far) {
                (t, normal) = (ray.world_t(hit.t, t_max), hit.normal);
            }
        }
        let material = data.material as usize;
        // Holes only where the scene has cutouts: other instances are forced opaque.
        if features.has::<ALPHA_MASKS>() & (t >= 0.0) {
            if material < materials.len() {
                let m = materials.get_unchecked(material);
                let mut alpha = shading::cutout_alpha(m, o + d * t);
                if triangle {
                    if m.cutout_pattern == CUTOUT_TEXTURE {
                        let corners = hit::corner_attributes(&data, primitive_id, vertices, indices);
                        let b: Vec2 = query.get_candidate_intersection_barycentrics();
                        // Indexed here and the image handed on, as `triangle_cutout_any_hit` does
                        // (twinray's guide, *Rust stages*).
                        let image = textures.index(m.texture.x as usize);
                        alpha *= texture::surface_alpha(image, (m, features), corners, b);
                    }
                }
                if alpha < m.cutout_threshold {
                    t = -1.0;
                }
            }
        }
    }
    (t, normal)
}

/// The meshes' vertex and index buffers. (The texture array goes beside them, never in a
/// tuple: a struct may not hold images in Vulkan's SPIR-V.)
pub type Mesh<'a> = (&'a [Vertex], &'a [u32]);

/// The buffers a ray query reads to decide what the pipeline's stages would: the objects,
/// primitives and materials, and the meshes'.
pub type Scene<'a> = ((&'a [ObjectData], &'a [Primitive], &'a [Material]), Mesh<'a>);

/// Whether nothing that casts shadows lies between `origin` and `distance` along `direction`
/// (as `trace::visible`), traced inline: any hit `candidate_hit` takes ends the query.
#[allow(clippy::too_many_arguments)]
pub fn visible_query(
    tlas: &AccelerationStructure,
    origin: Vec3,
    direction: Vec3,
    distance: f32,
    features: Features,
    (hit_buffers, mesh): Scene,
    textures: &RuntimeArray<Texture>,
) -> bool {
    spirv_std::ray_query!(let mut query);
    let mut occluded = false;
    // SAFETY: the TLAS is bound and built; `query` is this invocation's own ray query, and
    // each candidate is read only after `proceed` returned true.
    unsafe {
        query.initialize(tlas, RayFlags::TERMINATE_ON_FIRST_HIT, MASK_OCCLUDER, origin, 0.0, direction, distance);
        while query.proceed() {
            if candidate_hit(query, hit_buffers, mesh, textures, (0.0, distance), features).0 >= 0.0 {
                occluded = true;
                query.terminate();
            }
        }
        !occluded && query.get_committed_intersection_type() == CommittedIntersection::None
    }
}

/// The compute renderer's primary ray (see [`trace_query`]), over the pipeline's primary ray
/// interval.
#[allow(clippy::too_many_arguments)]
pub fn primary_query(
    tlas: &AccelerationStructure,
    ray: Ray,
    reach: (f32, f32),
    features: Features,
    payload: &mut HitPayload,
    frame: &FrameUniform,
    objects: &[ObjectData],
    primitives: &[Primitive],
    materials: &[Material],
    vertices: &[Vertex],
    indices: &[u32],
    textures: &RuntimeArray<Texture>,
) {
    let hit_buffers = (objects, primitives, materials);
    let mesh = (vertices, indices);
    trace_query(tlas, ray, reach, payload, frame.background, hit_buffers, mesh, textures, (frame.cone.x, features));
}

/// `ray` over `(t_min, t_max)`, traced inline: each candidate decided by `candidate_hit` and
/// committed if no farther than the closest so far; the committed hit described into `payload`
/// as the closest-hit stage of its hit group would, or `background` as the miss stage would;
/// meshes with their vertices, indices, textures and the spread angle of the ray's cone (0:
/// texture level 0).
#[allow(clippy::too_many_arguments)]
pub fn trace_query(
    tlas: &AccelerationStructure,
    ray: Ray,
    (t_min, t_max): (f32, f32),
    payload: &mut HitPayload,
    background: Vec4,
    (objects, primitives, materials): (&[ObjectData], &[Primitive], &[Material]),
    (vertices, indices): (&[Vertex], &[u32]),
    textures: &RuntimeArray<Texture>,
    (spread, features): (f32, Features),
) {
    spirv_std::ray_query!(let mut query);
    // The committed procedural hit's normal: each commit is no farther than the one before.
    let mut normal = Vec3::ZERO;
    // SAFETY: as in `visible_query`; the committed intersection is read only when there is one.
    unsafe {
        query.initialize(tlas, crate::flags::PRIMARY_RAY_FLAGS, 0xff, ray.origin, t_min, ray.direction, t_max);
        while query.proceed() {
            let closest = if query.get_committed_intersection_type() == CommittedIntersection::None {
                t_max
            } else {
                query.get_committed_intersection_t()
            };
            let hit_buffers = (objects, primitives, materials);
            let (t, n) = candidate_hit(query, hit_buffers, (vertices, indices), textures, (t_min, closest), features);
            if t >= 0.0 {
                if query.get_candidate_intersection_type() == CandidateIntersection::Triangle {
                    query.confirm_intersection();
                } else {
                    normal = n;
                    generate_intersection(query, t);
                }
            }
        }
        let committed = query.get_committed_intersection_type();
        if committed == CommittedIntersection::None {
            payload.color = background;
            payload.ids = UVec4::splat(NO_HIT);
            return;
        }
        let rays = (
            (ray.origin, ray.direction),
            (
                query.get_committed_intersection_object_ray_origin(),
                query.get_committed_intersection_object_ray_direction(),
            ),
        );
        let instance = query.get_committed_intersection_instance_id();
        let object = mesh_object(instance, query.get_committed_intersection_geometry_index());
        let primitive_id = query.get_committed_intersection_primitive_index();
        let t = query.get_committed_intersection_t();
        let world_to_object = committed_transform::<true>(query).to_mat3();
        let data = objects[object as usize];
        let material = materials[data.material as usize];
        if committed == CommittedIntersection::Triangle {
            let front = query.get_committed_intersection_front_face();
            let kind = if front { HIT_KIND_TRIANGLE_FRONT } else { HIT_KIND_TRIANGLE_BACK };
            let v = hit::triangle_vertices(&data, primitive_id, vertices, indices);
            let object_to_world = committed_transform::<false>(query);
            let t = hit::triangle_t(features, rays.0, (object_to_world.w_axis, world_to_object), &v, t);
            let surface = SurfaceHit::new(object, primitive_id, kind, rays, t, world_to_object);
            let barycentrics: Vec2 = query.get_committed_intersection_barycentrics();
            let (geometric, shading_normal) = hit::triangle_normals(&v, barycentrics);
            let object_to_world = object_to_world.to_mat3();
            let cone = hit::cone(&surface, object_to_world, &v, barycentrics, spread);
            let color = shading::material_color(&material, surface.object_point(), geometric)
                * texture::surface_tint(textures, (&material, features), &v, &cone);
            let emission = texture::surface_emission(textures, (&material, features), &v, &cone);
            hit::describe_surface(payload, &surface, material.kind, geometric, shading_normal, (color, emission));
        } else {
            let surface = SurfaceHit::new(object, primitive_id, data.shape & !SHAPE_NAIVE, rays, t, world_to_object);
            let primitive = query.get_committed_intersection_instance_custom_index() + primitive_id;
            let primitive = primitives[primitive as usize];
            let cone = (spread, features);
            let (tint, emission) = hit::procedural_tint(textures, (&material, &primitive), &surface, normal, cone);
            let color = shading::material_color(&material, surface.object_point(), normal) * tint;
            hit::describe_surface(payload, &surface, material.kind, normal, normal, (color, emission));
        }
    }
}

/// Commits a procedural candidate at `t` (`OpRayQueryGenerateIntersectionKHR`, which
/// spirv-std 0.11 lacks).
///
/// # Safety
/// The current candidate is an AABB, and `t` lies between the ray's t_min and the committed t.
unsafe fn generate_intersection(query: &RayQuery, t: f32) {
    asm!("OpRayQueryGenerateIntersectionKHR {query} {t}", query = in(reg) query, t = in(reg) t);
}

/// The candidate intersection's world-to-object transform
/// (`OpRayQueryGetIntersectionWorldToObjectKHR`, which spirv-std 0.11 lacks).
///
/// # Safety
/// `query` has a current candidate: `proceed` returned true.
unsafe fn candidate_world_to_object(query: &RayQuery) -> Matrix4x3 {
    let mut result = Matrix4x3::default();
    asm! {
        "%u32 = OpTypeInt 32 0",
        "%candidate = OpConstant %u32 0",
        "%result = OpRayQueryGetIntersectionWorldToObjectKHR typeof*{result} {query} %candidate",
        "OpStore {result} %result",
        query = in(reg) query,
        result = in(reg) &mut result,
    }
    result
}

/// The committed intersection's world-to-object transform (`WORLD_TO_OBJECT`) or
/// object-to-world transform (`OpRayQueryGetIntersectionWorldToObjectKHR` and
/// `OpRayQueryGetIntersectionObjectToWorldKHR`, which spirv-std 0.11 lacks).
///
/// # Safety
/// There is a committed intersection.
unsafe fn committed_transform<const WORLD_TO_OBJECT: bool>(query: &RayQuery) -> Matrix4x3 {
    let mut result = Matrix4x3::default();
    if WORLD_TO_OBJECT {
        asm! {
            "%u32 = OpTypeInt 32 0",
            "%committed = OpConstant %u32 1",
            "%result = OpRayQueryGetIntersectionWorldToObjectKHR typeof*{result} {query} %committed",
            "OpStore {result} %result",
            query = in(reg) query,
            result = in(reg) &mut result,
        }
    } else {
        asm! {
            "%u32 = OpTypeInt 32 0",
            "%committed = OpConstant %u32 1",
            "%result = OpRayQueryGetIntersectionObjectToWorldKHR typeof*{result} {query} %committed",
            "OpStore {result} %result",
            query = in(reg) query,
            result = in(reg) &mut result,
        }
    }
    result
}
