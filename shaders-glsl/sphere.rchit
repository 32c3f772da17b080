#version 460
// Twin of twinray_shaders::sphere_closest_hit: Lambert shading, normal recomputed from the hit point.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
#include "shading.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_SPHERES, std430) readonly buffer Spheres { Sphere spheres[]; };

layout(location = 0) rayPayloadInEXT RayPayload payload;

void main() {
    Sphere s = spheres[gl_PrimitiveID];
    // Object space is world space here: the scene's one instance has the identity transform.
    vec3 hit = gl_ObjectRayOriginEXT + gl_ObjectRayDirectionEXT * gl_RayTmaxEXT;
    vec3 normal = normalize(hit - s.center_radius.xyz);
    payload.color = vec4(lambert(s.color.xyz, normal), 1.0);
    payload.primitive = gl_PrimitiveID;
}
