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
// Twin of offset::offset_hit: p, hit at ray parameter t along a unit direction, moved off the
// surface by offset_ray and by at least 256 ULPs of the ray's reach (max |p_i| + t) along n;
// near the origin by the reach's step alone (no fixed step in scene units).
vec3 offset_hit(vec3 p, vec3 n, float t) {
    float step_reach = (max(max(abs(p.x), abs(p.y)), abs(p.z)) + abs(t)) * OFFSET_REACH_SCALE;
    vec3 moved = offset_ray(p, n);
    vec3 ulps = mix(moved, p, lessThan(abs(p), vec3(OFFSET_ORIGIN)));
    vec3 reach = p + step_reach * n;
    return mix(min(ulps, reach), max(ulps, reach), greaterThanEqual(n, vec3(0.0)));
}
#endif
