// Twin of the body of twinray_stages::procedural_closest_hit (hit.rs): the payload of a hit on
// a procedural shape, from the object-space normal its intersection reported. Shared by the
// procedural closest-hit stages and the compute renderer (render.comp), which reads the same
// values from its ray query. Included after `objects`, `primitives`, `materials`, `textures` and
// `payload`.
#ifndef TWINRAY_PROCEDURAL_HIT_GLSL
#define TWINRAY_PROCEDURAL_HIT_GLSL
#include "closest_hit.glsl"
#include "shape_dispatch.glsl"
#include "texture.glsl"

// Twin of twinray_stages::hit::procedural_tint: what the material's colour is multiplied by
// (tint) and the radiance emitted (emission) at a hit of shape `kind` on `primitive`; textures
// and emission read only where the scene uses them (HAS_FEATURE_*).
void procedural_tint(Material material, Primitive primitive, uint kind, vec3 point, vec3 normal,
                     mat3 world_to_object, vec3 direction, float width, out vec3 tint, out vec3 emission) {
    tint = primitive.tint.xyz;
    emission = HAS_FEATURE_EMISSION ? material.emission.xyz : vec3(0.0);
    if (!HAS_FEATURE_TEXTURES || (material.texture.x == 0u && material.texture.z == 0u)) {
        return;
    }
    vec2 uv, at, dx, dy;
    vec3 du, dv, color, light;
    shape_uv(kind, primitive, point, normal, uv, du, dv);
    shape_footprint(material, uv, du, dv, normal, world_to_object, direction, width, at, dx, dy);
    shape_textures(material, at, dx, dy, color, light);
    tint *= color;
    emission *= light;
}

// object: the instance id; primitive: custom index + primitive id; origin, direction: the
// world ray; object_origin, object_direction: the object-space ray; cone: the spread angle of
// the ray's cone (0: texture level 0).
void procedural_hit(uint object, uint primitive, uint primitive_id, uint hit_kind, vec3 origin, vec3 direction,
                    vec3 object_origin, vec3 object_direction, float t, mat3 world_to_object, vec3 normal,
                    float cone) {
    Material material = materials[objects[object].material];
    vec3 point = object_origin + object_direction * t;
    vec3 tint, emission;
    procedural_tint(material, primitives[primitive], hit_kind, point, normal, world_to_object, direction, cone * t,
                    tint, emission);
    vec3 color = SURFACE_COLOR(material, point, normal) * tint;
    vec3 geometric, shading;
    surface_normals(world_to_object, normal, normal, direction, geometric, shading);
    uvec4 ids = uvec4(object, primitive_id, material.kind, hit_kind);
    describe(origin + direction * t, t, geometric, shading, color, emission, ids);
}
#endif
