#version 460
// Twin of twinray_shaders::triangle_closest_hit (with CALLABLE_MATERIALS defined, of
// triangle_closest_hit_callable; with FLAT_MATERIAL, of triangle_closest_hit_flat): triangle
// meshes, normals from the vertices.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
#include "shading.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials { Material materials[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_VERTICES, std430) readonly buffer Vertices { Vertex vertices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_INDICES, std430) readonly buffer Indices { uint indices[]; };

layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec2 barycentrics;

#include "closest_hit.glsl"

void main() {
    ObjectData data = objects[gl_InstanceID];
    Material material = materials[data.material];
    uint first = data.index_base + 3u * gl_PrimitiveID;
    Vertex v0 = vertices[data.vertex_base + indices[first]];
    Vertex v1 = vertices[data.vertex_base + indices[first + 1u]];
    Vertex v2 = vertices[data.vertex_base + indices[first + 2u]];
    vec3 object_geometric, object_shading;
    triangle_normals(v0.position.xyz, v1.position.xyz, v2.position.xyz, v0.normal.xyz, v1.normal.xyz, v2.normal.xyz,
                     barycentrics.x, barycentrics.y, object_geometric, object_shading);
    float t = gl_RayTmaxEXT;
    vec3 color = SURFACE_COLOR(material, gl_ObjectRayOriginEXT + gl_ObjectRayDirectionEXT * t, object_geometric);
    vec3 geometric, shading;
    surface_normals(mat3(gl_WorldToObjectEXT), object_geometric, object_shading, gl_WorldRayDirectionEXT, geometric,
                    shading);
    uvec4 ids = uvec4(gl_InstanceID, gl_PrimitiveID, material.kind, gl_HitKindEXT);
    describe(gl_WorldRayOriginEXT + gl_WorldRayDirectionEXT * t, t, geometric, shading, color, ids);
}
