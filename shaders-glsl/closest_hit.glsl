// Twin of twinray_shaders::describe: the payload of a hit. Included by the closest-hit stages
// after they declare `payload`.
#ifndef TWINRAY_CLOSEST_HIT_GLSL
#define TWINRAY_CLOSEST_HIT_GLSL

void describe(vec3 point, float t, vec3 geometric, vec3 shading, vec3 color, uvec4 ids) {
    payload.position = vec4(point, t);
    payload.shading_normal = vec4(shading, 0.0);
    payload.geometric_normal = vec4(geometric, 0.0);
    payload.color = vec4(color, 1.0);
    payload.ids = ids;
}
#endif
