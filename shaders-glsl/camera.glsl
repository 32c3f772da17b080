// Twin of twinray_shared::camera: primary rays through a point of a pixel.
#ifndef TWINRAY_CAMERA_GLSL
#define TWINRAY_CAMERA_GLSL
#include "twinray_layout.glsl"

// offset in [0, 1)^2, (0.5, 0.5) being the pixel centre. An orthographic camera (cone.y 1)
// sends every ray down its -z from the point of its plane proj_inverse maps the pixel to.
void primary_ray(FrameUniform frame, uvec2 pixel, uvec2 size, vec2 offset, out vec3 origin, out vec3 direction) {
    vec2 uv = (vec2(pixel) + offset) / vec2(size);
    vec2 ndc = uv * 2.0 - vec2(1.0);
    if (frame.cone.y != 0.0) {
        vec4 on_plane = frame.proj_inverse * vec4(ndc.x, ndc.y, 0.0, 1.0);
        origin = (frame.view_inverse * vec4(on_plane.x, on_plane.y, 0.0, 1.0)).xyz;
        direction = (frame.view_inverse * vec4(0.0, 0.0, -1.0, 0.0)).xyz;
        return;
    }
    origin = (frame.view_inverse * vec4(0.0, 0.0, 0.0, 1.0)).xyz;
    vec4 target = frame.proj_inverse * vec4(ndc.x, ndc.y, 1.0, 1.0);
    direction = (frame.view_inverse * vec4(normalize(target.xyz), 0.0)).xyz;
}

// Sample (sx, sy) of m x m stratified, jittered samples: the centre when m is 1.
vec2 sample_offset(uint sx, uint sy, uint m, float r1, float r2) {
    if (m == 1u) {
        return vec2(0.5);
    }
    return vec2((float(sx) + r1) / float(m), (float(sy) + r2) / float(m));
}
#endif
