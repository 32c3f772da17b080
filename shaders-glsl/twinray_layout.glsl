// Generated from twinray-shared 0.3.0 by `cargo xtask shaders`; do not edit.
#ifndef TWINRAY_LAYOUT_GLSL
#define TWINRAY_LAYOUT_GLSL

#define DESCRIPTOR_SET 0u
#define BINDING_TLAS 0u
#define BINDING_IMAGE 1u
#define BINDING_FRAME 2u
#define BINDING_OBJECTS 3u
#define BINDING_PRIMITIVES 4u
#define BINDING_MATERIALS 5u
#define BINDING_LIGHTS 6u
#define BINDING_HIT_IDS 7u
#define HIT_IDS_PER_PIXEL 4u
#define BINDING_VERTICES 8u
#define BINDING_INDICES 9u
#define BINDING_PROBE_RAYS 10u
#define BINDING_PROBE_RESULTS 11u
#define BINDING_TEXTURES 12u
#define MAX_TAPS 8u
#define RENDER_GROUP_SIZE 8u
#define PROBE_GROUP_SIZE 64u
#define EXPLAIN_PRIMARY 0u
#define EXPLAIN_SHADOW 1u
#define HIT_KIND_TRIANGLE_FRONT 254u
#define HIT_KIND_TRIANGLE_BACK 255u
#define MISS_PRIMARY 0u
#define PRIMARY_RAY_FLAGS 16u
#define MISS_SHADOW 1u
#define MASK_OCCLUDER 1u
#define MASK_EMITTER 2u
#define SPEC_SHADOWS 0u
#define SPEC_SAMPLES_PER_SIDE 1u
#define SPEC_SHADOW_SAMPLER 2u
#define SPEC_FEATURES 3u
#define SPEC_SHADED_HITS 4u
#define FEATURES_ALL 63u
#define SHADOW_SAMPLER_STRATIFIED 0u
#define SHADOW_SAMPLER_RANDOM 1u
#define MATERIAL_DIFFUSE 0u
#define MATERIAL_EMISSIVE 1u
#define MATERIAL_CHECKER 2u
#define MATERIAL_CUTOUT 3u
#define MATERIAL_SHADED 4294967280u
#define CUTOUT_NONE 0u
#define CUTOUT_CHECKER 1u
#define CUTOUT_DISCS 2u
#define CUTOUT_TEXTURE 3u
#define LIGHT_DIRECTIONAL 0u
#define LIGHT_POINT 1u
#define LIGHT_RECT 2u
#define NO_HIT 4294967295u
#define UNWRITTEN 2141576877u
#define PROBE_NO_PAYLOAD 2141522861u
#define NO_PAYLOAD_FIRST_SHIFT 16u
#define SHAPE_NAIVE 128u
layout(constant_id = SPEC_FEATURES) const uint FEATURES = FEATURES_ALL;
#define FEATURE_TEXTURES 1u
#ifdef TWINRAY_WITHOUT_TEXTURES
#define HAS_FEATURE_TEXTURES false
#else
#define HAS_FEATURE_TEXTURES ((FEATURES & FEATURE_TEXTURES) != 0u)
#endif
#define FEATURE_AREA_LIGHTS 2u
#ifdef TWINRAY_WITHOUT_AREA_LIGHTS
#define HAS_FEATURE_AREA_LIGHTS false
#else
#define HAS_FEATURE_AREA_LIGHTS ((FEATURES & FEATURE_AREA_LIGHTS) != 0u)
#endif
#define FEATURE_ALPHA_MASKS 4u
#ifdef TWINRAY_WITHOUT_ALPHA_MASKS
#define HAS_FEATURE_ALPHA_MASKS false
#else
#define HAS_FEATURE_ALPHA_MASKS ((FEATURES & FEATURE_ALPHA_MASKS) != 0u)
#endif
#define FEATURE_EMISSION 8u
#ifdef TWINRAY_WITHOUT_EMISSION
#define HAS_FEATURE_EMISSION false
#else
#define HAS_FEATURE_EMISSION ((FEATURES & FEATURE_EMISSION) != 0u)
#endif
#define FEATURE_FAR_INSTANCES 16u
#ifdef TWINRAY_WITHOUT_FAR_INSTANCES
#define HAS_FEATURE_FAR_INSTANCES false
#else
#define HAS_FEATURE_FAR_INSTANCES ((FEATURES & FEATURE_FAR_INSTANCES) != 0u)
#endif
#define FEATURE_LIGHT_CONES 32u
#ifdef TWINRAY_WITHOUT_LIGHT_CONES
#define HAS_FEATURE_LIGHT_CONES false
#else
#define HAS_FEATURE_LIGHT_CONES ((FEATURES & FEATURE_LIGHT_CONES) != 0u)
#endif
#define HIT_KIND_SPHERE 1u
#define HIT_KIND_PLANE 2u
#define HIT_KIND_BOX 3u
#define HIT_KIND_CYLINDER 4u
#define HIT_KIND_CONE 5u
#define HIT_KIND_TORUS 6u
#define OFFSET_ORIGIN 0.03125
#define OFFSET_FLOAT_SCALE 1.5258789e-5
#define OFFSET_INT_SCALE 256.0
#define OFFSET_REACH_SCALE 3.0517578e-5
#define CHECKER_DEPTH 0.001
#define SELF_ROOT_REACH 0.1
#define NEAR_BOUNDS 2.0
#define FAR_BOUNDS 3.0
#define SPHERE_ON_SURFACE 0.001
#define PLANE_DISK 1.0
#define BOX_GAMMA_3 1.7881396e-7
#define CONE_POLISH_LIMIT 0.1
#define TORUS_ON_SURFACE 0.001
#define TORUS_ROOT_TOLERANCE 9.536743e-7
#define TORUS_SELF_BAND 0.004

// 192 bytes, as twinray_shared::layout::FrameUniform
struct FrameUniform {
    mat4 view_inverse; // offset 0
    mat4 proj_inverse; // offset 64
    vec4 background; // offset 128
    vec4 reach; // offset 144
    uint light_count; // offset 160
    uint seed; // offset 164
    uint width; // offset 168
    uint height; // offset 172
    vec4 cone; // offset 176
};

// 16 bytes, as twinray_shared::layout::ObjectData
struct ObjectData {
    uint material; // offset 0
    uint vertex_base; // offset 4
    uint index_base; // offset 8
    uint shape; // offset 12
};

// 64 bytes, as twinray_shared::layout::Vertex
struct Vertex {
    vec4 position; // offset 0
    vec4 normal; // offset 16
    vec4 uv; // offset 32
    vec4 color; // offset 48
};

// 48 bytes, as twinray_shared::layout::Primitive
struct Primitive {
    vec4 a; // offset 0
    vec4 b; // offset 16
    vec4 tint; // offset 32
};

// 112 bytes, as twinray_shared::layout::Material
struct Material {
    uint kind; // offset 0
    uint cutout_pattern; // offset 4
    float cutout_scale; // offset 8
    float cutout_threshold; // offset 12
    vec4 color_a; // offset 16
    vec4 color_b; // offset 32
    uvec4 texture; // offset 48
    vec4 uv_u; // offset 64
    vec4 uv_v; // offset 80
    vec4 emission; // offset 96
};

// 80 bytes, as twinray_shared::layout::Light
struct Light {
    uint kind; // offset 0
    uint samples; // offset 4
    uint shadows; // offset 8
    uint _pad0; // offset 12
    vec4 position; // offset 16
    vec4 radiance; // offset 32
    vec4 u; // offset 48
    vec4 v; // offset 64
};

// 80 bytes, as twinray_shared::layout::HitPayload
struct HitPayload {
    vec4 position; // offset 0
    vec4 shading_normal; // offset 16
    vec4 geometric_normal; // offset 32
    vec4 color; // offset 48
    uvec4 ids; // offset 64
};

// 4 bytes, as twinray_shared::layout::ShadowPayload
struct ShadowPayload {
    uint occluded; // offset 0
};

// 160 bytes, as twinray_shared::layout::MaterialCall
struct MaterialCall {
    Material material; // offset 0
    vec4 point; // offset 112
    vec4 normal; // offset 128
    vec4 color; // offset 144
};

// 32 bytes, as twinray_shared::layout::ProbeRay
struct ProbeRay {
    vec4 origin; // offset 0
    vec4 direction; // offset 16
};

// 32 bytes, as twinray_shared::layout::ProbeResult
struct ProbeResult {
    vec4 normal_t; // offset 0
    uvec4 ids; // offset 16
};

// 48 bytes, as twinray_shared::layout::ExplainRay
struct ExplainRay {
    vec4 origin; // offset 0
    vec4 direction; // offset 16
    uvec4 kind; // offset 32
};

// 96 bytes, as twinray_shared::layout::ExplainResult
struct ExplainResult {
    HitPayload hit; // offset 0
    uvec4 occluded; // offset 80
};

#endif
