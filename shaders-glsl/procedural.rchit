#version 460
// Twin of twinray_stages::procedural_closest_hit (with CALLABLE_MATERIALS defined, of
// procedural_closest_hit_callable; with FLAT_MATERIAL, of procedural_closest_hit_flat): every
// procedural shape, described from the reported object-space normal.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "twinray_layout.glsl"
#include "shading.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials { Material materials[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_FRAME) uniform Frame { FrameUniform frame; };
layout(set = DESCRIPTOR_SET, binding = BINDING_TEXTURES) uniform sampler2D textures[];

layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec3 normal;

#include "procedural_hit.glsl"

void main() {
    procedural_hit(gl_InstanceID, gl_InstanceCustomIndexEXT + gl_PrimitiveID, gl_PrimitiveID, gl_HitKindEXT,
                   gl_WorldRayOriginEXT, gl_WorldRayDirectionEXT, gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT,
                   gl_RayTmaxEXT, mat3(gl_WorldToObjectEXT), normal, frame.cone.x);
}
