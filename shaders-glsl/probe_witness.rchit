#version 460
// Twin of twinray_stages::probe_witness (with DRIVER_RAY defined, of probe_witness_driver): the
// probe's witness, a closest-hit stage twinray puts in place of a hit group's own (same
// intersection and any-hit stages) for one extra pass of the probe. It packs the object-space
// ray the intersection stages use (transform.glsl's stage_ray, brought near the primitive as
// they bring it), or with DRIVER_RAY the one the driver hands a hit group, how far along the
// world ray it starts, and the t the stages reported, into the payload fields the probe ray
// generation stage copies out, as twinray_shared::layout::ProbeResult documents.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
#include "transform.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;
#ifndef DRIVER_RAY
#include "shape_dispatch.glsl"
layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_VERTICES, std430) readonly buffer Vertices { Vertex vertices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_INDICES, std430) readonly buffer Indices { uint indices[]; };
#endif

void main() {
    StageRay ray;
    float t = gl_RayTmaxEXT;
#ifdef DRIVER_RAY
    ray = StageRay(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, 0.0);
#else
    if (gl_HitKindEXT == HIT_KIND_TRIANGLE_FRONT || gl_HitKindEXT == HIT_KIND_TRIANGLE_BACK) {
        // A triangle's hit the stages measure again where the scene has far instances
        // (transform.glsl's triangle_t): the ray brought near the triangle and the t measured on
        // it, or, where the ray was not moved, the driver's ray.
        ray = StageRay(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, 0.0);
        uint mesh = gl_InstanceID + gl_GeometryIndexEXT;
        if (HAS_FEATURE_FAR_INSTANCES && mesh < uint(objects.length())) {
            ObjectData data = objects[mesh];
            uint first = data.index_base + 3u * uint(gl_PrimitiveID);
            vec3 p0 = vertices[data.vertex_base + indices[first]].position.xyz;
            vec3 p1 = vertices[data.vertex_base + indices[first + 1u]].position.xyz;
            vec3 p2 = vertices[data.vertex_base + indices[first + 2u]].position.xyz;
            StageRay near = triangle_ray(gl_WorldRayOriginEXT, gl_WorldRayDirectionEXT, gl_ObjectToWorldEXT[3],
                                         mat3(gl_WorldToObjectEXT), p0, p1, p2);
            if (near.shift > 0.0) {
                ray = near;
            }
            t = plane_t(near, p0, p1, p2, t);
        }
        payload.position.w = t;
        payload.shading_normal.xyz = ray.origin;
        payload.ids = uvec4(floatBitsToUint(ray.direction), floatBitsToUint(ray.shift));
        return;
    }
    // The bound the intersection stage used: its object's routine (zero for the naive ones).
    vec4 bound = vec4(0.0);
    uint primitive = gl_InstanceCustomIndexEXT + gl_PrimitiveID;
    if (uint(gl_InstanceID) < uint(objects.length()) && primitive < uint(primitives.length())) {
        bound = shape_bound(objects[gl_InstanceID].shape, primitives[primitive]);
    }
    ray = stage_ray(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_WorldRayOriginEXT, gl_WorldRayDirectionEXT,
                    gl_ObjectToWorldEXT[3], mat3(gl_WorldToObjectEXT), bound);
#endif
    payload.position.w = t;
    payload.shading_normal.xyz = ray.origin;
    payload.ids = uvec4(floatBitsToUint(ray.direction), floatBitsToUint(ray.shift));
}
