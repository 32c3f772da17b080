// Twin of twinray_shared::transform: the object-space ray of an instance, computed from the
// world ray with the instance's translation taken off the world origin first and, for a robust
// routine and a ray that starts far from its primitive, the ray brought near it before the
// transform, so that a shape far from the world origin or from the ray's start keeps its
// precision (twinray's guide, *Numerics*).
#ifndef TWINRAY_TRANSFORM_GLSL
#define TWINRAY_TRANSFORM_GLSL
#include "twinray_layout.glsl"
#include "exact.glsl"

// Twin of transform::StageRay: the ray a routine is handed, its origin `shift` along the world ray.
struct StageRay {
    vec3 origin;
    vec3 direction;
    float shift;
};

// NEAR_BOUNDS (the sphere, in bounds, a far ray is brought onto) and FAR_BOUNDS (how many bounds
// from its primitive a ray may start and be transformed where it starts) are
// twinray_shared::transform's, written into twinray_layout.glsl.

// Twin of transform::entry: where the ray (from the centre of a sphere of `radius`, direction)
// enters the sphere NEAR_BOUNDS times that radius, or its point nearest the centre; 0 where behind.
float entry(vec3 from, vec3 direction, float radius) {
    float reach = NEAR_BOUNDS * radius;
    float a = dot(direction, direction);
    float nearest = -dot(from, direction) / a;
    vec3 closest = from + direction * nearest;
    float room = reach * reach - dot(closest, closest);
    float t = room > 0.0 ? nearest - sqrt(room / a) : nearest;
    return t > 0.0 ? t : 0.0;
}

// Twin of transform::near_ray: the world ray in object space, brought near the primitive in the
// sphere `bound` first, onto NEAR_BOUNDS times that sphere, where it starts farther than
// FAR_BOUNDS from it.
StageRay near_ray(vec3 origin, vec3 direction, vec3 translation, mat3 inverse_part, vec4 bound) {
    vec3 plain = inverse_part * (origin - translation);
    vec3 d = inverse_part * direction;
    vec3 from = plain - bound.xyz;
    float reach = FAR_BOUNDS * bound.w;
    StageRay ray = StageRay(plain, d, 0.0);
    if (bound.w > 0.0 && dot(from, from) > reach * reach) {
        float shift = entry(from, d, bound.w);
        if (shift > 0.0) {
            ray.origin = inverse_part * moved_origin(origin, translation, direction, shift);
            ray.shift = shift;
        }
    }
    return ray;
}

// Twin of transform::stage_ray: the stage's own ray where the scene has far instances (a
// specialisation constant), else the driver's (driver_o, driver_d).
StageRay stage_ray(vec3 driver_o, vec3 driver_d, vec3 origin, vec3 direction, vec3 translation, mat3 inverse_part,
                   vec4 bound) {
    if (HAS_FEATURE_FAR_INSTANCES) {
        return near_ray(origin, direction, translation, inverse_part, bound);
    }
    return StageRay(driver_o, driver_d, 0.0);
}

// Twin of transform::triangle_ray: the world ray in object space, brought near the triangle
// (p0, p1, p2, object space) first, onto the sphere NEAR_BOUNDS times the one about its centroid
// through its farthest corner.
StageRay triangle_ray(vec3 origin, vec3 direction, vec3 translation, mat3 inverse_part, vec3 p0, vec3 p1, vec3 p2) {
    vec3 centre = (p0 + p1 + p2) * (1.0 / 3.0);
    float a = length(p0 - centre);
    float b = length(p1 - centre);
    float c = length(p2 - centre);
    float ab = a > b ? a : b;
    float radius = ab > c ? ab : c;
    return near_ray(origin, direction, translation, inverse_part, vec4(centre, radius));
}

// Twin of transform::plane_t: where the ray meets the plane of the triangle, on the world ray; t
// where the ray was not moved or meets the plane edge-on.
float plane_t(StageRay ray, vec3 p0, vec3 p1, vec3 p2, float t) {
    vec3 normal = cross(p1 - p0, p2 - p0);
    float along = dot(normal, ray.direction);
    if (ray.shift > 0.0 && along != 0.0) {
        return ray.shift + dot(normal, p0 - ray.origin) / along;
    }
    return t;
}

// Twin of transform::triangle_t: the t of a hit the driver found on the triangle, measured again
// on its plane from the world ray brought near it, where the scene has far instances.
float triangle_t(vec3 origin, vec3 direction, vec3 translation, mat3 inverse_part, vec3 p0, vec3 p1, vec3 p2,
                 float t) {
    if (HAS_FEATURE_FAR_INSTANCES) {
        return plane_t(triangle_ray(origin, direction, translation, inverse_part, p0, p1, p2), p0, p1, p2, t);
    }
    return t;
}

// Twin of StageRay::range: the world ray's [t_min, t_max] in the stage ray's parameter.
vec2 stage_range(StageRay ray, float t_min, float t_max) {
    return vec2(t_min - ray.shift, t_max - ray.shift);
}

// Twin of StageRay::world_t: the world ray's parameter of the stage ray's t, no more than t_max.
float stage_world_t(StageRay ray, float t, float t_max) {
    float world = ray.shift + t;
    return world > t_max ? t_max : world;
}
#endif
