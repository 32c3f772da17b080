#version 460
// Twin of twinray_shaders::miss: grey background, no primitive.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"

layout(location = 0) rayPayloadInEXT RayPayload payload;

void main() {
    payload.color = vec4(MISS_GREY, MISS_GREY, MISS_GREY, 1.0);
    payload.primitive = NO_HIT;
}
