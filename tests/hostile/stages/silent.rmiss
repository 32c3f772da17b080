#version 460
// A miss stage that writes no payload: the rays that miss are counted and the miss stage named.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
layout(location = 0) rayPayloadInEXT HitPayload payload;
void main() {
}
