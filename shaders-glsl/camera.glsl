// Twin of twinray_shared::camera: the primary ray through the centre of a pixel.
#ifndef TWINRAY_CAMERA_GLSL
#define TWINRAY_CAMERA_GLSL
#include "twinray_layout.glsl"

void primary_ray(CameraUniform camera, uvec2 pixel, uvec2 size, out vec3 origin, out vec3 direction) {
    vec2 uv = (vec2(pixel) + vec2(0.5)) / vec2(size);
    vec2 ndc = uv * 2.0 - vec2(1.0);
    origin = (camera.view_inverse * vec4(0.0, 0.0, 0.0, 1.0)).xyz;
    vec4 target = camera.proj_inverse * vec4(ndc.x, ndc.y, 1.0, 1.0);
    direction = (camera.view_inverse * vec4(normalize(target.xyz), 0.0)).xyz;
}
#endif
