// Twin of twinray_shared::cone: capped cone about y, apex at y = a.y, base of radius a.x at
// y = -a.y; roots c / q and q / a with the stable q; only the nappe between apex and base.
#ifndef TWINRAY_CONE_GLSL
#define TWINRAY_CONE_GLSL
#include "twinray_layout.glsl"
#include "surface.glsl"

void cone_side(inout bool found, inout float best_t, inout vec3 best_n, vec3 o, vec3 d, vec3 apex, float height,
               float cos2, bool ok, float t, bool other_ok, float other, bool on_surface, float t_min, float t_max) {
    if (ok && !is_self_root(on_surface, t, other_ok, other)) {
        vec3 cp = o + d * t - apex;
        float along = -cp.y;
        if (along >= 0.0 && along <= height) {
            closer(found, best_t, best_n, t, cp * cos2 - vec3(0.0, cp.y, 0.0), t_min, t_max);
        }
    }
}

bool cone_intersect(vec3 origin, vec3 d, Primitive primitive, float t_min, float t_max, out float t, out vec3 n) {
    float r = primitive.a.x;
    float half_height = primitive.a.y;
    float height = 2.0 * half_height;
    float cos2 = height * height / (height * height + r * r);
    vec3 apex = vec3(0.0, half_height, 0.0);
    vec3 co = origin - apex;
    float dv = -d.y;
    float cov = -co.y;
    float a = dv * dv - cos2 * dot(d, d);
    float half_b = dv * cov - dot(d, co) * cos2;
    float c = cov * cov - dot(co, co) * cos2;
    float discriminant = half_b * half_b - a * c;
    bool found = false;
    t = 0.0;
    n = vec3(0.0);
    if (discriminant >= 0.0) {
        bool on_surface = abs(c) <= SPHERE_ON_SURFACE * dot(co, co);
        bool ok0, ok1;
        float r0, r1;
        stable_roots(a, half_b, c, discriminant, ok0, r0, ok1, r1);
        cone_side(found, t, n, origin, d, apex, height, cos2, ok0, r0, ok1, r1, on_surface, t_min, t_max);
        cone_side(found, t, n, origin, d, apex, height, cos2, ok1, r1, ok0, r0, on_surface, t_min, t_max);
    }
    if (d.y != 0.0) {
        float tb = (-half_height - origin.y) / d.y;
        vec3 p = origin + d * tb;
        if (p.x * p.x + p.z * p.z <= r * r) {
            closer(found, t, n, tb, vec3(0.0, -1.0, 0.0), t_min, t_max);
        }
    }
    return found;
}
#endif
