// Twin of twinray_shared::sphere: cancellation-free ray/sphere roots (Ray Tracing Gems ch. 7).
#ifndef TWINRAY_SPHERE_GLSL
#define TWINRAY_SPHERE_GLSL

// Returns false on a miss; otherwise near <= far are the two ray parameters.
bool sphere_intersect(vec3 origin, vec3 direction, vec3 center, float radius, out float near, out float far) {
    near = 0.0;
    far = 0.0;
    vec3 f = origin - center;
    float a = dot(direction, direction);
    float half_b = dot(f, direction);
    float c = dot(f, f) - radius * radius;
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

// The root to report for [t_min, t_max]: the near one, or the far one when the ray starts inside.
bool sphere_reported_root(float near, float far, float t_min, float t_max, out float t) {
    t = near >= t_min ? near : far;
    return t >= t_min && t <= t_max;
}
#endif
