// Twin of twinray_shared::exact: error-free arithmetic, results rounded at their own size. Each
// result is `precise` (SPIR-V NoContraction), so that no driver fuses or reorders the steps the
// routines lean on; the Rust set's build decorates its twins the same way.
#ifndef TWINRAY_EXACT_GLSL
#define TWINRAY_EXACT_GLSL

// Twin of exact::split: the top 12 significant bits of x, and the rest.
vec2 exact_split(float x) {
    float high = uintBitsToFloat(floatBitsToUint(x) & 0xFFFFF000u);
    precise vec2 halves = vec2(high, x - high);
    return halves;
}

// Twin of exact::point_at: o + d t rounded relative to the result, with no need for the driver
// to fuse the multiply and add.
vec3 point_at(vec3 o, vec3 d, float t) {
    vec2 ts = exact_split(t);
    precise vec3 p;
    for (int i = 0; i < 3; i++) {
        vec2 ds = exact_split(d[i]);
        p[i] = (o[i] + ds.x * ts.x) + (ds.x * ts.y + ds.y * ts.x) + ds.y * ts.y;
    }
    return p;
}

// Twin of exact::split_difference: a - b as high + low, both cut at one power of two Q (2^-12 of
// the larger's binade), so that nothing of the order of a or b is rounded.
vec2 split_difference(float a, float b) {
    float a_size = abs(a);
    float b_size = abs(b);
    float larger = a_size > b_size ? a_size : b_size;
    uint exponent = (floatBitsToUint(larger) >> 23) & 0xffu;
    exponent = exponent > 24u ? exponent : 24u;
    float quantum = uintBitsToFloat((exponent - 12u) << 23);
    float inverse = uintBitsToFloat((266u - exponent) << 23);
    precise float a_high = trunc(a * inverse) * quantum;
    precise float b_high = trunc(b * inverse) * quantum;
    precise vec2 parts = vec2(a_high - b_high, (a - a_high) - (b - b_high));
    return parts;
}

// Twin of exact::moved_origin: (origin - translation) + shift direction, rounded at its own size.
vec3 moved_origin(vec3 origin, vec3 translation, vec3 direction, float shift) {
    vec2 x = split_difference(origin.x, translation.x);
    vec2 y = split_difference(origin.y, translation.y);
    vec2 z = split_difference(origin.z, translation.z);
    precise vec3 moved = point_at(vec3(x.x, y.x, z.x), direction, shift) + vec3(x.y, y.y, z.y);
    return moved;
}
#endif
