// Twin of twinray_shared::offset: secondary-ray origins (Ray Tracing Gems ch. 6).
#ifndef TWINRAY_OFFSET_GLSL
#define TWINRAY_OFFSET_GLSL
#include "twinray_layout.glsl"

float offset_component(float p, float n) {
    if (abs(p) < OFFSET_ORIGIN) {
        return p + OFFSET_FLOAT_SCALE * n;
    }
    int of = int(OFFSET_INT_SCALE * n);
    int step_ulps = p < 0.0 ? -of : of;
    return intBitsToFloat(floatBitsToInt(p) + step_ulps);
}

// p moved off the surface along n (unit, towards the side the new ray leaves from).
vec3 offset_ray(vec3 p, vec3 n) {
    return vec3(offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z));
}
#endif
