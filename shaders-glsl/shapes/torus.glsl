// Twin of twinray_shared::shapes::torus: torus about y (ring radius a.x, tube radius a.y). Scaled to
// R = 1 with a unit direction, origin shifted onto the bounding sphere of radius R + 2r, the
// quartic solved there (Inigo Quilez's closed form), each root polished by Newton steps on g
// and kept only if g says it lies on the surface; then the entry and exit near the two places
// where the ray passes closest to the ring, from g alone (a thin tube's quartic loses them).
// The origin moves to the entry point even when it lies behind (see the Rust twin): a ray
// starting on the torus would otherwise put a root at 0, where the solver divides by k0.
#ifndef TWINRAY_TORUS_GLSL
#define TWINRAY_TORUS_GLSL
#include "twinray_layout.glsl"
#include "shape_uv.glsl"
#include "sphere.glsl"

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

float torus_polish_step(vec3 o, vec3 d, float r, float s) {
    vec3 grad;
    float g = torus_distance(o + d * s, r, grad);
    float slope = dot(grad, d);
    return abs(slope) > 1.0e-6 ? s - g / slope : s;
}

float torus_polish(vec3 o, vec3 d, float r, float s) {
    return torus_polish_step(o, d, r, torus_polish_step(o, d, r, torus_polish_step(o, d, r, s)));
}

// One Newton step towards a local minimum of D(s) = (ring - 1)^2 + y^2 - r^2.
float torus_approach_step(vec3 o, vec3 d, float s) {
    vec3 p = o + d * s;
    float ring = sqrt(p.x * p.x + p.z * p.z);
    if (ring <= 0.0) {
        return s;
    }
    float ring1 = (p.x * d.x + p.z * d.z) / ring;
    float ring2 = (d.x * d.x + d.z * d.z - ring1 * ring1) / ring;
    float radial = ring - 1.0;
    float slope = radial * ring1 + p.y * d.y;
    float curvature = ring1 * ring1 + radial * ring2 + d.y * d.y;
    return curvature > 0.0 ? s - slope / curvature : s;
}

float torus_closest_approach(vec3 o, vec3 d, float s) {
    return torus_approach_step(o, d, torus_approach_step(o, d, torus_approach_step(o, d, torus_approach_step(o, d, s))));
}

// Where the ray's projection on the ring's plane crosses the ring (or passes nearest it, or
// where the ray crosses the plane when it runs along the axis).
vec2 torus_ring_crossings(vec3 o, vec3 d) {
    float flat_ = d.x * d.x + d.z * d.z;
    if (flat_ < 1.0e-6) {
        return vec2(-o.y * d.y);
    }
    float nearest = -(o.x * d.x + o.z * d.z) / flat_;
    float x = o.x + d.x * nearest;
    float z = o.z + d.z * nearest;
    float half_ = sqrt(max((1.0 - x * x - z * z) / flat_, 0.0));
    return vec2(nearest - half_, nearest + half_);
}

// Twin of the Rust Candidate.
struct TorusCandidate {
    vec3 o;
    vec3 d;
    vec3 start;
    float r;
    float shift;
    float to_t;
    bool on_surface;
    float t_min;
    float t_max;
    bool polish;
};

// Twin of Candidate::consider: `found`, `t`, `n` hold the best hit so far.
void torus_consider(TorusCandidate c, bool valid, float guess, inout bool found, inout float t, inout vec3 n) {
    if (!valid) {
        return;
    }
    float s = c.polish ? torus_polish(c.start, c.d, c.r, guess) : guess;
    if (c.polish) {
        vec3 p = c.start + c.d * s;
        vec3 unused;
        float g = torus_distance(p, c.r, unused);
        if (!(abs(g) <= TORUS_ROOT_TOLERANCE * max(length(p), 1.0))) {
            return;
        }
    }
    s += c.shift;
    if (c.on_surface && abs(s) <= TORUS_SELF_BAND * c.r) {
        return;
    }
    float ti = s * c.to_t;
    float limit = found ? t : c.t_max;
    if (ti >= c.t_min && ti <= limit) {
        vec3 p = c.o + c.d * s;
        found = true;
        t = ti;
        n = p - normalize(vec3(p.x, 0.0, p.z));
    }
}

// Twin of Candidate::consider_approach.
void torus_consider_approach(TorusCandidate c, float around, inout bool found, inout float t, inout vec3 n) {
    float s = torus_closest_approach(c.start, c.d, around);
    vec3 p = c.start + c.d * s;
    float ring = sqrt(p.x * p.x + p.z * p.z);
    float dist = sqrt((ring - 1.0) * (ring - 1.0) + p.y * p.y);
    if (dist >= c.r) {
        return;
    }
    float ring1 = ring > 0.0 ? (p.x * c.d.x + p.z * c.d.z) / ring : 0.0;
    float ring2 = ring > 0.0 ? (c.d.x * c.d.x + c.d.z * c.d.z - ring1 * ring1) / ring : 0.0;
    float curvature = max(ring1 * ring1 + (ring - 1.0) * ring2 + c.d.y * c.d.y, 1.0e-12);
    float half_ = sqrt((c.r - dist) * (c.r + dist) / curvature);
    torus_consider(c, true, s - half_, found, t, n);
    torus_consider(c, true, s + half_, found, t, n);
}

// The nearest of the quartic's roots (solved from `start`) that is a hit.
void torus_consider_quartic(TorusCandidate c, inout bool found, inout float t, inout vec3 n) {
    bool valid[4];
    float roots[4];
    torus_quartic_roots(c.start, c.d, c.r, valid, roots);
    for (int i = 0; i < 4; i++) {
        torus_consider(c, valid[i], roots[i], found, t, n);
    }
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
    vec3 start = o + d * near;
    TorusCandidate c = TorusCandidate(o, d, start, r, near, big_r / len, on_surface, t_min, t_max, true);
    bool found = false;
    torus_consider_quartic(c, found, t, n);
    vec2 crossings = torus_ring_crossings(start, d);
    torus_consider_approach(c, crossings.x, found, t, n);
    torus_consider_approach(c, crossings.y, found, t, n);
    return found;
}

// Twin of torus::naive_intersect: the quartic from the ray's own origin, no shift onto the
// bounding sphere, no polish, no self-root rejection; kept on purpose.
bool torus_naive_intersect(vec3 origin, vec3 direction, Primitive primitive, float t_min, float t_max, out float t,
                           out vec3 n) {
    float big_r = primitive.a.x;
    float len = length(direction);
    vec3 d = direction / len;
    vec3 o = origin / big_r;
    t = 0.0;
    n = vec3(0.0);
    TorusCandidate c = TorusCandidate(o, d, o, primitive.a.y / big_r, 0.0, big_r / len, false, t_min, t_max, false);
    bool found = false;
    torus_consider_quartic(c, found, t, n);
    return found;
}
// u by the turn about y, v by the turn about the tube (0.5 on the outer equator).
void torus_uv(Primitive primitive, vec3 p, vec3 n, out vec2 uv, out vec3 du, out vec3 dv) {
    float u = around_y(p, du);
    float rho = sqrt(max(p.x * p.x + p.z * p.z, 1.0e-30));
    float out_r = rho - primitive.a.x;
    float psi = atan(p.y, out_r);
    vec3 d_psi = (vec3(0.0, 1.0, 0.0) * out_r - vec3(p.x, 0.0, p.z) * (p.y / rho)) /
                 max(out_r * out_r + p.y * p.y, 1.0e-30);
    float turn = 0.5 / UV_PI;
    uv = vec2(u, 0.5 - psi * turn);
    dv = -d_psi * turn;
}

// Twin of twinray_shared::shapes::torus::bound: the sphere the primitive lies in (xyz: centre,
// w: radius, object space).
vec4 torus_bound(Primitive p) {
    return vec4(0.0, 0.0, 0.0, p.a.x + p.a.y);
}
#endif
