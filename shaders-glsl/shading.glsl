// Twin of twinray_shared::shading: Lambert under one directional light.
#ifndef TWINRAY_SHADING_GLSL
#define TWINRAY_SHADING_GLSL
#include "twinray_layout.glsl"

vec3 lambert(vec3 albedo, vec3 normal) {
    return albedo * max(dot(normal, normalize(LIGHT_DIRECTION)), 0.0);
}
#endif
