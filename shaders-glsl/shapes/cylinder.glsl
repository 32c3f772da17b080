// Twin of twinray_shared::shapes::cylinder: capped cylinder about y (radius a.x, half height a.y), the
// side with the Lagrange-identity discriminant, side and caps tested separately and inclusively.
#ifndef TWINRAY_CYLINDER_GLSL
#define TWINRAY_CYLINDER_GLSL
#include "twinray_layout.glsl"
#include "shape_uv.glsl"
#include "surface.glsl"

void cylinder_side(inout bool found, inout float best_t, inout vec3 best_n, vec3 o, vec3 d, float r, float half_height,
                   bool ok, float t, bool other_ok, float other, float reach2, float t_min, float t_max) {
    if (ok && !is_self_root(reach2, t, other_ok, other)) {
        vec3 p = o + d * t;
        if (abs(p.y) <= half_height) {
            closer(found, best_t, best_n, t, vec3(p.x, 0.0, p.z) / r, t_min, t_max);
        }
    }
}

void cylinder_cap(inout bool found, inout float best_t, inout vec3 best_n, vec3 o, vec3 d, float r, float y,
                  float t_min, float t_max) {
    float t = (y - o.y) / d.y;
    vec3 p = o + d * t;
    if (p.x * p.x + p.z * p.z <= r * r) {
        closer(found, best_t, best_n, t, vec3(0.0, y > 0.0 ? 1.0 : -1.0, 0.0), t_min, t_max);
    }
}

// Side and caps; robust picks the side's discriminant and roots (the caps are the same).
bool cylinder_solve(vec3 o, vec3 d, Primitive primitive, float t_min, float t_max, bool robust, out float t, out vec3 n) {
    float r = primitive.a.x;
    float half_height = primitive.a.y;
    bool found = false;
    t = 0.0;
    n = vec3(0.0);
    float a = d.x * d.x + d.z * d.z;
    if (a > 0.0) {
        float half_b = o.x * d.x + o.z * d.z;
        float c = o.x * o.x + o.z * o.z - r * r;
        float cross_y = o.x * d.z - o.z * d.x;
        float discriminant = robust ? a * r * r - cross_y * cross_y : half_b * half_b - a * c;
        if (discriminant >= 0.0) {
            bool on_surface = robust && abs(c) <= SPHERE_ON_SURFACE * r * r;
            float reach2 = self_reach2(on_surface, r * r, dot(d, d));
            bool ok0 = true, ok1 = true;
            float r0, r1;
            if (robust) {
                stable_roots(a, half_b, c, discriminant, ok0, r0, ok1, r1);
            } else {
                float root = sqrt(discriminant);
                r0 = (-half_b - root) / a;
                r1 = (-half_b + root) / a;
            }
            cylinder_side(found, t, n, o, d, r, half_height, ok0, r0, ok1, r1, reach2, t_min, t_max);
            cylinder_side(found, t, n, o, d, r, half_height, ok1, r1, ok0, r0, reach2, t_min, t_max);
        }
    }
    if (d.y != 0.0) {
        cylinder_cap(found, t, n, o, d, r, half_height, t_min, t_max);
        cylinder_cap(found, t, n, o, d, r, -half_height, t_min, t_max);
    }
    return found;
}

bool cylinder_intersect(vec3 o, vec3 d, Primitive primitive, float t_min, float t_max, out float t, out vec3 n) {
    return cylinder_solve(o, d, primitive, t_min, t_max, true, t, n);
}

// Twin of cylinder::naive_intersect: the textbook discriminant k1^2 - k2 k0, no self-root
// rejection; kept on purpose (it cancels far from the axis).
bool cylinder_naive_intersect(vec3 o, vec3 d, Primitive primitive, float t_min, float t_max, out float t, out vec3 n) {
    return cylinder_solve(o, d, primitive, t_min, t_max, false, t, n);
}
void cylinder_uv(Primitive primitive, vec3 p, vec3 n, out vec2 uv, out vec3 du, out vec3 dv) {
    revolved_uv(p, n, primitive.a.x, primitive.a.y, uv, du, dv);
}

// Twin of twinray_shared::shapes::cylinder::bound: the sphere the primitive lies in (xyz: centre,
// w: radius, object space).
vec4 cylinder_bound(Primitive p) {
    return vec4(0.0, 0.0, 0.0, length(p.a.xy));
}
#endif
