// Generated from twinray-shared by `cargo xtask shaders`; do not edit.
#ifndef TWINRAY_LAYOUT_GLSL
#define TWINRAY_LAYOUT_GLSL

#define DESCRIPTOR_SET 0u
#define BINDING_TLAS 0u
#define BINDING_IMAGE 1u
#define BINDING_CAMERA 2u
#define BINDING_SPHERES 3u
#define BINDING_HIT_IDS 4u
#define NO_HIT 4294967295u
#define T_MIN 0.1
#define T_MAX 1000.0
#define MISS_GREY 0.3
#define LIGHT_DIRECTION vec3(1.0, 1.0, 1.0)

// 128 bytes, as twinray_shared::layout::CameraUniform
struct CameraUniform {
    mat4 view_inverse; // offset 0
    mat4 proj_inverse; // offset 64
};

// 32 bytes, as twinray_shared::layout::Sphere
struct Sphere {
    vec4 center_radius; // offset 0
    vec4 color; // offset 16
};

// 32 bytes, as twinray_shared::layout::RayPayload
struct RayPayload {
    vec4 color; // offset 0
    uint primitive; // offset 16
};

#endif
