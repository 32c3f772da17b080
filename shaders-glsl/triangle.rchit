#version 460
// Twin of twinray_stages::triangle_closest_hit (with CALLABLE_MATERIALS defined, of
// triangle_closest_hit_callable; with FLAT_MATERIAL, of triangle_closest_hit_flat): triangle
// meshes, normals from the vertices.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "twinray_layout.glsl"
#include "shading.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials { Material materials[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_VERTICES, std430) readonly buffer Vertices { Vertex vertices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_INDICES, std430) readonly buffer Indices { uint indices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_FRAME) uniform Frame { FrameUniform frame; };
layout(set = DESCRIPTOR_SET, binding = BINDING_TEXTURES) uniform sampler2D textures[];

layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec2 barycentrics;

#include "triangle_hit.glsl"

void main() {
    // The object: instance id plus geometry index (twinray_shared::bindings::mesh_object).
    triangle_hit(gl_InstanceID + gl_GeometryIndexEXT, gl_PrimitiveID, gl_HitKindEXT, gl_WorldRayOriginEXT, gl_WorldRayDirectionEXT,
                 gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_RayTmaxEXT, mat3(gl_WorldToObjectEXT),
                 gl_ObjectToWorldEXT, barycentrics, frame.cone.x);
}
