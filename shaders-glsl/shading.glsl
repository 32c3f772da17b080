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

vec3 material_color(Material material, vec3 object_point) {
    if (material.kind == MATERIAL_CHECKER) {
        vec3 cell = floor(object_point * material.color_b.w);
        int parity = int(cell.x + cell.y + cell.z) & 1;
        return parity == 0 ? material.color_a.xyz : material.color_b.xyz;
    }
    return material.color_a.xyz;
}
#endif
