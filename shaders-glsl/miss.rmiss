#version 460
// Twin of twinray_stages::miss: primary rays that hit nothing see the background.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_FRAME) uniform Frame { FrameUniform frame; };

layout(location = 0) rayPayloadInEXT HitPayload payload;

void main() {
    payload.color = frame.background;
    payload.ids = uvec4(NO_HIT);
}
