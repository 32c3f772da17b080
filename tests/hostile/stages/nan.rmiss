#version 460
// A miss stage that returns NaN as the background: the pixels it colours are counted as
// non-finite (exit code 1), and shown in magenta.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
layout(location = 0) rayPayloadInEXT HitPayload payload;
void main() {
    payload.color = vec4(uintBitsToFloat(0x7fc00000u));
    payload.ids = uvec4(NO_HIT);
}
