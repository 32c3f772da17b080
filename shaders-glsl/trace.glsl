// Twin of twinray_stages::trace: primary rays, and shading with shadow rays to every light.
// Included by raygen.rgen after it declares tlas, frame, lights, payload and shadow_payload.
#ifndef TWINRAY_TRACE_GLSL
#define TWINRAY_TRACE_GLSL
#include "lighting.glsl"
#include "offset.glsl"
#include "random.glsl"

#ifdef SHADOW_QUERY
#include "query.glsl"
#endif

#ifdef RENDER_COMPUTE
// Twin of twinray_stages::query::primary_query.
void trace_primary(vec3 origin, vec3 direction) {
    trace_query(origin, frame.reach.z, direction, frame.reach.x, frame.background, frame.cone.x);
}
#else
void trace_primary(vec3 origin, vec3 direction) {
    traceRayEXT(tlas, PRIMARY_RAY_FLAGS, 0xff, 0, 0, MISS_PRIMARY, origin, frame.reach.z, direction, frame.reach.x, 0);
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

#ifndef TRACE_ONLY
// 1 where a closest hit may shade the surface itself (a set with a stage from disk), 0 for
// twinray's own sets: twin of the Rust renderer's `shaded_hits`.
layout(constant_id = SPEC_SHADED_HITS) const uint SHADED_HITS = 0u;

// shadows: whether any light casts shadows (a specialisation constant); stratified: rect lights'
// shadow samples one per cell of an N x N grid, else independent. Adds the shadow rays it
// traces to shadow_rays.
vec3 shade(bool shadows, bool stratified, uint pixel, uint sample_index, inout uint shadow_rays) {
    // A miss, an emitter, or a surface its closest hit shaded (only where the set's may): the
    // colour is the radiance.
    bool shaded = SHADED_HITS != 0u && payload.ids.z == MATERIAL_SHADED;
    if (payload.ids.w == NO_HIT || shaded || (HAS_FEATURE_EMISSION && payload.ids.z == MATERIAL_EMISSIVE)) {
        return payload.color.xyz;
    }
    vec3 point = payload.position.xyz;
    vec3 normal = payload.shading_normal.xyz;
    vec3 origin = offset_hit(point, payload.geometric_normal.xyz, payload.position.w);
    vec3 light_sum = vec3(0.0);
    for (uint l = 0u; l < frame.light_count; l++) {
        Light light = lights[l];
        // Without area lights every light takes one sample at a fixed place.
        uint n = HAS_FEATURE_AREA_LIGHTS ? light_samples_per_side(light) : 1u;
        for (uint j = 0u; j < n; j++) {
            for (uint i = 0u; i < n; i++) {
                uint dimension = 2u + 2u * (l * 64u + j * n + i);
                // Only area lights are sampled at random positions.
                float r1 = 0.0, r2 = 0.0;
                if (HAS_FEATURE_AREA_LIGHTS && light.kind == LIGHT_RECT) {
                    r1 = random(frame.seed, pixel, sample_index, dimension);
                    r2 = random(frame.seed, pixel, sample_index, dimension + 1u);
                }
                // Independent samples: cell (0, 0) stretched over the whole light.
                float nf = float(n);
                LightSample s = stratified ? light_sample(light, point, i, j, r1, r2, frame.reach.y)
                                           : light_sample(light, point, 0u, 0u, r1 * nf, r2 * nf, frame.reach.y);
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
    // Plus the radiance the surface emits, in the spare w components (HitPayload::emission).
    vec3 lit = payload.color.xyz * light_sum;
    if (!HAS_FEATURE_EMISSION) {
        return lit;
    }
    return lit + vec3(payload.shading_normal.w, payload.geometric_normal.w, payload.color.w);
}
#endif // TRACE_ONLY
#endif
