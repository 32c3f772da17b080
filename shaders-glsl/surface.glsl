// Twin of twinray_shared::surface: combining candidate hits, stable quadratic roots, self-roots.
#ifndef TWINRAY_SURFACE_GLSL
#define TWINRAY_SURFACE_GLSL

// Takes (t, n) if t lies in [t_min, best so far or t_max].
void closer(inout bool found, inout float best_t, inout vec3 best_n, float t, vec3 n, float t_min, float t_max) {
    float limit = found ? best_t : t_max;
    if (t >= t_min && t <= limit) {
        found = true;
        best_t = t;
        best_n = n;
    }
}

// Roots c / q and q / a with q = -(half_b + sign(half_b) sqrt(disc)); a root whose denominator
// is zero is marked invalid.
void stable_roots(float a, float half_b, float c, float discriminant, out bool ok0, out float r0, out bool ok1,
                  out float r1) {
    float sign_b = half_b >= 0.0 ? 1.0 : -1.0;
    float q = -(half_b + sign_b * sqrt(discriminant));
    ok0 = q != 0.0;
    r0 = ok0 ? c / q : 0.0;
    ok1 = a != 0.0;
    r1 = ok1 ? q / a : 0.0;
}

// Squared reach of a self root (see twinray_shared::surface::SELF_ROOT_REACH): negative, so
// no root qualifies, when the origin is not on the surface.
float self_reach2(bool on_surface, float size2, float dd) {
    return on_surface ? SELF_ROOT_REACH * SELF_ROOT_REACH * size2 / dd : -1.0;
}

// Whether root t is the ray's own origin: within the reach and nearer to 0 than other.
bool is_self_root(float reach2, float t, bool other_ok, float other) {
    return t * t <= reach2 && (other_ok ? abs(t) < abs(other) : true);
}
#endif
