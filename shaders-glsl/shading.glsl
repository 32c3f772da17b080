// Twin of twinray_shared::shading: world-space normals and material colours.
#ifndef TWINRAY_SHADING_GLSL
#define TWINRAY_SHADING_GLSL
#include "twinray_layout.glsl"

// Normals transform by the inverse transpose: n * M is transpose(M) * n.
vec3 world_normal(mat3 world_to_object, vec3 object_normal) {
    return normalize(object_normal * world_to_object);
}

vec3 face_forward(vec3 n, vec3 d) {
    return dot(n, d) > 0.0 ? -n : n;
}

// World geometric normal faced against the ray, shading normal turned to its side.
void surface_normals(mat3 world_to_object, vec3 geometric, vec3 shading, vec3 direction, out vec3 g, out vec3 s) {
    g = face_forward(world_normal(world_to_object, geometric), direction);
    s = world_normal(world_to_object, shading);
    s = dot(s, g) < 0.0 ? -s : s;
}

// Geometric normal (from the winding) and interpolated shading normal of a triangle.
void triangle_normals(vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2, float u, float v, out vec3 geometric,
                      out vec3 shading) {
    geometric = cross(p1 - p0, p2 - p0);
    shading = n0 * (1.0 - u - v) + n1 * u + n2 * v;
}

// The checker is evaluated CHECKER_DEPTH cells below the surface: on a plane through a cell
// boundary it would otherwise flip with the rounding of each hit point.
vec3 material_color(Material material, vec3 object_point, vec3 object_normal) {
    if (material.kind == MATERIAL_CHECKER) {
        float scale = material.color_b.w;
        vec3 inside = object_point - normalize(object_normal) * (CHECKER_DEPTH / scale);
        vec3 cell = floor(inside * scale);
        int parity = int(cell.x + cell.y + cell.z) & 1;
        return parity == 0 ? material.color_a.xyz : material.color_b.xyz;
    }
    return material.color_a.xyz;
}

// A cutout's alpha over object-space x and z (see twinray_shared::shading::cutout_alpha).
float cutout_alpha(Material material, vec3 object_point) {
    vec2 q = object_point.xz * material.cutout_scale;
    vec2 cell = floor(q);
    if (material.cutout_pattern == CUTOUT_CHECKER) {
        int parity = int(cell.x + cell.y) & 1;
        return parity == 0 ? 1.0 : 0.0;
    } else if (material.cutout_pattern == CUTOUT_DISCS) {
        return min(length((q - cell - vec2(0.5)) * 2.0), 1.0);
    } else if (material.cutout_pattern == CUTOUT_TEXTURE) {
        // Its opacity: the triangle any-hit stage multiplies in the texture's and the vertices'.
        return material.color_a.w;
    }
    return 1.0;
}

bool cutout_solid(Material material, vec3 object_point) {
    return cutout_alpha(material, object_point) >= material.cutout_threshold;
}
#endif
