// Twin of the body of twinray_shaders::procedural_closest_hit (hit.rs): the payload of a hit on
// a procedural shape, from the object-space normal its intersection reported. Shared by the
// procedural closest-hit stages and the compute renderer (render.comp), which reads the same
// values from its ray query. Included after `objects`, `primitives`, `materials` and `payload`.
#ifndef TWINRAY_PROCEDURAL_HIT_GLSL
#define TWINRAY_PROCEDURAL_HIT_GLSL
#include "closest_hit.glsl"

// object: the instance id; primitive: custom index + primitive id; origin, direction: the
// world ray; object_origin, object_direction: the object-space ray.
void procedural_hit(uint object, uint primitive, uint primitive_id, uint hit_kind, vec3 origin, vec3 direction,
                    vec3 object_origin, vec3 object_direction, float t, mat3 world_to_object, vec3 normal) {
    Material material = materials[objects[object].material];
    vec3 tint = primitives[primitive].tint.xyz;
    vec3 color = SURFACE_COLOR(material, object_origin + object_direction * t, normal) * tint;
    vec3 geometric, shading;
    surface_normals(world_to_object, normal, normal, direction, geometric, shading);
    uvec4 ids = uvec4(object, primitive_id, material.kind, hit_kind);
    describe(origin + direction * t, t, geometric, shading, color, material.emission.xyz, ids);
}
#endif
