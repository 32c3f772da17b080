// Twin of twinray_shared::lighting: one sample of a light as seen from a point.
#ifndef TWINRAY_LIGHTING_GLSL
#define TWINRAY_LIGHTING_GLSL
#include "twinray_layout.glsl"

struct LightSample {
    vec3 direction;
    float distance;
    vec3 irradiance;
};

// Twin of twinray_shared::lighting::falloff: what a point light's range and cone leave of its
// inverse-square light at `distance` along `direction` (from the point to the light).
float light_falloff(Light light, vec3 direction, float distance) {
    float x = distance * light.position.w;
    float x2 = x * x;
    float window = min(max(1.0 - x2 * x2, 0.0), 1.0);
    float cone = min(max(dot(light.u.xyz, -direction) * light.v.x + light.v.y, 0.0), 1.0);
    return window * (cone * cone);
}

// A directional light's shadow ray reaches `across` (frame.reach.y: across the whole scene).
LightSample light_sample(Light light, vec3 point, uint i, uint j, float r1, float r2, float across) {
    vec3 radiance = light.radiance.xyz;
    if (light.kind == LIGHT_DIRECTIONAL) {
        return LightSample(light.position.xyz, across, radiance);
    }
    vec3 target;
    if (light.kind == LIGHT_POINT) {
        target = light.position.xyz;
    } else {
        float n = float(light.samples);
        float s = (float(i) + r1) / n - 0.5;
        float t = (float(j) + r2) / n - 0.5;
        target = light.position.xyz + light.u.xyz * s + light.v.xyz * t;
    }
    vec3 to_light = target - point;
    float distance_sq = dot(to_light, to_light);
    float distance = sqrt(distance_sq);
    vec3 direction = to_light / distance;
    vec3 irradiance;
    if (light.kind == LIGHT_POINT) {
        // Times the falloff first: a plain point light (falloff 1) gives radiance / d^2 exactly.
        // Dimmed only where the scene has a range or a cone (HAS_FEATURE_LIGHT_CONES).
        vec3 dimmed = HAS_FEATURE_LIGHT_CONES ? radiance * light_falloff(light, direction, distance) : radiance;
        irradiance = dimmed / distance_sq;
    } else {
        // Area light, two-sided: radiance x cosine at the light x solid angle of one stratum.
        vec3 area_normal = cross(light.u.xyz, light.v.xyz);
        float cos_light = abs(dot(area_normal, direction)) / length(area_normal);
        float n = float(light.samples);
        irradiance = radiance * (cos_light * length(area_normal) / (n * n * distance_sq));
    }
    return LightSample(direction, distance, irradiance);
}

uint light_samples_per_side(Light light) {
    if (light.kind == LIGHT_DIRECTIONAL || light.kind == LIGHT_POINT) {
        return 1u;
    }
    return light.samples;
}
#endif
