#version 460
// Twin of twinray_shaders::procedural_closest_hit (with CALLABLE_MATERIALS defined, of
// procedural_closest_hit_callable; with FLAT_MATERIAL, of procedural_closest_hit_flat): every
// procedural shape, described from the reported object-space normal.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
#include "shading.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials { Material materials[]; };

layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec3 normal;

#include "closest_hit.glsl"

void main() {
    ObjectData data = objects[gl_InstanceID];
    Material material = materials[data.material];
    vec3 tint = primitives[gl_InstanceCustomIndexEXT + gl_PrimitiveID].tint.xyz;
    float t = gl_RayTmaxEXT;
    vec3 color = SURFACE_COLOR(material, gl_ObjectRayOriginEXT + gl_ObjectRayDirectionEXT * t, normal) * tint;
    vec3 geometric, shading;
    surface_normals(mat3(gl_WorldToObjectEXT), normal, normal, gl_WorldRayDirectionEXT, geometric, shading);
    uvec4 ids = uvec4(gl_InstanceID, gl_PrimitiveID, material.kind, gl_HitKindEXT);
    describe(gl_WorldRayOriginEXT + gl_WorldRayDirectionEXT * t, t, geometric, shading, color, ids);
}
