// Twin of twinray_shared::shapes::boxes: NaN-safe slab test (pbrt-v3 after Ize 2013) of the box with
// half extents a.xyz, t_far widened by 1 + 2 gamma_3 only where it is compared with t_near (an exit
// is returned as computed), every min/max an explicit comparison.
#ifndef TWINRAY_BOX_GLSL
#define TWINRAY_BOX_GLSL
#include "twinray_layout.glsl"
#include "shape_uv.glsl"

struct Slabs {
    float near;
    float far;
    vec3 near_axis;
    vec3 far_axis;
    bool empty;
};

Slabs slab(Slabs s, float o, float d, float h, vec3 unit) {
    if (d == 0.0) {
        s.empty = s.empty || o < -h || o > h;
        return s;
    }
    float inv = 1.0 / d;
    float a = (-h - o) * inv;
    float b = (h - o) * inv;
    float t0 = a <= b ? a : b;
    float t1 = a <= b ? b : a;
    float sign_d = d > 0.0 ? 1.0 : -1.0;
    Slabs next = s;
    if (t0 > s.near) {
        next.near = t0;
        next.near_axis = unit * -sign_d;
    }
    if (t1 < s.far) {
        next.far = t1;
        next.far_axis = unit * sign_d;
    }
    next.empty = s.empty || next.near > next.far * (1.0 + 2.0 * BOX_GAMMA_3);
    return next;
}

bool box_intersect(vec3 origin, vec3 direction, Primitive primitive, float t_min, float t_max, out float t, out vec3 n) {
    vec4 h = primitive.a;
    const float MAX = 3.40282347e38;
    Slabs s = Slabs(-MAX, MAX, vec3(0.0), vec3(0.0), false);
    s = slab(s, origin.x, direction.x, h.x, vec3(1.0, 0.0, 0.0));
    s = slab(s, origin.y, direction.y, h.y, vec3(0.0, 1.0, 0.0));
    s = slab(s, origin.z, direction.z, h.z, vec3(0.0, 0.0, 1.0));
    t = 0.0;
    n = vec3(0.0);
    if (s.empty) {
        return false;
    }
    if (s.near >= t_min && s.near <= t_max) {
        t = s.near;
        n = s.near_axis;
        return true;
    }
    if (s.far >= t_min && s.far <= t_max) {
        t = s.far;
        n = s.far_axis;
        return true;
    }
    return false;
}
// The face the intersection's normal n names, seen from outside.
void box_uv(Primitive primitive, vec3 p, vec3 n, out vec2 uv, out vec3 du, out vec3 dv) {
    vec3 h = primitive.a.xyz;
    vec3 m = abs(n);
    vec3 right, up;
    if (m.x >= m.y && m.x >= m.z) {
        right = vec3(0.0, 0.0, n.x < 0.0 ? 1.0 : -1.0);
        up = vec3(0.0, 1.0, 0.0);
    } else if (m.z >= m.y) {
        right = vec3(n.z < 0.0 ? -1.0 : 1.0, 0.0, 0.0);
        up = vec3(0.0, 1.0, 0.0);
    } else {
        right = vec3(1.0, 0.0, 0.0);
        up = vec3(0.0, 0.0, n.y < 0.0 ? 1.0 : -1.0);
    }
    float width = 2.0 * dot(abs(right), h);
    float height = 2.0 * dot(abs(up), h);
    uv = vec2(0.5 + dot(p, right) / width, 0.5 - dot(p, up) / height);
    du = right / width;
    dv = -up / height;
}

// Twin of twinray_shared::shapes::boxes::bound: the sphere the primitive lies in (xyz: centre,
// w: radius, object space).
vec4 box_bound(Primitive p) {
    return vec4(0.0, 0.0, 0.0, length(p.a.xyz));
}
#endif
