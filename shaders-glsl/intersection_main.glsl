// The main() every procedural intersection stage shares, the twin of the Rust
// `procedural_intersection!` macro. Define SHAPE_INTERSECT (a function with the signature
// bool f(vec3 o, vec3 d, Primitive p, float t_min, float t_max, out float t, out vec3 n)),
// SHAPE_HIT_KIND and, for a robust routine, SHAPE_BOUND (vec4 f(Primitive p): the sphere the
// primitive lies in) before including this file.
#include "transform.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };

hitAttributeEXT vec3 normal;

void main() {
    // The instance custom index is the object's first primitive.
    Primitive p = primitives[gl_InstanceCustomIndexEXT + gl_PrimitiveID];
    // Where the scene has far instances, the object-space ray from the world ray, brought near
    // the primitive first (see transform.glsl); the naive routines define no SHAPE_BOUND and
    // keep the textbook transform.
#ifdef SHAPE_BOUND
    vec4 bound = SHAPE_BOUND(p);
#else
    vec4 bound = vec4(0.0);
#endif
    StageRay ray = stage_ray(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_WorldRayOriginEXT,
                             gl_WorldRayDirectionEXT, gl_ObjectToWorldEXT[3], mat3(gl_WorldToObjectEXT), bound);
    vec2 range = stage_range(ray, gl_RayTminEXT, gl_RayTmaxEXT);
    float t;
    vec3 n;
    if (SHAPE_INTERSECT(ray.origin, ray.direction, p, range.x, range.y, t, n)) {
        // Put back what was there if the hit is not taken (see the Rust twin).
        vec3 before = normal;
        normal = n;
        if (!reportIntersectionEXT(stage_world_t(ray, t, gl_RayTmaxEXT), SHAPE_HIT_KIND)) {
            normal = before;
        }
    }
}
