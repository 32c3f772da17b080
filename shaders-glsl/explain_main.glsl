// The body of twinray explain's stages (explain.rgen, explain_query.comp), twin of the Rust
// entry points twinray_stages::explain and explain_query: one ray per launch index, traced as
// the renderer traces rays of its kind (trace.glsl's trace_primary or visible, which the
// renderers call); writes the primary ray's payload, or whether the shadow ray was occluded.
// With SHADOW_QUERY and RENDER_COMPUTE defined, both are traced inline by ray queries.
#include "twinray_layout.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_TLAS) uniform accelerationStructureEXT tlas;
layout(set = DESCRIPTOR_SET, binding = BINDING_FRAME) uniform Frame { FrameUniform frame; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PROBE_RAYS, std430) readonly buffer Rays { ExplainRay rays[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PROBE_RESULTS, std430) buffer Results { ExplainResult results[]; };

#ifdef RENDER_COMPUTE
layout(local_size_x = PROBE_GROUP_SIZE) in;
HitPayload payload;
layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials { Material materials[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_VERTICES, std430) readonly buffer Vertices { Vertex vertices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_INDICES, std430) readonly buffer Indices { uint indices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_TEXTURES) uniform sampler2D textures[];
#define EXPLAIN_INDEX gl_GlobalInvocationID.x
#else
layout(location = 0) rayPayloadEXT HitPayload payload;
layout(location = 1) rayPayloadEXT ShadowPayload shadow_payload;
#define EXPLAIN_INDEX gl_LaunchIDEXT.x
#endif

// These stages trace but do not shade: trace.glsl's shading (which reads the lights) is left out.
#define TRACE_ONLY
#include "payload.glsl"
#include "trace.glsl"

void main() {
    uint i = EXPLAIN_INDEX;
    // Whole workgroups cover the rays; checked before the traces, as the Rust twins do.
    if (i >= uint(rays.length()) || i >= uint(results.length())) {
        return;
    }
    ExplainRay ray = rays[i];
    HitPayload none = HitPayload(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), uvec4(0u));
    if (ray.kind.x == EXPLAIN_SHADOW) {
        bool lit = visible(ray.origin.xyz, ray.direction.xyz, ray.direction.w);
        results[i] = ExplainResult(none, uvec4(lit ? 0u : 1u, 0u, 0u, 0u));
    } else {
#ifdef RENDER_COMPUTE
        payload = none;
#else
        poison_payload();
#endif
        trace_primary(ray.origin.xyz, ray.direction.xyz);
        results[i] = ExplainResult(payload, uvec4(0u));
    }
}
