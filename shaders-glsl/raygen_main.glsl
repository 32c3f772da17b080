// The body of both ray generation stages (raygen.rgen, raygen_query.rgen) and of the compute
// renderer (render.comp), twin of the Rust `renderer!` macro: M x M primary samples per pixel,
// shaded here; writes the mean colour and the ids of what the first sample hit; the payload is
// poisoned before each trace, and a ray whose stage left it so is counted, not shaded. With
// SHADOW_QUERY defined, shadow rays are traced inline by ray queries (trace.glsl), which read the
// objects, primitives, materials, and for alpha-tested meshes vertices, indices and textures; with RENDER_COMPUTE too, primary rays are, and the payload
// is a plain variable that trace.glsl describes hits into as the closest-hit stages would.
#include "twinray_layout.glsl"

layout(set = DESCRIPTOR_SET, binding = BINDING_TLAS) uniform accelerationStructureEXT tlas;
layout(set = DESCRIPTOR_SET, binding = BINDING_IMAGE, rgba32f) uniform writeonly image2D image;
layout(set = DESCRIPTOR_SET, binding = BINDING_FRAME) uniform Frame { FrameUniform frame; };
layout(set = DESCRIPTOR_SET, binding = BINDING_LIGHTS, std430) readonly buffer Lights { Light lights[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_HIT_IDS, std430) buffer HitIds { uint hit_ids[]; };

layout(constant_id = SPEC_SHADOWS) const uint SHADOWS = 0u;
layout(constant_id = SPEC_SAMPLES_PER_SIDE) const uint SAMPLES_PER_SIDE = 1u;
layout(constant_id = SPEC_SHADOW_SAMPLER) const uint SHADOW_SAMPLER = SHADOW_SAMPLER_STRATIFIED;

#ifdef RENDER_COMPUTE
HitPayload payload;
// Compute has no launch size: the image's, from the frame constants.
#define LAUNCH_ID gl_GlobalInvocationID.xy
#define LAUNCH_SIZE uvec2(frame.width, frame.height)
#else
layout(location = 0) rayPayloadEXT HitPayload payload;
#define LAUNCH_ID gl_LaunchIDEXT.xy
#define LAUNCH_SIZE gl_LaunchSizeEXT.xy
#endif
#ifdef SHADOW_QUERY
layout(set = DESCRIPTOR_SET, binding = BINDING_OBJECTS, std430) readonly buffer Objects { ObjectData objects[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_PRIMITIVES, std430) readonly buffer Primitives { Primitive primitives[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_MATERIALS, std430) readonly buffer Materials { Material materials[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_VERTICES, std430) readonly buffer Vertices { Vertex vertices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_INDICES, std430) readonly buffer Indices { uint indices[]; };
layout(set = DESCRIPTOR_SET, binding = BINDING_TEXTURES) uniform sampler2D textures[];
#else
layout(location = 1) rayPayloadEXT ShadowPayload shadow_payload;
#endif

#include "camera.glsl"
#include "payload.glsl"
#include "trace.glsl"

// One primary sample (sx, sy) of the pixel: traced, its ids kept if it is the first, shaded.
void one_sample(uvec2 pixel, uint pixel_index, uint sx, uint sy, inout vec3 sum, inout uint shadow_rays,
                inout uint no_payload) {
    uint sample_index = sy * SAMPLES_PER_SIDE + sx;
    // Jitter only when there is more than one sample.
    float r1 = 0.5, r2 = 0.5;
    if (SAMPLES_PER_SIDE > 1u) {
        r1 = random(frame.seed, pixel_index, sample_index, 0u);
        r2 = random(frame.seed, pixel_index, sample_index, 1u);
    }
    vec2 offset = sample_offset(sx, sy, SAMPLES_PER_SIDE, r1, r2);
    vec3 origin, direction;
    primary_ray(frame, pixel, LAUNCH_SIZE, offset, origin, direction);
    poison_payload();
    trace_primary(origin, direction);
    bool unwritten = payload_unwritten(payload, true);
    if (sample_index == 0u) {
        hit_ids[HIT_IDS_PER_PIXEL * pixel_index] = unwritten ? NO_HIT : payload.ids.x;
        hit_ids[HIT_IDS_PER_PIXEL * pixel_index + 1u] = unwritten ? NO_HIT : payload.ids.y;
    }
    if (unwritten) {
        no_payload = no_payload_word(no_payload, sample_index);
    } else {
        sum += shade(SHADOWS != 0u, SHADOW_SAMPLER == SHADOW_SAMPLER_STRATIFIED, pixel_index, sample_index,
                     shadow_rays);
    }
}

void main() {
    uvec2 pixel = LAUNCH_ID;
#ifdef RENDER_COMPUTE
    // Whole workgroups cover the image.
    if (pixel.x >= LAUNCH_SIZE.x || pixel.y >= LAUNCH_SIZE.y) {
        return;
    }
#endif
    uint pixel_index = pixel.y * LAUNCH_SIZE.x + pixel.x;
    // Not checked against hit_ids.length(), as in the Rust twin: the host sizes it to the launch,
    // and a length read before the first trace cost about 10 us a frame (up to 8% at 1 spp) on
    // NVIDIA (twinray's nvidia-code bench report).
    vec3 sum = vec3(0.0);
    uint shadow_rays = 0u;
    uint no_payload = 0u;
    // One sample is not looped over: NVIDIA's driver keeps a top-tested loop whose constant count
    // is 1, and that cost 0.3 to 1.7% of a 1-spp frame on 8 of 9 scenes, nothing at 16 spp
    // (twinray's nvidia-code bench report). The Rust twin keeps its bottom-tested
    // loop: the same branch there made 1-spp frames up to 1.8% slower.
    if (SAMPLES_PER_SIDE == 1u) {
        one_sample(pixel, pixel_index, 0u, 0u, sum, shadow_rays, no_payload);
    } else {
        for (uint sy = 0u; sy < SAMPLES_PER_SIDE; sy++) {
            for (uint sx = 0u; sx < SAMPLES_PER_SIDE; sx++) {
                one_sample(pixel, pixel_index, sx, sy, sum, shadow_rays, no_payload);
            }
        }
    }
    hit_ids[HIT_IDS_PER_PIXEL * pixel_index + 2u] = shadow_rays;
    hit_ids[HIT_IDS_PER_PIXEL * pixel_index + 3u] = no_payload;
    vec3 color = no_payload == 0u ? sum / float(SAMPLES_PER_SIDE * SAMPLES_PER_SIDE) : vec3(uintBitsToFloat(0x7fc00000u));
    imageStore(image, ivec2(pixel), vec4(color, 1.0));
}
