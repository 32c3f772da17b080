#version 460
// Twin of twinray_shaders::probe_witness (with DRIVER_RAY defined, of probe_witness_driver): the
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
#endif

void main() {
    StageRay ray;
#ifdef DRIVER_RAY
    ray = StageRay(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, 0.0);
#else
    // The bound the intersection stage used: its object's routine (zero for the naive ones and
    // for triangles, whose custom index names no primitive of theirs).
    vec4 bound = vec4(0.0);
    uint primitive = gl_InstanceCustomIndexEXT + gl_PrimitiveID;
    if (uint(gl_InstanceID) < uint(objects.length()) && primitive < uint(primitives.length())) {
        bound = shape_bound(objects[gl_InstanceID].shape, primitives[primitive]);
    }
    ray = stage_ray(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_WorldRayOriginEXT, gl_WorldRayDirectionEXT,
                    gl_ObjectToWorldEXT[3], mat3(gl_WorldToObjectEXT), bound);
#endif
    payload.position.w = gl_RayTmaxEXT;
    payload.shading_normal.xyz = ray.origin;
    payload.ids = uvec4(floatBitsToUint(ray.direction), floatBitsToUint(ray.shift));
}
