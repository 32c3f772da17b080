// Twin of HitPayload::poison and HitPayload::unwritten (twinray_shared::layout) and of
// no_payload_word (twinray_shared::bindings): ray generation poisons the payload before each
// trace, so that a hit or miss stage that writes nothing is seen. Included after the stage
// declares `payload`.
#ifndef TWINRAY_PAYLOAD_GLSL
#define TWINRAY_PAYLOAD_GLSL

// The six words payload_unwritten reads (all twenty cost 3.7% on showcase on an H100).
void poison_payload() {
    float f = uintBitsToFloat(UNWRITTEN);
    payload.ids.w = UNWRITTEN;
    payload.color.x = f;
    payload.position.x = f;
    payload.position.w = f;
    payload.shading_normal.x = f;
    payload.geometric_normal.x = f;
}

bool poisoned(float x) {
    return floatBitsToUint(x) == UNWRITTEN;
}

// Whether the stage that took the ray left what its reader needs of the poison: every field
// (all), or only what the probe reads. Each test in a variable first: glslang writes `||` over
// a function call as a branch, over variables as one instruction (the Rust twin uses `|`).
bool payload_unwritten(HitPayload p, bool all) {
    bool unwritten = p.ids.w == UNWRITTEN;
    bool hit = p.ids.w != NO_HIT;
    bool color = poisoned(p.color.x);
    bool position = poisoned(p.position.x);
    bool geometric = poisoned(p.geometric_normal.x);
    bool t = poisoned(p.position.w);
    bool shading = poisoned(p.shading_normal.x);
    bool seen_by_all = color || (hit && (position || geometric));
    bool seen_by_probe = hit && (t || shading);
    return unwritten || (all && seen_by_all) || seen_by_probe;
}

uint no_payload_word(uint word, uint sample_index) {
    return word == 0u ? (1u | (sample_index << NO_PAYLOAD_FIRST_SHIFT)) : word + 1u;
}

#endif
