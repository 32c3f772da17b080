//! The edits that make a starter crate shade in its closest hits, for the own-stages tests.

use std::path::Path;

/// Shading where the crate puts it: every procedural closest hit of the crate in `krate`, in
/// Rust and in its GLSL twin, lights the surface with twinray's lights and shadow rays and
/// leaves radiance (`MATERIAL_SHADED`) through a soft ramp; the crate declares recursion depth
/// 2. Each edit is (file, a line of the starter, what follows it).
const SHADING: [(&str, &str, &str); 6] = [
    (
        "src/hit.rs",
        "    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,\n",
        "    #[spirv(descriptor_set = 0, binding = 0)] tlas: &spirv_std::ray_tracing::AccelerationStructure,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] lights: &crate::trace::Lights,
    #[spirv(ray_payload)] shadow: &mut twinray_shared::layout::ShadowPayload,\n",
    ),
    (
        "src/hit.rs",
        "    hit::describe_surface(payload, &surface, material.kind, *normal, *normal, (color, emission));\n",
        "    let mut rays = 0;
    let lit = crate::trace::shade(tlas, frame, lights, true, true, false, Features::new(features), payload, shadow, 0, 0, &mut rays);
    payload.color = (lit / (lit + Vec3::ONE)).extend(payload.color.w);
    payload.ids.z = twinray_shared::bindings::MATERIAL_SHADED;\n",
    ),
    ("shared/src/lib.rs", "#![cfg_attr(target_arch = \"spirv\", no_std)]\n", "pub const RECURSION_DEPTH: u32 = 2;\n"),
    (
        "glsl/procedural.rchit",
        "hitAttributeEXT vec3 normal;\n",
        "layout(set = DESCRIPTOR_SET, binding = BINDING_TLAS) uniform accelerationStructureEXT tlas;
layout(set = DESCRIPTOR_SET, binding = BINDING_LIGHTS, std430) readonly buffer Lights { Light lights[]; };
layout(location = 1) rayPayloadEXT ShadowPayload shadow_payload;\n",
    ),
    ("glsl/procedural.rchit", "#include \"procedural_hit.glsl\"\n", "#include \"trace.glsl\"\n"),
    (
        "glsl/procedural.rchit",
        "gl_RayTmaxEXT, mat3(gl_WorldToObjectEXT), normal, frame.cone.x);\n",
        "    uint rays = 0u;
    vec3 lit = shade(true, true, 0u, 0u, rays);
    payload.color.xyz = lit / (lit + vec3(1.0));
    payload.ids.z = MATERIAL_SHADED;\n",
    ),
];

pub fn shade_in_closest_hits(krate: &Path) {
    for (file, line, after) in SHADING {
        let source = std::fs::read_to_string(krate.join(file)).unwrap();
        assert!(source.contains(line), "{file}: the starter moved ({line}): this test must follow");
        std::fs::write(krate.join(file), source.replacen(line, &format!("{line}{after}"), 1)).unwrap();
    }
}
