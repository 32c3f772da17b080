#version 460
// Twin of twinray_stages::probe_query: the probe of the compute renderer, one ray per
// invocation, traced inline by the code that traces the renderer's primary rays; writes what it
// described, or NO_HIT.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#define RENDER_COMPUTE
#include "twinray_layout.glsl"

layout(local_size_x = PROBE_GROUP_SIZE) in;

layout(set = DESCRIPTOR_SET, binding = BINDING_TLAS) uniform accelerationStructureEXT tlas;
layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials { Material materials[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_VERTICES, std430) readonly buffer Vertices { Vertex vertices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_INDICES, std430) readonly buffer Indices { uint indices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_TEXTURES) uniform sampler2D textures[];
layout(set = DESCRIPTOR_SET, binding = BINDING_PROBE_RAYS, std430) readonly buffer Rays { ProbeRay rays[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PROBE_RESULTS, std430) buffer Results { ProbeResult results[]; };

HitPayload payload;

#include "query.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    // Whole workgroups cover the rays.
    if (i >= uint(rays.length())) {
        return;
    }
    ProbeRay ray = rays[i];
    payload = HitPayload(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), uvec4(0u));
    // No cone: probes judge geometry, and their rays come from no camera.
    trace_query(ray.origin.xyz, ray.origin.w, ray.direction.xyz, ray.direction.w, vec4(0.0), 0.0);
    results[i] = ProbeResult(vec4(payload.shading_normal.xyz, payload.position.w), payload.ids);
}
