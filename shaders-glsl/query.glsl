// Twin of twinray_stages::query: tracing inline with ray queries, deciding what the
// pipeline's stages would (a procedural candidate by its shape's routine, a cutout's holes by
// its pattern) and describing the committed hit as its closest-hit stage would. Included after
// the includer declares tlas, objects, primitives, materials, vertices, indices and textures;
// with RENDER_COMPUTE defined, also `payload` (a plain HitPayload), for trace_query.
#ifndef TWINRAY_QUERY_GLSL
#define TWINRAY_QUERY_GLSL
#include "shading.glsl"
#include "shape_dispatch.glsl"
#include "texture.glsl"
#include "transform.glsl"

// The ray parameter of the query's candidate if it is a hit, decided as the pipeline's stages
// would, else -1: a triangle at its t (up to t_max), a procedural primitive by its shape's
// routine between t_min and t_max, and for cutouts (the only instances not forced opaque) not
// in a hole: of their pattern, or on meshes of their own alpha, as triangle_cutout_any_hit
// decides. normal: a procedural hit's object-space normal.
float candidate_hit(rayQueryEXT query, float t_min, float t_max, out vec3 normal) {
    // The object: instance id plus geometry index (twinray_shared::bindings::mesh_object).
    ObjectData data = objects[rayQueryGetIntersectionInstanceIdEXT(query, false) +
                              rayQueryGetIntersectionGeometryIndexEXT(query, false)];
    vec3 o = rayQueryGetIntersectionObjectRayOriginEXT(query, false);
    vec3 d = rayQueryGetIntersectionObjectRayDirectionEXT(query, false);
    float t = -1.0;
    normal = vec3(0.0);
    bool triangle = rayQueryGetIntersectionTypeEXT(query, false) == gl_RayQueryCandidateIntersectionTriangleEXT;
    if (triangle) {
        float candidate = rayQueryGetIntersectionTEXT(query, false);
        if (candidate <= t_max) {
            t = candidate;
        }
    } else {
        uint primitive = rayQueryGetIntersectionInstanceCustomIndexEXT(query, false) +
                         rayQueryGetIntersectionPrimitiveIndexEXT(query, false);
        // The shape sees the object-space ray its intersection stage would (transform.glsl);
        // the cutout's pattern below, the driver's.
        Primitive p = primitives[primitive];
        StageRay ray = stage_ray(o, d, rayQueryGetWorldRayOriginEXT(query), rayQueryGetWorldRayDirectionEXT(query),
                                 rayQueryGetIntersectionObjectToWorldEXT(query, false)[3],
                                 mat3(rayQueryGetIntersectionWorldToObjectEXT(query, false)), shape_bound(data.shape, p));
        vec2 range = stage_range(ray, t_min, t_max);
        float hit_t;
        vec3 n;
        if (shape_intersect(data.shape, ray.origin, ray.direction, p, range.x, range.y, hit_t, n)) {
            t = stage_world_t(ray, hit_t, t_max);
            normal = n;
        }
    }
    // Holes only where the scene has cutouts: other instances are forced opaque.
    if (HAS_FEATURE_ALPHA_MASKS && t >= 0.0) {
        Material material = materials[data.material];
        float alpha = cutout_alpha(material, o + d * t);
        if (triangle && material.cutout_pattern == CUTOUT_TEXTURE) {
            uint first = data.index_base + 3u * rayQueryGetIntersectionPrimitiveIndexEXT(query, false);
            Vertex v0 = vertices[data.vertex_base + indices[first]];
            Vertex v1 = vertices[data.vertex_base + indices[first + 1u]];
            Vertex v2 = vertices[data.vertex_base + indices[first + 2u]];
            alpha *= surface_alpha(material, v0, v1, v2, rayQueryGetIntersectionBarycentricsEXT(query, false));
        }
        if (alpha < material.cutout_threshold) {
            t = -1.0;
        }
    }
    return t;
}

// Traced inline with a ray query: every candidate the traversal cannot decide alone is decided
// by candidate_hit. Any hit ends it.
bool visible(vec3 origin, vec3 direction, float distance) {
    rayQueryEXT query;
    rayQueryInitializeEXT(query, tlas, gl_RayFlagsTerminateOnFirstHitEXT, MASK_OCCLUDER, origin, 0.0, direction,
                          distance);
    bool occluded = false;
    while (rayQueryProceedEXT(query)) {
        vec3 normal;
        if (candidate_hit(query, 0.0, distance, normal) >= 0.0) {
            occluded = true;
            rayQueryTerminateEXT(query);
        }
    }
    return !occluded && rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionNoneEXT;
}

#ifdef RENDER_COMPUTE
#include "procedural_hit.glsl"
#include "triangle_hit.glsl"

// Twin of twinray_stages::query::trace_query: the ray over [t_min, t_max] traced inline, each
// candidate decided by candidate_hit and committed if no farther than the closest so far; the
// committed hit described into `payload` as the closest-hit stage of its hit group would, or
// `background` as the miss stage would. cone: the spread angle of the ray's cone (0: texture
// level 0).
void trace_query(vec3 origin, float t_min, vec3 direction, float t_max, vec4 background, float cone) {
    rayQueryEXT query;
    rayQueryInitializeEXT(query, tlas, PRIMARY_RAY_FLAGS, 0xff, origin, t_min, direction, t_max);
    vec3 normal = vec3(0.0);
    while (rayQueryProceedEXT(query)) {
        bool none = rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionNoneEXT;
        float closest = none ? t_max : rayQueryGetIntersectionTEXT(query, true);
        vec3 n;
        float t = candidate_hit(query, t_min, closest, n);
        if (t >= 0.0) {
            if (rayQueryGetIntersectionTypeEXT(query, false) == gl_RayQueryCandidateIntersectionTriangleEXT) {
                rayQueryConfirmIntersectionEXT(query);
            } else {
                // The committed procedural hit's normal: each commit is no farther than the last.
                normal = n;
                rayQueryGenerateIntersectionEXT(query, t);
            }
        }
    }
    uint committed = rayQueryGetIntersectionTypeEXT(query, true);
    if (committed == gl_RayQueryCommittedIntersectionNoneEXT) {
        payload.color = background;
        payload.ids = uvec4(NO_HIT);
        return;
    }
    uint object = rayQueryGetIntersectionInstanceIdEXT(query, true) + rayQueryGetIntersectionGeometryIndexEXT(query, true);
    uint primitive_id = rayQueryGetIntersectionPrimitiveIndexEXT(query, true);
    vec3 object_origin = rayQueryGetIntersectionObjectRayOriginEXT(query, true);
    vec3 object_direction = rayQueryGetIntersectionObjectRayDirectionEXT(query, true);
    float t = rayQueryGetIntersectionTEXT(query, true);
    mat3 world_to_object = mat3(rayQueryGetIntersectionWorldToObjectEXT(query, true));
    if (committed == gl_RayQueryCommittedIntersectionTriangleEXT) {
        uint kind = rayQueryGetIntersectionFrontFaceEXT(query, true) ? HIT_KIND_TRIANGLE_FRONT : HIT_KIND_TRIANGLE_BACK;
        triangle_hit(object, primitive_id, kind, origin, direction, object_origin, object_direction, t,
                     world_to_object, rayQueryGetIntersectionObjectToWorldEXT(query, true),
                     rayQueryGetIntersectionBarycentricsEXT(query, true), cone);
    } else {
        uint primitive = rayQueryGetIntersectionInstanceCustomIndexEXT(query, true) + primitive_id;
        uint kind = objects[object].shape & ~SHAPE_NAIVE;
        procedural_hit(object, primitive, primitive_id, kind, origin, direction, object_origin, object_direction,
                       t, world_to_object, normal, cone);
    }
}
#endif
#endif
