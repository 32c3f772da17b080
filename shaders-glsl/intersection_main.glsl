// The main() every procedural intersection stage shares, the twin of the Rust
// `procedural_intersection!` macro. Define SHAPE_INTERSECT (a function with the signature
// bool f(vec3 o, vec3 d, Primitive p, float t_min, float t_max, out float t, out vec3 n)) and
// SHAPE_HIT_KIND before including this file.
#include "transform.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };

hitAttributeEXT vec3 normal;

void main() {
    // The instance custom index is the object's first primitive.
    Primitive p = primitives[gl_InstanceCustomIndexEXT + gl_PrimitiveID];
    // Where the scene has far instances, the object-space ray from the world ray, not the
    // driver's (see transform.glsl).
    vec3 o, d;
    stage_ray(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_WorldRayOriginEXT, gl_WorldRayDirectionEXT,
              gl_ObjectToWorldEXT[3], mat3(gl_WorldToObjectEXT), o, d);
    float t;
    vec3 n;
    if (SHAPE_INTERSECT(o, d, p, gl_RayTminEXT, gl_RayTmaxEXT, t, n)) {
        // Put back what was there if the hit is not taken (see the Rust twin).
        vec3 before = normal;
        normal = n;
        if (!reportIntersectionEXT(t, SHAPE_HIT_KIND)) {
            normal = before;
        }
    }
}
