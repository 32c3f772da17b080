//! The edits that make a starter crate shade in its closest hits, for the own-stages tests.

use std::path::Path;

/// Shading where the crate puts it: every procedural closest hit of the crate in `krate`, in
/// Rust and in its GLSL twin, lights the surface with twinray's lights and shadow rays and
/// leaves radiance (`MATERIAL_SHADED`) through a soft ramp; the crate declares recursion depth
/// 2. Each edit is (file, lines of the starter, what follows them wherever they are: in Rust,
/// every procedural closest hit); `SHADE` follows each procedural closest hit's body.
const SHADING: [(&str, &str, &str); 5] = [
    (
        "src/closest_hit.rs",
        "    #[spirv(hit_attribute)] normal: &Vec3,\n",
        "    #[spirv(descriptor_set = 0, binding = 0)] tlas: &spirv_std::ray_tracing::AccelerationStructure,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] lights: &crate::trace::Lights,
    #[spirv(ray_payload)] shadow: &mut twinray_shared::layout::ShadowPayload,\n",
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

/// What the Rust procedural closest hits do once their body has described the surface.
const SHADE: &str =
    "    let options = crate::render::Options { shadows: true, stratified: true, features, shaded_hits: false };
    let mut rays = 0;
    let lit = crate::trace::shade(tlas, (frame, lights), options, payload, shadow, (0, 0), &mut rays);
    payload.color = (lit / (lit + Vec3::ONE)).extend(payload.color.w);
    payload.ids.z = twinray_shared::bindings::MATERIAL_SHADED;\n";

/// `source` with `SHADE` after each call of the procedural closest hits' body.
fn shade_after_each_body(source: &str) -> String {
    let (call, end) = ("hit::procedural_surface(", "\n    );\n");
    assert_eq!(source.matches(call).count(), 3, "the procedural closest hits moved: this test must follow");
    let (mut out, mut rest) = (String::new(), source);
    while let Some(at) = rest.find(call) {
        let after = at + rest[at..].find(end).expect("the call ends") + end.len();
        out.push_str(&rest[..after]);
        out.push_str(SHADE);
        rest = &rest[after..];
    }
    out + rest
}

pub fn shade_in_closest_hits(krate: &Path) {
    let hits = krate.join("src/closest_hit.rs");
    std::fs::write(&hits, shade_after_each_body(&std::fs::read_to_string(&hits).unwrap())).unwrap();
    for (file, line, after) in SHADING {
        let source = std::fs::read_to_string(krate.join(file)).unwrap();
        assert!(source.contains(line), "{file}: the starter moved ({line}): this test must follow");
        if file == "src/closest_hit.rs" {
            assert_eq!(source.matches(line).count(), 3, "{file}: the procedural closest hits moved ({line})");
        }
        std::fs::write(krate.join(file), source.replace(line, &format!("{line}{after}"))).unwrap();
    }
}
