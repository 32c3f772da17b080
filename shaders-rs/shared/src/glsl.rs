//! Generates `twinray_layout.glsl` of the GLSL twins, the GLSL mirror of [`crate::layout`] and
//! [`crate::bindings`], so the two shader sets cannot read different layouts.
//!
//! Each field is listed with its GLSL type; the Rust offset comes from `offset_of!`, and
//! [`GlslStruct::check`] verifies it against the std140/std430 rules for that GLSL type (for
//! the types used here the two rules agree), and that the fields cover the whole struct.

use crate::bindings::*;
use crate::layout::{
    ExplainRay, ExplainResult, FrameUniform, HitPayload, Light, Material, MaterialCall, ObjectData, Primitive,
    ProbeRay, ProbeResult, ShadowPayload, Vertex,
};
use crate::offset::{OFFSET_FLOAT_SCALE, OFFSET_INT_SCALE, OFFSET_ORIGIN, OFFSET_REACH_SCALE};
use crate::shading::CHECKER_DEPTH;
use crate::shapes::SHAPES;
use std::fmt::Write;
use std::mem::{offset_of, size_of};

/// One field of a mirrored struct.
pub struct GlslField {
    /// The field's GLSL type (`vec4`, `uint`, ...).
    pub glsl_type: &'static str,
    /// The field's name, the same in both languages.
    pub name: &'static str,
    /// Its byte offset, from the Rust struct (`offset_of!`).
    pub offset: usize,
}

/// A Rust struct and the GLSL declaration that mirrors it.
pub struct GlslStruct {
    /// The struct's name, the same in both languages.
    pub name: &'static str,
    /// Its size in bytes, from the Rust struct.
    pub size: usize,
    /// Its fields, in order.
    pub fields: Vec<GlslField>,
}

/// `glsl_struct!(T { field: "glsl type", .. })` expands to the `GlslStruct` of `T`: its name,
/// `size_of`, and each field's GLSL type, name and `offset_of`.
macro_rules! glsl_struct {
    ($ty:ident { $($field:ident : $glsl:literal),* $(,)? }) => {
        GlslStruct {
            name: stringify!($ty),
            size: size_of::<$ty>(),
            fields: vec![$(GlslField {
                glsl_type: $glsl,
                name: stringify!($field),
                offset: offset_of!($ty, $field),
            }),*],
        }
    };
}

/// Every struct the GLSL set reads or writes.
pub fn structs() -> Vec<GlslStruct> {
    vec![
        glsl_struct!(FrameUniform {
            view_inverse: "mat4",
            proj_inverse: "mat4",
            background: "vec4",
            reach: "vec4",
            light_count: "uint",
            seed: "uint",
            width: "uint",
            height: "uint",
            cone: "vec4",
        }),
        glsl_struct!(ObjectData { material: "uint", vertex_base: "uint", index_base: "uint", shape: "uint" }),
        glsl_struct!(Vertex { position: "vec4", normal: "vec4", uv: "vec4", color: "vec4" }),
        glsl_struct!(Primitive { a: "vec4", b: "vec4", tint: "vec4" }),
        glsl_struct!(Material {
            kind: "uint",
            cutout_pattern: "uint",
            cutout_scale: "float",
            cutout_threshold: "float",
            color_a: "vec4",
            color_b: "vec4",
            texture: "uvec4",
            uv_u: "vec4",
            uv_v: "vec4",
            emission: "vec4"
        }),
        glsl_struct!(Light {
            kind: "uint",
            samples: "uint",
            shadows: "uint",
            _pad0: "uint",
            position: "vec4",
            radiance: "vec4",
            u: "vec4",
            v: "vec4",
        }),
        glsl_struct!(HitPayload {
            position: "vec4",
            shading_normal: "vec4",
            geometric_normal: "vec4",
            color: "vec4",
            ids: "uvec4",
        }),
        glsl_struct!(ShadowPayload { occluded: "uint" }),
        glsl_struct!(MaterialCall { material: "Material", point: "vec4", normal: "vec4", color: "vec4" }),
        glsl_struct!(ProbeRay { origin: "vec4", direction: "vec4" }),
        glsl_struct!(ProbeResult { normal_t: "vec4", ids: "uvec4" }),
        glsl_struct!(ExplainRay { origin: "vec4", direction: "vec4", kind: "uvec4" }),
        glsl_struct!(ExplainResult { hit: "HitPayload", occluded: "uvec4" }),
    ]
}

/// (size, alignment) of a GLSL type under std430 (equal to std140 for these types).
fn glsl_size_align(glsl_type: &str) -> Option<(usize, usize)> {
    match glsl_type {
        "float" | "uint" | "int" => Some((4, 4)),
        "vec4" | "uvec4" | "ivec4" => Some((16, 16)),
        "mat4" => Some((64, 16)),
        // Struct members: Material and HitPayload are 16-aligned (their vec4s) and multiples of 16 long.
        "Material" => Some((size_of::<Material>(), 16)),
        "HitPayload" => Some((size_of::<HitPayload>(), 16)),
        _ => None,
    }
}

impl GlslStruct {
    /// Checks that GLSL would place every field where Rust does, and that no bytes are unlisted.
    pub fn check(&self) -> Result<(), String> {
        let mut end = 0usize;
        let mut struct_align = 1usize;
        for f in &self.fields {
            let (size, align) = glsl_size_align(f.glsl_type)
                .ok_or_else(|| format!("{}.{}: unsupported GLSL type {}", self.name, f.name, f.glsl_type))?;
            let glsl_offset = end.next_multiple_of(align);
            if glsl_offset != f.offset {
                return Err(format!("{}.{}: GLSL offset {glsl_offset}, Rust offset {}", self.name, f.name, f.offset));
            }
            end = glsl_offset + size;
            struct_align = struct_align.max(align);
        }
        let glsl_size = end.next_multiple_of(struct_align);
        if glsl_size != self.size {
            return Err(format!("{}: GLSL size {glsl_size}, Rust size {}", self.name, self.size));
        }
        Ok(())
    }
}

/// The text of `twinray_layout.glsl`.
pub fn layout_include() -> Result<String, String> {
    let mut s = String::new();
    // The contract's version first: a folder of GLSL twins is built against the one it names.
    let _ = writeln!(
        s,
        "// Generated from twinray-shared {} by `cargo xtask shaders`; do not edit.",
        crate::contract::CONTRACT_VERSION
    );
    s.push_str("#ifndef TWINRAY_LAYOUT_GLSL\n#define TWINRAY_LAYOUT_GLSL\n\n");
    let uints = [
        ("DESCRIPTOR_SET", DESCRIPTOR_SET),
        ("BINDING_TLAS", BINDING_TLAS),
        ("BINDING_IMAGE", BINDING_IMAGE),
        ("BINDING_FRAME", BINDING_FRAME),
        ("BINDING_OBJECTS", BINDING_OBJECTS),
        ("BINDING_PRIMITIVES", BINDING_PRIMITIVES),
        ("BINDING_MATERIALS", BINDING_MATERIALS),
        ("BINDING_LIGHTS", BINDING_LIGHTS),
        ("BINDING_HIT_IDS", BINDING_HIT_IDS),
        ("HIT_IDS_PER_PIXEL", crate::bindings::HIT_IDS_PER_PIXEL),
        ("BINDING_VERTICES", BINDING_VERTICES),
        ("BINDING_INDICES", BINDING_INDICES),
        ("BINDING_PROBE_RAYS", BINDING_PROBE_RAYS),
        ("BINDING_PROBE_RESULTS", BINDING_PROBE_RESULTS),
        ("BINDING_TEXTURES", BINDING_TEXTURES),
        ("MAX_TAPS", crate::texture::MAX_TAPS),
        ("RENDER_GROUP_SIZE", crate::bindings::RENDER_GROUP_SIZE),
        ("PROBE_GROUP_SIZE", crate::bindings::PROBE_GROUP_SIZE),
        ("EXPLAIN_PRIMARY", crate::bindings::EXPLAIN_PRIMARY),
        ("EXPLAIN_SHADOW", crate::bindings::EXPLAIN_SHADOW),
        ("HIT_KIND_TRIANGLE_FRONT", crate::bindings::HIT_KIND_TRIANGLE_FRONT),
        ("HIT_KIND_TRIANGLE_BACK", crate::bindings::HIT_KIND_TRIANGLE_BACK),
        ("MISS_PRIMARY", MISS_PRIMARY),
        ("PRIMARY_RAY_FLAGS", crate::bindings::PRIMARY_RAY_FLAGS),
        ("MISS_SHADOW", MISS_SHADOW),
        ("MASK_OCCLUDER", MASK_OCCLUDER),
        ("MASK_EMITTER", MASK_EMITTER),
        ("SPEC_SHADOWS", SPEC_SHADOWS),
        ("SPEC_SAMPLES_PER_SIDE", SPEC_SAMPLES_PER_SIDE),
        ("SPEC_SHADOW_SAMPLER", SPEC_SHADOW_SAMPLER),
        ("SPEC_FEATURES", SPEC_FEATURES),
        ("SPEC_SHADED_HITS", crate::bindings::SPEC_SHADED_HITS),
        ("FEATURES_ALL", crate::features::ALL),
        ("SHADOW_SAMPLER_STRATIFIED", SHADOW_SAMPLER_STRATIFIED),
        ("SHADOW_SAMPLER_RANDOM", SHADOW_SAMPLER_RANDOM),
        ("MATERIAL_DIFFUSE", MATERIAL_DIFFUSE),
        ("MATERIAL_EMISSIVE", MATERIAL_EMISSIVE),
        ("MATERIAL_CHECKER", MATERIAL_CHECKER),
        ("MATERIAL_CUTOUT", MATERIAL_CUTOUT),
        ("MATERIAL_SHADED", crate::bindings::MATERIAL_SHADED),
        ("CUTOUT_NONE", CUTOUT_NONE),
        ("CUTOUT_CHECKER", CUTOUT_CHECKER),
        ("CUTOUT_DISCS", CUTOUT_DISCS),
        ("CUTOUT_TEXTURE", CUTOUT_TEXTURE),
        ("LIGHT_DIRECTIONAL", LIGHT_DIRECTIONAL),
        ("LIGHT_POINT", LIGHT_POINT),
        ("LIGHT_RECT", LIGHT_RECT),
        ("NO_HIT", NO_HIT),
        ("UNWRITTEN", UNWRITTEN),
        ("PROBE_NO_PAYLOAD", PROBE_NO_PAYLOAD),
        ("NO_PAYLOAD_FIRST_SHIFT", NO_PAYLOAD_FIRST_SHIFT),
        ("SHAPE_NAIVE", crate::shapes::SHAPE_NAIVE),
    ];
    for (name, value) in uints {
        writeln!(s, "#define {name} {value}u").map_err(|e| e.to_string())?;
    }
    features_glsl(&mut s).map_err(|e| e.to_string())?;
    // Each procedural shape's hit kind, from the registry (crate::shapes).
    for shape in SHAPES {
        writeln!(s, "#define HIT_KIND_{} {}u", shape.name.to_uppercase(), shape.hit_kind).map_err(|e| e.to_string())?;
    }
    let floats = [
        ("OFFSET_ORIGIN", OFFSET_ORIGIN),
        ("OFFSET_FLOAT_SCALE", OFFSET_FLOAT_SCALE),
        ("OFFSET_INT_SCALE", OFFSET_INT_SCALE),
        ("OFFSET_REACH_SCALE", OFFSET_REACH_SCALE),
        ("CHECKER_DEPTH", CHECKER_DEPTH),
        ("SELF_ROOT_REACH", crate::surface::SELF_ROOT_REACH),
        ("NEAR_BOUNDS", crate::transform::NEAR_BOUNDS),
        ("FAR_BOUNDS", crate::transform::FAR_BOUNDS),
    ];
    // Then the constants each shape's GLSL twin reads, from its registration.
    let shape_constants = SHAPES.iter().flat_map(|shape| shape.spec.glsl_constants.iter().copied());
    for (name, value) in floats.into_iter().chain(shape_constants) {
        writeln!(s, "#define {name} {value:?}").map_err(|e| e.to_string())?;
    }
    for st in structs() {
        st.check()?;
        writeln!(s, "\n// {} bytes, as twinray_shared::layout::{}", st.size, st.name).map_err(|e| e.to_string())?;
        writeln!(s, "struct {} {{", st.name).map_err(|e| e.to_string())?;
        for f in &st.fields {
            writeln!(s, "    {} {}; // offset {}", f.glsl_type, f.name, f.offset).map_err(|e| e.to_string())?;
        }
        s.push_str("};\n");
    }
    s.push_str("\n#endif\n");
    Ok(s)
}

/// Each feature's bit (`FEATURE_TEXTURES`, ...) and its test (`HAS_FEATURE_TEXTURES`): a
/// constant false where the set is built without its code (`-DTWINRAY_WITHOUT_TEXTURES`), else
/// its bit of the specialisation constant `FEATURES` (the twin of
/// `crate::features::Features::has`).
fn features_glsl(s: &mut String) -> std::fmt::Result {
    s.push_str("layout(constant_id = SPEC_FEATURES) const uint FEATURES = FEATURES_ALL;\n");
    for f in crate::features::FEATURES {
        let name = f.macro_name();
        writeln!(s, "#define FEATURE_{name} {}u", f.bit)?;
        writeln!(s, "#ifdef TWINRAY_WITHOUT_{name}\n#define HAS_FEATURE_{name} false\n#else")?;
        writeln!(s, "#define HAS_FEATURE_{name} ((FEATURES & FEATURE_{name}) != 0u)\n#endif")?;
    }
    Ok(())
}

/// `shape_dispatch.glsl` of the GLSL twins, generated from the shape registry: every shape's GLSL
/// routine, chosen by `ObjectData::shape` (the twin of `twinray_shared::shapes::intersect_shape`),
/// for stages that meet procedural primitives themselves (ray queries).
pub fn shape_dispatch_include() -> String {
    let mut s = String::from(
        "// Generated by `cargo xtask shaders` from the shape registry (twinray_shared::shapes): the\n\
         // twin of twinray_shared::shapes::intersect_shape, every shape's routine chosen by\n\
         // ObjectData::shape (its hit kind, plus SHAPE_NAIVE for the naive variant).\n\
         #ifndef TWINRAY_SHAPE_DISPATCH_GLSL\n\
         #define TWINRAY_SHAPE_DISPATCH_GLSL\n\
         #include \"twinray_layout.glsl\"\n",
    );
    for shape in SHAPES {
        s += &format!("#include \"shapes/{}.glsl\"\n", shape.name);
    }
    s += "\nbool shape_intersect(uint shape, vec3 o, vec3 d, Primitive p, float t_min, float t_max, out float t, out vec3 n) {\n";
    for shape in SHAPES {
        let kind = format!("HIT_KIND_{}", shape.name.to_uppercase());
        s += &format!(
            "    if (shape == {kind}) {{\n        return {}_intersect(o, d, p, t_min, t_max, t, n);\n    }}\n",
            shape.name
        );
        if shape.naive_module.is_some() {
            s += &format!(
                "    if (shape == {kind} + SHAPE_NAIVE) {{\n        return {}_naive_intersect(o, d, p, t_min, t_max, t, n);\n    }}\n",
                shape.name
            );
        }
    }
    s += "    t = 0.0;\n    n = vec3(0.0);\n    return false;\n}\n";
    s += "\n// Twin of twinray_shared::shapes::shape_bound: the sphere the primitive of a robust routine lies in,\n\
          // zero for the naive ones and unknown shapes.\n\
          vec4 shape_bound(uint shape, Primitive p) {\n";
    for shape in SHAPES {
        let kind = format!("HIT_KIND_{}", shape.name.to_uppercase());
        s += &format!("    if (shape == {kind}) {{\n        return {}_bound(p);\n    }}\n", shape.name);
    }
    s += "    return vec4(0.0);\n}\n";
    s += "\n// Twin of twinray_shared::shapes::shape_uv: the texture coordinates of shape `kind` (its hit kind)\n\
          // at the object-space point q, where its intersection reported the normal n.\n\
          void shape_uv(uint kind, Primitive p, vec3 q, vec3 n, out vec2 uv, out vec3 du, out vec3 dv) {\n";
    for shape in SHAPES {
        let kind = format!("HIT_KIND_{}", shape.name.to_uppercase());
        s += &format!(
            "    if (kind == {kind}) {{\n        {}_uv(p, q, n, uv, du, dv);\n        return;\n    }}\n",
            shape.name
        );
    }
    s += "    uv = vec2(0.0);\n    du = vec3(0.0);\n    dv = vec3(0.0);\n}\n#endif\n";
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_struct_matches_glsl_rules() {
        for st in structs() {
            st.check().unwrap_or_else(|e| panic!("{e}"));
        }
    }

    #[test]
    fn check_catches_a_misplaced_field() {
        let bad = GlslStruct {
            name: "Bad",
            size: 32,
            fields: vec![
                GlslField { glsl_type: "uint", name: "a", offset: 0 },
                GlslField { glsl_type: "vec4", name: "b", offset: 4 },
            ],
        };
        assert!(bad.check().unwrap_err().contains("Bad.b"));
    }

    #[test]
    fn check_catches_unlisted_bytes() {
        let mut primitive = glsl_struct!(Primitive { a: "vec4", b: "vec4", tint: "vec4" });
        primitive.fields.pop();
        assert!(primitive.check().unwrap_err().contains("size"));
    }
}
