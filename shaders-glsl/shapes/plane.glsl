// Twin of twinray_shared::shapes::plane: rectangles and disks in the plane y = 0 of object space.
#ifndef TWINRAY_PLANE_GLSL
#define TWINRAY_PLANE_GLSL
#include "twinray_layout.glsl"
#include "shape_uv.glsl"

// A ray parallel to the plane never meets it: no division by zero.
bool plane_intersect(vec3 origin, vec3 direction, Primitive primitive, float t_min, float t_max, out float t,
                     out vec3 n) {
    t = 0.0;
    n = vec3(0.0, 1.0, 0.0);
    if (direction.y == 0.0) {
        return false;
    }
    t = -origin.y / direction.y;
    if (!(t >= t_min && t <= t_max)) {
        return false;
    }
    vec3 p = origin + direction * t;
    vec4 a = primitive.a;
    if (primitive.b.x == PLANE_DISK) {
        return p.x * p.x + p.z * p.z <= a.x * a.x;
    }
    return abs(p.x) <= a.x && abs(p.z) <= a.y;
}
void plane_uv(Primitive primitive, vec3 p, vec3 n, out vec2 uv, out vec3 du, out vec3 dv) {
    vec4 a = primitive.a;
    flat_uv(p, primitive.b.x == PLANE_DISK ? vec2(a.x) : a.xy, 1.0, uv, du, dv);
}

// Twin of twinray_shared::shapes::plane::bound: the sphere the primitive lies in (xyz: centre,
// w: radius, object space).
vec4 plane_bound(Primitive p) {
    return vec4(0.0, 0.0, 0.0, length(p.a.xy));
}
#endif
