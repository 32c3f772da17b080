// Twin of twinray_shaders::trace: primary rays, and shading with shadow rays to every light.
// Included by raygen.rgen after it declares tlas, frame, lights, payload and shadow_payload.
#ifndef TWINRAY_TRACE_GLSL
#define TWINRAY_TRACE_GLSL
#include "lighting.glsl"
#include "offset.glsl"
#include "random.glsl"

#ifdef SHADOW_QUERY
#include "shading.glsl"
#include "shape_dispatch.glsl"

// The ray parameter of the query's candidate if it is a hit, decided as the pipeline's stages
// would, else -1: a triangle at its t (up to t_max), a procedural primitive by its shape's
// routine between t_min and t_max, and for cutouts (the only instances not forced opaque) not
// in a hole. normal: a procedural hit's object-space normal.
float candidate_hit(rayQueryEXT query, float t_min, float t_max, out vec3 normal) {
    ObjectData data = objects[rayQueryGetIntersectionInstanceIdEXT(query, false)];
    vec3 o = rayQueryGetIntersectionObjectRayOriginEXT(query, false);
    vec3 d = rayQueryGetIntersectionObjectRayDirectionEXT(query, false);
    float t = -1.0;
    normal = vec3(0.0);
    if (rayQueryGetIntersectionTypeEXT(query, false) == gl_RayQueryCandidateIntersectionTriangleEXT) {
        float candidate = rayQueryGetIntersectionTEXT(query, false);
        if (candidate <= t_max) {
            t = candidate;
        }
    } else {
        uint primitive = rayQueryGetIntersectionInstanceCustomIndexEXT(query, false) +
                         rayQueryGetIntersectionPrimitiveIndexEXT(query, false);
        float hit_t;
        vec3 n;
        if (shape_intersect(data.shape, o, d, primitives[primitive], t_min, t_max, hit_t, n)) {
            t = hit_t;
            normal = n;
        }
    }
    if (t >= 0.0 && !cutout_solid(materials[data.material], o + d * t)) {
        t = -1.0;
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
#endif

#ifdef RENDER_COMPUTE
#include "procedural_hit.glsl"
#include "triangle_hit.glsl"

// Twin of twinray_shaders::trace::primary_query: the primary ray traced inline, each candidate
// decided by candidate_hit and committed if no farther than the closest so far; the committed
// hit described into `payload` as the closest-hit stage of its hit group would, or the
// background as the miss stage would.
void trace_primary(vec3 origin, vec3 direction) {
    rayQueryEXT query;
    rayQueryInitializeEXT(query, tlas, gl_RayFlagsNoneEXT, 0xff, origin, T_MIN, direction, T_MAX);
    vec3 normal = vec3(0.0);
    while (rayQueryProceedEXT(query)) {
        bool none = rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionNoneEXT;
        float closest = none ? T_MAX : rayQueryGetIntersectionTEXT(query, true);
        vec3 n;
        float t = candidate_hit(query, T_MIN, closest, n);
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
        payload.color = frame.background;
        payload.ids = uvec4(NO_HIT);
        return;
    }
    uint object = rayQueryGetIntersectionInstanceIdEXT(query, true);
    uint primitive_id = rayQueryGetIntersectionPrimitiveIndexEXT(query, true);
    vec3 object_origin = rayQueryGetIntersectionObjectRayOriginEXT(query, true);
    vec3 object_direction = rayQueryGetIntersectionObjectRayDirectionEXT(query, true);
    float t = rayQueryGetIntersectionTEXT(query, true);
    mat3 world_to_object = mat3(rayQueryGetIntersectionWorldToObjectEXT(query, true));
    if (committed == gl_RayQueryCommittedIntersectionTriangleEXT) {
        uint kind = rayQueryGetIntersectionFrontFaceEXT(query, true) ? HIT_KIND_TRIANGLE_FRONT : HIT_KIND_TRIANGLE_BACK;
        triangle_hit(object, primitive_id, kind, origin, direction, object_origin, object_direction, t,
                     world_to_object, rayQueryGetIntersectionBarycentricsEXT(query, true));
    } else {
        uint primitive = rayQueryGetIntersectionInstanceCustomIndexEXT(query, true) + primitive_id;
        uint kind = objects[object].shape & ~SHAPE_NAIVE;
        procedural_hit(object, primitive, primitive_id, kind, origin, direction, object_origin, object_direction,
                       t, world_to_object, normal);
    }
}
#else
void trace_primary(vec3 origin, vec3 direction) {
    traceRayEXT(tlas, gl_RayFlagsNoneEXT, 0xff, 0, 0, MISS_PRIMARY, origin, T_MIN, direction, T_MAX, 0);
}
#endif

#ifndef SHADOW_QUERY
bool visible(vec3 origin, vec3 direction, float distance) {
    shadow_payload.occluded = 1u;
    uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT;
    traceRayEXT(tlas, flags, MASK_OCCLUDER, 0, 0, MISS_SHADOW, origin, 0.0, direction, distance, 1);
    return shadow_payload.occluded == 0u;
}
#endif

// shadows: whether any light casts shadows (a specialisation constant); stratified: rect lights'
// shadow samples one per cell of an N x N grid, else independent. Adds the shadow rays it
// traces to shadow_rays.
vec3 shade(bool shadows, bool stratified, uint pixel, uint sample_index, inout uint shadow_rays) {
    if (payload.ids.w == NO_HIT || payload.ids.z == MATERIAL_EMISSIVE) {
        return payload.color.xyz;
    }
    vec3 point = payload.position.xyz;
    vec3 normal = payload.shading_normal.xyz;
    vec3 origin = offset_ray(point, payload.geometric_normal.xyz);
    vec3 light_sum = vec3(0.0);
    for (uint l = 0u; l < frame.light_count; l++) {
        Light light = lights[l];
        uint n = light_samples_per_side(light);
        for (uint j = 0u; j < n; j++) {
            for (uint i = 0u; i < n; i++) {
                uint dimension = 2u + 2u * (l * 64u + j * n + i);
                // Only area lights are sampled at random positions.
                float r1 = 0.0, r2 = 0.0;
                if (light.kind == LIGHT_RECT) {
                    r1 = random(frame.seed, pixel, sample_index, dimension);
                    r2 = random(frame.seed, pixel, sample_index, dimension + 1u);
                }
                // Independent samples: cell (0, 0) stretched over the whole light.
                float nf = float(n);
                LightSample s = stratified ? light_sample(light, point, i, j, r1, r2)
                                           : light_sample(light, point, 0u, 0u, r1 * nf, r2 * nf);
                float cosine = dot(normal, s.direction);
                bool casts = shadows && light.shadows != 0u;
                if (cosine > 0.0) {
                    bool lit = true;
                    if (casts) {
                        shadow_rays++;
                        lit = visible(origin, s.direction, s.distance);
                    }
                    if (lit) {
                        light_sum += s.irradiance * cosine;
                    }
                }
            }
        }
    }
    return payload.color.xyz * light_sum;
}
#endif
