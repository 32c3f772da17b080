#version 460
// A procedural closest-hit stage that writes no payload: ray generation poisons the payload
// before each trace, finds it unchanged, and every command names this stage and fails.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec3 normal;
void main() {
}
