//! The check and the pass on modules whose answer is known: GLSL stages glslang compiles here,
//! with and without `nonuniformEXT`, and the Rust set before and after the pass.

use super::*;
use std::path::Path;
use std::process::Command;

/// `source` (a GLSL stage of `kind`) compiled by glslang with the set's include path.
fn glsl(kind: &str, source: &str) -> Vec<u8> {
    // One folder per source: the tests run in parallel.
    let hash = source.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    let dir = std::env::temp_dir().join(format!("twinray-uniformity-{}-{hash:x}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (src, out) = (dir.join(format!("stage.{kind}")), dir.join(format!("{kind}.spv")));
    std::fs::write(&src, source).unwrap();
    let status = Command::new("glslangValidator")
        .args(["-V", "--target-env", "spirv1.4", "-o"])
        .arg(&out)
        .arg(&src)
        .output()
        .expect("glslangValidator runs (cargo xtask setup installs it)");
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stdout));
    std::fs::read(out).unwrap()
}

/// A closest-hit stage sampling texture `index` of an array of textures.
fn closest_hit(index: &str) -> String {
    format!(
        "#version 460\n#extension GL_EXT_ray_tracing : require\n#extension GL_EXT_nonuniform_qualifier : require\n\
         layout(set = 0, binding = 3, std430) readonly buffer Objects {{ uint material[]; }};\n\
         layout(set = 0, binding = 12) uniform sampler2D textures[];\n\
         layout(location = 0) rayPayloadInEXT vec4 payload;\n\
         layout(push_constant) uniform Push {{ uint chosen; }};\n\
         void main() {{ uint m = material[gl_InstanceID]; uint i = 0u; if (gl_PrimitiveID > 3) {{ i = 2u; }}\n\
         payload = textureLod(textures[{index}], vec2(0.5), 0.0); }}\n"
    )
}

fn faults(bytes: &[u8]) -> Vec<Fault> {
    check(bytes).unwrap()
}

#[test]
fn an_index_from_the_instance_through_memory_without_non_uniform_is_found() {
    let found = faults(&glsl("rchit", &closest_hit("m")));
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].binding, (0, 12));
    assert!(found[0].source.contains("InstanceId"), "{}", found[0]);
}

#[test]
fn an_index_chosen_by_a_branch_on_the_primitive_is_found() {
    let found = faults(&glsl("rchit", &closest_hit("i")));
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].source.contains("PrimitiveId"), "{}", found[0]);
}

#[test]
fn non_uniform_ext_and_uniform_indices_pass() {
    assert_eq!(faults(&glsl("rchit", &closest_hit("nonuniformEXT(m)"))), []);
    assert_eq!(faults(&glsl("rchit", &closest_hit("chosen"))), [], "a push constant is uniform");
    assert_eq!(faults(&glsl("rchit", &closest_hit("1"))), []);
}

/// The pass decorates what the check asks for, with its capabilities, and the module stays
/// valid.
#[test]
fn the_pass_decorates_and_the_module_validates() {
    let bare = glsl("rchit", &closest_hit("m"));
    let decorated = decorate(&bare).unwrap();
    assert_eq!(faults(&decorated), []);
    let info = twinray_shared::spirv_info::parse(&decorated).unwrap();
    assert!(info.capabilities.contains(&(Capability::ShaderNonUniform as u32)));
    assert!(info.capabilities.contains(&(Capability::SampledImageArrayNonUniformIndexing as u32)));
    let path = std::env::temp_dir().join(format!("twinray-uniformity-{}-decorated.spv", std::process::id()));
    std::fs::write(&path, &decorated).unwrap();
    let val = Command::new("spirv-val").args(twinray_shared::catalog::SPIRV_VAL_ARGS).arg(&path).output().unwrap();
    assert!(val.status.success(), "{}", String::from_utf8_lossy(&val.stderr));
    assert_eq!(decorate(&decorated).unwrap(), decorated, "decorating twice changes nothing");
}

/// Both committed sets: every texture access of the Rust set carries the pass's decoration,
/// and the GLSL set's `nonuniformEXT`.
#[test]
fn the_committed_sets_index_their_textures_non_uniformly() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for spec in twinray_shared::catalog::MODULES {
        for language in twinray_shared::catalog::Language::ALL {
            let bytes = std::fs::read(root.join(spec.spirv_path(language))).unwrap();
            assert_eq!(faults(&bytes), [], "{} {}", language.name(), spec.name);
        }
    }
}

/// rust-gpu's own output before the pass: the texture array reaches the sampling function as a
/// parameter, and the material slots through a struct in memory read by the instance id, one
/// access for the base colour texture and one for emission. (The file is a committed module
/// with the pass's decorations and capabilities taken out: docs/testing.md.)
#[test]
fn rust_gpu_output_without_the_pass_is_found() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let bytes = std::fs::read(dir.join("testdata/triangle_closest_hit.undecorated.spv")).unwrap();
    let found = faults(&bytes);
    assert_eq!(found.len(), 2, "{found:?}");
    for fault in &found {
        assert_eq!(fault.binding, (0, 12));
        assert!(fault.source.contains("InstanceId"), "{fault}");
    }
    assert_eq!(faults(&decorate(&bytes).unwrap()), []);
}

/// The reproducer of docs/upstream/non-uniform.md as rust-gpu 0.11 writes it: no NonUniform
/// anywhere; the check names the access and the built-in, and the pass adds exactly the
/// decorations of the access chain and the load, and two capabilities.
#[test]
fn the_upstream_reproducer_is_found_and_fixed_as_the_note_says() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("testdata/textured_hit.rust-gpu.spv");
    let bytes = std::fs::read(path).unwrap();
    let found = faults(&bytes);
    assert_eq!(found.len(), 1);
    assert!(found[0].to_string().starts_with("%27 = OpAccessChain indexes the descriptor array at set 0 binding 0 with a value derived from the built-in InstanceId"), "{}", found[0]);
    let fixed = decorate(&bytes).unwrap();
    let module = load(&fixed).unwrap();
    let mut decorated: Vec<Word> = Facts::of(&module).non_uniform.into_iter().collect();
    decorated.sort_unstable();
    assert_eq!(decorated, [27, 29]);
    let before = twinray_shared::spirv_info::parse(&bytes).unwrap().capabilities.len();
    assert_eq!(twinray_shared::spirv_info::parse(&fixed).unwrap().capabilities.len(), before + 2);
}
