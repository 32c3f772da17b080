#version 460
// Twin of twinray_stages::shadow_miss: a shadow ray that reaches its light.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"

layout(location = 1) rayPayloadInEXT ShadowPayload shadow_payload;

void main() {
    shadow_payload.occluded = 0u;
}
