// Twin of twinray_shared::shapes::cone: capped cone about y, apex at y = a.y, base of radius a.x at
// y = -a.y; roots c / q and q / a with the stable q; only the nappe between apex and base.
// Discriminant in the Lagrange-identity form cos^2 (sin^2 |w|^2 - w_y^2), w = co x d, all
// coefficients multiplied by h^2 + r^2; side roots get one Newton step at the hit point.
#ifndef TWINRAY_CONE_GLSL
#define TWINRAY_CONE_GLSL
#include "twinray_layout.glsl"
#include "shape_uv.glsl"
#include "surface.glsl"
#include "exact.glsl"

// One Newton step on the implicit function at the hit point, at most CONE_POLISH_LIMIT * t
// (see twinray_shared::shapes::cone::polish).
float cone_polish(vec3 o, vec3 apex, vec3 d, float h2, float r2, float t) {
    vec3 cp = point_at(o, d, t) - apex;
    float f = r2 * cp.y * cp.y - h2 * (cp.x * cp.x + cp.z * cp.z);
    float slope = 2.0 * (r2 * cp.y * d.y - h2 * (cp.x * d.x + cp.z * d.z));
    return abs(f) <= CONE_POLISH_LIMIT * abs(t) * abs(slope) ? t - f / slope : t;
}

void cone_side(inout bool found, inout float best_t, inout vec3 best_n, vec3 o, vec3 d, vec3 apex, float height,
               float h2, float r2, bool ok, float t, bool other_ok, float other, float reach2, float t_min,
               float t_max) {
    if (ok && !is_self_root(reach2, t, other_ok, other)) {
        t = cone_polish(o, apex, d, h2, r2, t);
        vec3 cp = point_at(o, d, t) - apex;
        float along = -cp.y;
        if (along >= 0.0 && along <= height) {
            closer(found, best_t, best_n, t, vec3(h2 * cp.x, -r2 * cp.y, h2 * cp.z), t_min, t_max);
        }
    }
}

// Coefficients scaled by h^2 + r^2 so that no rounded cos^2 enters (see the Rust twin).
bool cone_intersect(vec3 origin, vec3 d, Primitive primitive, float t_min, float t_max, out float t, out vec3 n) {
    float r = primitive.a.x;
    float half_height = primitive.a.y;
    float height = 2.0 * half_height;
    float h2 = height * height;
    float r2 = r * r;
    vec3 apex = vec3(0.0, half_height, 0.0);
    vec3 co = origin - apex;
    float dv = -d.y;
    float cov = -co.y;
    float a = r2 * dv * dv - h2 * (d.x * d.x + d.z * d.z);
    float half_b = r2 * dv * cov - h2 * (d.x * co.x + d.z * co.z);
    float c = r2 * cov * cov - h2 * (co.x * co.x + co.z * co.z);
    vec3 w = cross(co, d);
    float discriminant = h2 * (r2 * (w.x * w.x + w.z * w.z) - h2 * w.y * w.y);
    bool found = false;
    t = 0.0;
    n = vec3(0.0);
    if (discriminant >= 0.0) {
        bool on_surface = abs(c) <= SPHERE_ON_SURFACE * (r2 + h2) * dot(co, co);
        float reach2 = self_reach2(on_surface, dot(co, co), dot(d, d));
        bool ok0, ok1;
        float r0, r1;
        stable_roots(a, half_b, c, discriminant, ok0, r0, ok1, r1);
        cone_side(found, t, n, origin, d, apex, height, h2, r2, ok0, r0, ok1, r1, reach2, t_min, t_max);
        cone_side(found, t, n, origin, d, apex, height, h2, r2, ok1, r1, ok0, r0, reach2, t_min, t_max);
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
void cone_uv(Primitive primitive, vec3 p, vec3 n, out vec2 uv, out vec3 du, out vec3 dv) {
    revolved_uv(p, n, primitive.a.x, primitive.a.y, uv, du, dv);
}

// Twin of twinray_shared::shapes::cone::bound: the sphere the primitive lies in (xyz: centre,
// w: radius, object space).
vec4 cone_bound(Primitive p) {
    return vec4(0.0, 0.0, 0.0, length(p.a.xy));
}
#endif
