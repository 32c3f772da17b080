#version 460
// Twin of twinray_shaders::probe_witness: the probe's witness, a closest-hit stage twinray puts
// in place of a hit group's own (same intersection and any-hit stages) for one extra pass of
// the probe. It packs the object-space ray the GPU handed the hit group and the t its stages
// reported into the payload fields the probe ray generation stage copies out, as
// twinray_shared::layout::ProbeResult documents.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;

void main() {
    payload.position.w = gl_RayTmaxEXT;
    payload.shading_normal.xyz = gl_ObjectRayOriginEXT;
    payload.ids = uvec4(floatBitsToUint(gl_ObjectRayDirectionEXT), gl_HitKindEXT);
}
