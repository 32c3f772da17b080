// Twin of twinray_stages::describe: the payload of a hit, and the material's colour. Included
// by the closest-hit stages after they declare `payload`.
#ifndef TWINRAY_CLOSEST_HIT_GLSL
#define TWINRAY_CLOSEST_HIT_GLSL

// SURFACE_COLOR(material, object point, object normal): the material's colour, computed here;
// compiled with CALLABLE_MATERIALS (material_shading = "callable"), by the callable the
// material's kind selects in the SBT's callable region; with FLAT_MATERIAL, its one colour.
#ifdef CALLABLE_MATERIALS
layout(location = 0) callableDataEXT MaterialCall material_call;

vec3 call_material(Material material, vec3 object_point, vec3 object_normal) {
    material_call.material = material;
    material_call.point = vec4(object_point, 1.0);
    material_call.normal = vec4(object_normal, 0.0);
    // Poisoned, so that a callable that writes no colour leaves a NaN in the image.
    material_call.color = vec4(uintBitsToFloat(UNWRITTEN));
    executeCallableEXT(material.kind, 0);
    return material_call.color.xyz;
}
#define SURFACE_COLOR call_material
#elif defined(FLAT_MATERIAL)
// Hit groups of diffuse, emissive and cutout materials (hit_groups = "per-material").
vec3 flat_color(Material material, vec3 object_point, vec3 object_normal) {
    return material.color_a.xyz;
}
#define SURFACE_COLOR flat_color
#else
#define SURFACE_COLOR material_color
#endif

// The emission in the spare w components (HitPayload::emission).
void describe(vec3 point, float t, vec3 geometric, vec3 shading, vec3 color, vec3 emission, uvec4 ids) {
    payload.position = vec4(point, t);
    payload.shading_normal = vec4(shading, emission.x);
    payload.geometric_normal = vec4(geometric, emission.y);
    payload.color = vec4(color, emission.z);
    payload.ids = ids;
}
#endif
