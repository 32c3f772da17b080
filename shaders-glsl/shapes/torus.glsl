// Twin of twinray_shared::shapes::torus: torus about y (ring radius a.x, tube radius a.y). Scaled to
// R = 1 with a unit direction, origin shifted onto the bounding sphere of radius R + 2r, the
// quartic solved there (Inigo Quilez's closed form), each root polished by Newton steps on g.
// The origin moves to the entry point even when it lies behind (see the Rust twin): a ray
// starting on the torus would otherwise put a root at 0, where the solver divides by k0.
#ifndef TWINRAY_TORUS_GLSL
#define TWINRAY_TORUS_GLSL
#include "twinray_layout.glsl"
#include "sphere.glsl"

const uint TORUS_POLISH_STEPS = 2u;

void torus_quartic_roots(vec3 o, vec3 d, float r, out bool valid[4], out float roots[4]) {
    for (int i = 0; i < 4; i++) {
        valid[i] = false;
        roots[i] = 0.0;
    }
    float m = dot(o, o);
    float n = dot(o, d);
    float k = (m - r * r - 1.0) / 2.0;
    float k3 = n;
    float k2 = n * n + d.y * d.y + k;
    float k1 = k * n + o.y * d.y;
    float k0 = k * k + o.y * o.y - r * r;
    bool inverted = abs(k3 * (k3 * k3 - k2) + k1) < 0.01;
    if (inverted) {
        float tmp = k1;
        k1 = k3;
        k3 = tmp;
        k0 = 1.0 / k0;
        k1 *= k0;
        k2 *= k0;
        k3 *= k0;
    }
    float c2 = (2.0 * k2 - 3.0 * k3 * k3) / 3.0;
    float c1 = 2.0 * (k3 * (k3 * k3 - k2) + k1);
    float c0 = (k3 * (k3 * (-3.0 * k3 * k3 + 4.0 * k2) - 8.0 * k1) + 4.0 * k0) / 3.0;
    float q = c2 * c2 + c0;
    float rr = 3.0 * c0 * c2 - c2 * c2 * c2 - c1 * c1;
    float h = rr * rr - q * q * q;
    float z;
    if (h < 0.0) {
        float sq = sqrt(q);
        z = 2.0 * sq * cos(acos(rr / (sq * q)) / 3.0);
    } else {
        float sq = pow(sqrt(h) + abs(rr), 1.0 / 3.0);
        float sign_r = rr > 0.0 ? 1.0 : (rr < 0.0 ? -1.0 : 0.0);
        z = sign_r * abs(sq + q / sq);
    }
    z = c2 - z;
    float d1 = z - 3.0 * c2;
    float d2 = z * z - 3.0 * c0;
    if (abs(d1) < 1.0e-4) {
        if (d2 < 0.0) {
            return;
        }
        d2 = sqrt(d2);
    } else {
        if (d1 < 0.0) {
            return;
        }
        d1 = sqrt(d1 / 2.0);
        d2 = c1 / d1;
    }
    float h1 = d1 * d1 - z + d2;
    if (h1 > 0.0) {
        float s = sqrt(h1);
        float a = -d1 - s - k3;
        float b = -d1 + s - k3;
        valid[0] = true;
        roots[0] = inverted ? 2.0 / a : a;
        valid[1] = true;
        roots[1] = inverted ? 2.0 / b : b;
    }
    float h2 = d1 * d1 - z - d2;
    if (h2 > 0.0) {
        float s = sqrt(h2);
        float a = d1 - s - k3;
        float b = d1 + s - k3;
        valid[2] = true;
        roots[2] = inverted ? 2.0 / a : a;
        valid[3] = true;
        roots[3] = inverted ? 2.0 / b : b;
    }
}

// Signed distance to the torus (R = 1, tube radius r) and its gradient.
float torus_distance(vec3 p, float r, out vec3 grad) {
    float ring = sqrt(p.x * p.x + p.z * p.z);
    float radial = ring - 1.0;
    float g = sqrt(radial * radial + p.y * p.y);
    grad = (ring > 0.0 && g > 0.0) ? vec3(p.x / ring * radial, p.y, p.z / ring * radial) / g : vec3(0.0, 1.0, 0.0);
    return g - r;
}

float torus_polish(vec3 o, vec3 d, float r, float s) {
    for (uint i = 0u; i < TORUS_POLISH_STEPS; i++) {
        vec3 grad;
        float g = torus_distance(o + d * s, r, grad);
        float slope = dot(grad, d);
        if (abs(slope) > 1.0e-6) {
            s -= g / slope;
        }
    }
    return s;
}

// Twin of the Rust Candidate: the nearest root of the quartic solved from `start` (`shift`
// along the ray from o), polished or not, in [t_min, t_max]; when the ray starts on the surface
// the root nearest t = 0 is its own origin and is skipped.
bool torus_best(vec3 o, vec3 d, vec3 start, float r, float shift, float to_t, bool on_surface, bool polish, float t_min,
                float t_max, out float t, out vec3 n) {
    t = 0.0;
    n = vec3(0.0);
    bool valid[4];
    float roots[4];
    torus_quartic_roots(start, d, r, valid, roots);
    float nearest_abs = 3.40282347e38;
    for (int i = 0; i < 4; i++) {
        if (valid[i] && abs(roots[i] + shift) < nearest_abs) {
            nearest_abs = abs(roots[i] + shift);
        }
    }
    bool found = false;
    for (int i = 0; i < 4; i++) {
        if (!valid[i] || (on_surface && abs(roots[i] + shift) == nearest_abs)) {
            continue;
        }
        float s = (polish ? torus_polish(start, d, r, roots[i]) : roots[i]) + shift;
        float ti = s * to_t;
        float limit = found ? t : t_max;
        if (ti >= t_min && ti <= limit) {
            vec3 p = o + d * s;
            found = true;
            t = ti;
            n = p - normalize(vec3(p.x, 0.0, p.z));
        }
    }
    return found;
}

bool torus_intersect(vec3 origin, vec3 direction, Primitive primitive, float t_min, float t_max, out float t,
                     out vec3 n) {
    float big_r = primitive.a.x;
    float r = primitive.a.y / big_r;
    float len = length(direction);
    vec3 d = direction / len;
    vec3 o = origin / big_r;
    t = 0.0;
    n = vec3(0.0);
    float near, far;
    bool bound_surface;
    if (!sphere_roots(o, d, vec3(0.0), 1.0 + 2.0 * r, near, far, bound_surface) || far < 0.0) {
        return false;
    }
    vec3 unused;
    bool on_surface = abs(torus_distance(o, r, unused)) <= TORUS_ON_SURFACE * r;
    return torus_best(o, d, o + d * near, r, near, big_r / len, on_surface, true, t_min, t_max, t, n);
}

// Twin of torus::naive_intersect: the quartic from the ray's own origin, no shift onto the
// bounding sphere, no polish, no self-root rejection; kept on purpose.
bool torus_naive_intersect(vec3 origin, vec3 direction, Primitive primitive, float t_min, float t_max, out float t,
                           out vec3 n) {
    float big_r = primitive.a.x;
    float len = length(direction);
    vec3 d = direction / len;
    vec3 o = origin / big_r;
    return torus_best(o, d, o, primitive.a.y / big_r, 0.0, big_r / len, false, false, t_min, t_max, t, n);
}
#endif
