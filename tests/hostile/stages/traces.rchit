#version 460
// A closest-hit stage that traces a ray of its own: beyond the pipeline's recursion depth of
// 1, which the driver may take as anything. twinray refuses the module (exit code 2).
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
layout(set = DESCRIPTOR_SET, binding = BINDING_TLAS) uniform accelerationStructureEXT tlas;
layout(location = 0) rayPayloadInEXT HitPayload payload;
layout(location = 1) rayPayloadEXT ShadowPayload shadow_payload;
hitAttributeEXT vec3 normal;
void main() {
    traceRayEXT(tlas, gl_RayFlagsNoneEXT, 0xff, 0, 0, MISS_SHADOW, gl_WorldRayOriginEXT, 0.0, normal, 10.0, 1);
    payload.ids = uvec4(NO_HIT);
}
