// Twin of twinray_shared::shapes::uv: texture coordinates on the procedural shapes, (u, v) of
// each shape's parametrisation and their object-space gradients du, dv. Each piece holds the
// image once, unmirrored from outside, v running down the image.
#ifndef TWINRAY_SHAPE_UV_GLSL
#define TWINRAY_SHAPE_UV_GLSL

const float AXIS_EPSILON2 = 1.0e-30;
const float UV_PI = 3.14159265358979323846;

// The turn of q about the y axis in [0, 1] (0.5 on +x, growing towards -z), and its gradient.
float around_y(vec3 q, out vec3 du) {
    float rho2 = max(q.x * q.x + q.z * q.z, AXIS_EPSILON2);
    du = vec3(q.z, 0.0, -q.x) * (0.5 / UV_PI / rho2);
    return atan(-q.z, q.x) * (0.5 / UV_PI) + 0.5;
}

// A disk or rectangle of half extents `half_extent` (x, z) in a plane y = const, seen from the
// side `up` (+1: from +y, -1: from -y).
void flat_uv(vec3 p, vec2 half_extent, float up, out vec2 uv, out vec3 du, out vec3 dv) {
    float w = 2.0 * half_extent.x;
    float h = 2.0 * half_extent.y * up;
    uv = vec2(0.5 + p.x / w, 0.5 + p.z / h);
    du = vec3(1.0, 0.0, 0.0) / w;
    dv = vec3(0.0, 0.0, 1.0) / h;
}

// A capped cylinder or cone about y at p, its intersection having reported the normal n.
void revolved_uv(vec3 p, vec3 n, float radius, float half_height, out vec2 uv, out vec3 du, out vec3 dv) {
    if (n.x == 0.0 && n.z == 0.0) {
        flat_uv(p, vec2(radius), n.y < 0.0 ? -1.0 : 1.0, uv, du, dv);
        return;
    }
    float height = 2.0 * half_height;
    uv = vec2(around_y(p, du), 0.5 - p.y / height);
    dv = vec3(0.0, -1.0, 0.0) / height;
}
#endif
