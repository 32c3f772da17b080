#version 460
// Twin of twinray_shaders::probe_witness (with DRIVER_RAY defined, of probe_witness_driver): the
// probe's witness, a closest-hit stage twinray puts in place of a hit group's own (same
// intersection and any-hit stages) for one extra pass of the probe. It packs the object-space
// ray the intersection stages use (transform.glsl's stage_ray), or with DRIVER_RAY
// the one the driver hands a hit group, and the t the stages reported, into the payload fields
// the probe ray generation stage copies out, as twinray_shared::layout::ProbeResult documents.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
#include "transform.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;

void main() {
    vec3 o, d;
#ifdef DRIVER_RAY
    o = gl_ObjectRayOriginEXT;
    d = gl_ObjectRayDirectionEXT;
#else
    stage_ray(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_WorldRayOriginEXT, gl_WorldRayDirectionEXT,
              gl_ObjectToWorldEXT[3], mat3(gl_WorldToObjectEXT), o, d);
#endif
    payload.position.w = gl_RayTmaxEXT;
    payload.shading_normal.xyz = o;
    payload.ids = uvec4(floatBitsToUint(d), gl_HitKindEXT);
}
