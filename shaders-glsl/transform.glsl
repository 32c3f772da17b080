// Twin of twinray_shared::transform: the object-space ray of an instance, computed from the
// world ray with the instance's translation taken off the world origin first, so that a shape
// far from the world origin keeps its precision (docs/numerics.md).
#ifndef TWINRAY_TRANSFORM_GLSL
#define TWINRAY_TRANSFORM_GLSL
#include "twinray_layout.glsl"

// The object-space origin and direction of the world ray (origin, direction) for an instance
// whose object-to-world translation is `translation` and world-to-object 3x3 part `inverse`.
void object_ray(vec3 origin, vec3 direction, vec3 translation, mat3 inverse_part, out vec3 o, out vec3 d) {
    o = inverse_part * (origin - translation);
    d = inverse_part * direction;
}

// Twin of transform::stage_ray: the stage's own object-space ray where the scene has far
// instances (a specialisation constant), else the driver's (driver_o, driver_d).
void stage_ray(vec3 driver_o, vec3 driver_d, vec3 origin, vec3 direction, vec3 translation, mat3 inverse_part,
               out vec3 o, out vec3 d) {
    if (HAS_FEATURE_FAR_INSTANCES) {
        object_ray(origin, direction, translation, inverse_part, o, d);
    } else {
        o = driver_o;
        d = driver_d;
    }
}
#endif
