// Twin of the body of twinray_stages::triangle_closest_hit (hit.rs): the payload of a hit on
// a triangle, normals from its vertices. Shared by the triangle closest-hit stages and the
// compute renderer (render.comp), which reads the same values from its ray query. Included
// after `objects`, `materials`, `vertices`, `indices`, `textures` and `payload`.
#ifndef TWINRAY_TRIANGLE_HIT_GLSL
#define TWINRAY_TRIANGLE_HIT_GLSL
#include "closest_hit.glsl"
#include "texture.glsl"
#include "transform.glsl"

// object: the instance id; origin, direction: the world ray; object_origin, object_direction:
// the object-space ray; driver_t: the hit's t as the driver found it (measured again here where
// the scene has far instances, `triangle_t`); translation: the instance's; cone: the spread
// angle of the ray's cone (0: texture level 0).
void triangle_hit(uint object, uint primitive_id, uint hit_kind, vec3 origin, vec3 direction, vec3 object_origin,
                  vec3 object_direction, float driver_t, mat3 world_to_object, mat4x3 object_to_world_4x3,
                  vec2 barycentrics, float cone) {
    ObjectData data = objects[object];
    Material material = materials[data.material];
    uint first = data.index_base + 3u * primitive_id;
    Vertex v0 = vertices[data.vertex_base + indices[first]];
    Vertex v1 = vertices[data.vertex_base + indices[first + 1u]];
    Vertex v2 = vertices[data.vertex_base + indices[first + 2u]];
    mat3 object_to_world = mat3(object_to_world_4x3);
    float t = triangle_t(origin, direction, object_to_world_4x3[3], world_to_object, v0.position.xyz, v1.position.xyz,
                         v2.position.xyz, driver_t);
    vec3 object_geometric, object_shading;
    triangle_normals(v0.position.xyz, v1.position.xyz, v2.position.xyz, v0.normal.xyz, v1.normal.xyz, v2.normal.xyz,
                     barycentrics.x, barycentrics.y, object_geometric, object_shading);
    vec3 color = SURFACE_COLOR(material, object_origin + object_direction * t, object_geometric) *
                 surface_tint(material, v0, v1, v2, object_to_world, barycentrics, direction, cone * t);
    vec3 emission = surface_emission(material, v0, v1, v2, object_to_world, barycentrics, direction, cone * t);
    vec3 geometric, shading;
    surface_normals(world_to_object, object_geometric, object_shading, direction, geometric, shading);
    uvec4 ids = uvec4(object, primitive_id, material.kind, hit_kind);
    describe(origin + direction * t, t, geometric, shading, color, emission, ids);
}
#endif
