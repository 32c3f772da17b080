// Twin of twinray_shared::shapes::sphere: cancellation-free ray/sphere roots (Ray Tracing Gems ch. 7).
#ifndef TWINRAY_SPHERE_GLSL
#define TWINRAY_SPHERE_GLSL

#include "twinray_layout.glsl"
#include "shape_uv.glsl"

// Returns false on a miss; otherwise near <= far are the two ray parameters. on_surface: the ray
// starts on the sphere (|c| <= SPHERE_ON_SURFACE r^2), so one root is its own origin.
bool sphere_roots(vec3 origin, vec3 direction, vec3 center, float radius, out float near, out float far,
                  out bool on_surface) {
    near = 0.0;
    far = 0.0;
    vec3 f = origin - center;
    float a = dot(direction, direction);
    float half_b = dot(f, direction);
    float c = dot(f, f) - radius * radius;
    on_surface = abs(c) <= SPHERE_ON_SURFACE * radius * radius;
    // b'^2 - ac written as a * (r^2 - |f_perp|^2): no cancellation when the sphere is far away.
    vec3 f_perp = f - direction * (half_b / a);
    float discriminant = a * (radius * radius - dot(f_perp, f_perp));
    if (discriminant < 0.0) {
        return false;
    }
    float sign_b = half_b >= 0.0 ? 1.0 : -1.0;
    float q = -(half_b + sign_b * sqrt(discriminant));
    float t0 = c / q;
    float t1 = q / a;
    near = t0 <= t1 ? t0 : t1;
    far = t0 <= t1 ? t1 : t0;
    return true;
}

// The root to report for [t_min, t_max]: the near one, or the far one when the ray starts
// inside; for a ray starting on the surface, only the root farther from t = 0.
bool sphere_reported_root(float near, float far, bool on_surface, float t_min, float t_max, out float t) {
    if (on_surface) {
        t = abs(near) < abs(far) ? far : near;
    } else {
        t = near >= t_min ? near : far;
    }
    return t >= t_min && t <= t_max;
}

// The sphere of a primitive (centre a.xyz, radius a.w) in the common procedural form.
bool sphere_intersect(vec3 origin, vec3 direction, Primitive primitive, float t_min, float t_max, out float t, out vec3 n) {
    vec4 s = primitive.a;
    float near, far;
    bool on_surface;
    n = vec3(0.0);
    if (!(sphere_roots(origin, direction, s.xyz, s.w, near, far, on_surface)
          && sphere_reported_root(near, far, on_surface, t_min, t_max, t))) {
        return false;
    }
    n = (origin + direction * t - s.xyz) / s.w;
    return true;
}

// Twin of sphere::naive_intersect: the textbook form, kept on purpose (it cancels for distant spheres).
bool sphere_naive_intersect(vec3 origin, vec3 direction, Primitive primitive, float t_min, float t_max, out float t,
                      out vec3 n) {
    vec4 s = primitive.a;
    vec3 oc = origin - s.xyz;
    float a = dot(direction, direction);
    float half_b = dot(oc, direction);
    float c = dot(oc, oc) - s.w * s.w;
    float discriminant = half_b * half_b - a * c;
    t = 0.0;
    n = vec3(0.0);
    if (discriminant < 0.0) {
        return false;
    }
    float root = sqrt(discriminant);
    float near = (-half_b - root) / a;
    t = near >= t_min ? near : (-half_b + root) / a;
    if (!(t >= t_min && t <= t_max)) {
        return false;
    }
    n = (origin + direction * t - s.xyz) / s.w;
    return true;
}
// Twin of twinray_shared::shapes::sphere::spherical_uv: a sphere about the origin at q.
void spherical_uv(vec3 q, out vec2 uv, out vec3 du, out vec3 dv) {
    float u = around_y(q, du);
    float r2 = max(dot(q, q), 1.0e-30);
    float r = sqrt(r2);
    float rho = sqrt(max(q.x * q.x + q.z * q.z, 1.0e-30));
    uv = vec2(u, acos(clamp(q.y / r, -1.0, 1.0)) / UV_PI);
    dv = (q * q.y - vec3(0.0, 1.0, 0.0) * r2) / (r2 * rho * UV_PI);
}

void sphere_uv(Primitive primitive, vec3 p, vec3 n, out vec2 uv, out vec3 du, out vec3 dv) {
    spherical_uv(p - primitive.a.xyz, uv, du, dv);
}

// Twin of twinray_shared::shapes::sphere::bound: the sphere the primitive lies in (xyz: centre,
// w: radius, object space).
vec4 sphere_bound(Primitive p) {
    return p.a;
}
#endif
