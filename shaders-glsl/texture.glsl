// Twin of twinray_shared::texture: texture coordinates of mesh and procedural hits and the ray
// cone's footprint in texture space, and the sampling of the scene's texture array. Included after
// `textures`.
#ifndef TWINRAY_TEXTURE_GLSL
#define TWINRAY_TEXTURE_GLSL

// Twin of twinray_shared::texture::interpolate: exactly a0 where the three agree.
vec4 interpolate(vec4 a0, vec4 a1, vec4 a2, float u, float v) {
    return a0 + (a1 - a0) * u + (a2 - a0) * v;
}

// Twin of twinray_shared::texture::transform_uv and transform_gradient: the material's texture
// coordinate transform, and its linear part.
vec2 transform_uv(Material material, vec2 uv) {
    return vec2(dot(material.uv_u.xy, uv) + material.uv_u.z, dot(material.uv_v.xy, uv) + material.uv_v.z);
}

vec2 transform_gradient(Material material, vec2 g) {
    return vec2(dot(material.uv_u.xy, g), dot(material.uv_v.xy, g));
}

// The coordinates a texture of the material reads from its set (texture.y: base colour, .w:
// emission), through the material's one transform.
vec2 vertex_uv(Material material, Vertex v, uint set) {
    return transform_uv(material, set == 1u ? v.uv.zw : v.uv.xy);
}

vec2 uv_at(vec2 uv0, vec2 uv1, vec2 uv2, vec2 b) {
    return uv0 * (1.0 - b.x - b.y) + uv1 * b.x + uv2 * b.y;
}

// Barycentrics of the point `p` away from the hit, along the plane (normal n, edges e1, e2, twice
// the area), carried to texture space: the uv there less the hit's.
vec2 footprint_gradient(vec3 p, vec3 n, vec3 e1, vec3 e2, float twice_area, vec2 uv0, vec2 uv1, vec2 uv2) {
    float u = dot(n, cross(p, e2)) / twice_area;
    float v = dot(n, cross(e1, p)) / twice_area;
    return (uv1 - uv0) * u + (uv2 - uv0) * v;
}

// Twin of twinray_shared::texture::cone_axes: the world-space axes of the ellipse a cone of
// `width` along the unit direction d cuts from the plane of unit normal n.
void cone_axes(vec3 n, vec3 d, float width, out vec3 a0, out vec3 a1) {
    a0 = d - n * dot(n, d);
    if (dot(a0, a0) <= 1.0e-8) {
        a0 = cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0));
    }
    a0 = a0 * (width / max(length(a0 - d * dot(d, a0)), 1.0e-4));
    a1 = cross(n, a0);
    a1 = a1 * (width / max(length(a1 - d * dot(d, a1)), 1.0e-4));
}

// The hit's texture coordinates `at` and their gradients dx, dy across the cone's footprint
// (twinray_shared::texture::footprint).
void footprint(mat3 object_to_world, vec3 p0, vec3 p1, vec3 p2, vec2 barycentrics, vec3 d, float width, vec2 uv0,
               vec2 uv1, vec2 uv2, out vec2 at, out vec2 dx, out vec2 dy) {
    at = uv_at(uv0, uv1, uv2, barycentrics);
    dx = vec2(0.0);
    dy = vec2(0.0);
    if (width <= 0.0) {
        return;
    }
    vec3 e1 = object_to_world * (p1 - p0);
    vec3 e2 = object_to_world * (p2 - p0);
    vec3 c = cross(e1, e2);
    float twice_area = length(c);
    if (twice_area <= 0.0) {
        return;
    }
    vec3 n = c / twice_area;
    vec3 a0, a1;
    cone_axes(n, d, width, a0, a1);
    dx = footprint_gradient(a0, n, e1, e2, twice_area, uv0, uv1, uv2);
    dy = footprint_gradient(a1, n, e1, e2, twice_area, uv0, uv1, uv2);
}

// Twin of twinray_shared::texture::taps: the samples a footprint is filtered with.
void taps(vec2 at, vec2 dx, vec2 dy, out uint count, out vec2 first, out vec2 step, out vec2 tap_dx,
          out vec2 tap_dy) {
    bool x_longer = dot(dx, dx) >= dot(dy, dy);
    vec2 major = x_longer ? dx : dy;
    vec2 minor = x_longer ? dy : dx;
    float long_axis = length(major), short_axis = length(minor);
    float ratio = short_axis > 0.0 ? long_axis / short_axis : (long_axis > 0.0 ? float(MAX_TAPS) : 1.0);
    count = clamp(uint(ceil(ratio)), 1u, MAX_TAPS);
    step = major / float(count);
    first = at - major * 0.5 + step * 0.5;
    tap_dx = step;
    tap_dy = minor;
}

// Twin of twinray_shared::texture::shape_footprint: the coordinates a material reads on a
// procedural shape (its parametrisation's uv, du, dv at the hit, the object-space normal n) and
// their gradients across the cone's footprint.
void shape_footprint(Material material, vec2 uv, vec3 du, vec3 dv, vec3 normal, mat3 world_to_object, vec3 direction,
                     float width, out vec2 at, out vec2 dx, out vec2 dy) {
    at = transform_uv(material, uv);
    dx = vec2(0.0);
    dy = vec2(0.0);
    vec3 n = transpose(world_to_object) * normal;
    float n_length = length(n);
    if (width <= 0.0 || n_length <= 0.0) {
        return;
    }
    vec3 a0, a1;
    cone_axes(n / n_length, direction, width, a0, a1);
    vec3 o0 = world_to_object * a0;
    vec3 o1 = world_to_object * a1;
    dx = transform_gradient(material, vec2(dot(du, o0), dot(dv, o0)));
    dy = transform_gradient(material, vec2(dot(du, o1), dot(dv, o1)));
}

// Twin of twinray_stages::texture::filtered: texture `slot`'s colour over a cone's footprint
// (at, dx, dy).
vec3 filtered_at(uint slot, vec2 at, vec2 dx, vec2 dy) {
    uint count;
    vec2 first, step, tap_dx, tap_dy;
    taps(at, dx, dy, count, first, step, tap_dx, tap_dy);
    vec4 sum = vec4(0.0);
    for (uint i = 0u; i < count; i++) {
        sum += textureGrad(textures[nonuniformEXT(slot)], first + step * float(i), tap_dx, tap_dy);
    }
    return sum.xyz / float(count);
}

// Texture `slot`'s colour over the cone's footprint on a triangle whose corners read their
// coordinates from `set`.
vec3 filtered(uint slot, uint set, Material material, Vertex v0, Vertex v1, Vertex v2, mat3 object_to_world,
              vec2 barycentrics, vec3 direction, float width) {
    vec2 at, dx, dy;
    footprint(object_to_world, v0.position.xyz, v1.position.xyz, v2.position.xyz, barycentrics, direction, width,
              vertex_uv(material, v0, set), vertex_uv(material, v1, set), vertex_uv(material, v2, set), at, dx, dy);
    return filtered_at(slot, at, dx, dy);
}

// Twin of twinray_stages::texture::shape_textures: what a procedural shape's colour (color) and
// emission (light) are multiplied by, each texture filtered over the footprint (at, dx, dy).
void shape_textures(Material material, vec2 at, vec2 dx, vec2 dy, out vec3 color, out vec3 light) {
    color = material.texture.x == 0u ? vec3(1.0) : filtered_at(material.texture.x, at, dx, dy);
    light = material.texture.z == 0u ? vec3(1.0) : filtered_at(material.texture.z, at, dx, dy);
}

// Twin of twinray_stages::texture::surface_tint: what the material's colour is multiplied by on
// a mesh: the vertex colour, times its texture sampled over the cone's footprint.
vec3 surface_tint(Material material, Vertex v0, Vertex v1, Vertex v2, mat3 object_to_world, vec2 barycentrics,
                  vec3 direction, float width) {
    vec4 color = interpolate(v0.color, v1.color, v2.color, barycentrics.x, barycentrics.y);
    if (!HAS_FEATURE_TEXTURES || material.texture.x == 0u) {
        return color.xyz;
    }
    return color.xyz * filtered(material.texture.x, material.texture.y, material, v0, v1, v2, object_to_world,
                                barycentrics, direction, width);
}

// Twin of twinray_stages::texture::surface_emission: the radiance a mesh emits at the hit.
vec3 surface_emission(Material material, Vertex v0, Vertex v1, Vertex v2, mat3 object_to_world, vec2 barycentrics,
                      vec3 direction, float width) {
    if (!HAS_FEATURE_EMISSION) {
        return vec3(0.0);
    }
    if (!HAS_FEATURE_TEXTURES || material.texture.z == 0u) {
        return material.emission.xyz;
    }
    return material.emission.xyz * filtered(material.texture.z, material.texture.w, material, v0, v1, v2,
                                             object_to_world, barycentrics, direction, width);
}

// Twin of twinray_stages::texture::surface_alpha: the alpha a mesh's vertex colours and
// texture (at level 0) give the surface at the hit.
float surface_alpha(Material material, Vertex v0, Vertex v1, Vertex v2, vec2 barycentrics) {
    vec4 color = interpolate(v0.color, v1.color, v2.color, barycentrics.x, barycentrics.y);
    if (!HAS_FEATURE_TEXTURES || material.texture.x == 0u) {
        return color.w;
    }
    uint set = material.texture.y;
    vec2 at = uv_at(vertex_uv(material, v0, set), vertex_uv(material, v1, set), vertex_uv(material, v2, set),
                    barycentrics);
    vec4 texel = textureGrad(textures[nonuniformEXT(material.texture.x)], at, vec2(0.0), vec2(0.0));
    return color.w * texel.w;
}
#endif
