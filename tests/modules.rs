//! Every committed module of both sets: SPIR-V 1.4, the entry point and execution model the
//! host asks for, only bindings from twinray_shared::bindings, the same bindings in both
//! languages, and each binding visible to the module's stage in the host's descriptor layout.

use twinray_host::render::pipeline::{descriptor_bindings, stage_flag};
use twinray_host::sets::{Language, Stage, MODULES};
use twinray_shared::spirv_info::{self, ModuleInfo};
use twinray_tests::repo_root;

fn read(spirv_path: &str) -> ModuleInfo {
    let path = repo_root().join(spirv_path);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    spirv_info::parse(&bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn every_module_declares_what_the_host_expects() {
    for spec in MODULES {
        for language in Language::ALL {
            let info = read(&spec.spirv_path(language));
            if let Err(e) = twinray_shared::module_check::check_declarations(spec, &info, language) {
                panic!("{} {}: {e}", language.name(), spec.name);
            }
        }
    }
}

#[test]
fn both_languages_bind_the_same_descriptors() {
    for spec in MODULES {
        let [rust, glsl] = Language::ALL.map(|l| read(&spec.spirv_path(l)));
        assert_eq!(rust.bindings, glsl.bindings, "{}", spec.name);
    }
}

/// What each module passes between stages (twinray_shared::interface) is read in full from
/// both languages, and is the same: the payloads, attributes and callable data of every
/// variable, each traced ray's miss index and payload, each callable call's data.
#[test]
fn both_languages_pass_the_same_payloads_attributes_and_callable_data() {
    let mut traced = 0;
    for spec in MODULES {
        let [rust, glsl] = Language::ALL.map(|l| read(&spec.spirv_path(l)).interface);
        let sorted = |i: &spirv_info::Interface| {
            let (mut v, mut t, mut c) = (i.variables.clone(), i.traces.clone(), i.calls.clone());
            v.sort_unstable();
            t.sort_unstable();
            t.dedup();
            c.sort_unstable();
            c.dedup();
            (v, t, c)
        };
        assert_eq!(sorted(&rust), sorted(&glsl), "{}", spec.name);
        let all_sized = rust.variables.iter().all(|(_, b)| b.is_some())
            && rust.traces.iter().all(|(m, p)| m.is_some() && p.is_some());
        assert!(all_sized, "{}: every size and miss index is read: {rust:?}", spec.name);
        traced += rust.traces.len();
        if matches!(spec.stage, Stage::Miss | Stage::ClosestHit | Stage::Callable) {
            assert_eq!(rust.variables.len(), glsl.variables.len());
            assert!(!rust.variables.is_empty(), "{} reads what its caller passes", spec.name);
        }
    }
    assert!(traced > 0, "the ray generation stages' traces are read");
}

#[test]
fn descriptor_layout_exposes_each_binding_to_the_stages_that_use_it() {
    let layout = descriptor_bindings();
    for spec in MODULES {
        for language in Language::ALL {
            for &(_, binding) in &read(&spec.spirv_path(language)).bindings {
                let entry = layout.iter().find(|(b, _, _, _)| *b == binding);
                let visible = entry.is_some_and(|(_, _, _, stages)| stages.contains(stage_flag(spec.stage)));
                assert!(visible, "{} {} uses binding {binding}, not visible to its stage", language.name(), spec.name);
            }
        }
    }
}

#[test]
fn every_stage_has_a_module() {
    for stage in Stage::ALL {
        assert!(MODULES.iter().any(|m| m.stage == stage), "no module for {}", stage.name());
    }
}

/// Each compute module's workgroup size, in both languages, is the one the host dispatches for
/// (`RENDER_GROUP_SIZE`, `PROBE_GROUP_SIZE`): the Rust attribute and the GLSL layout spell it
/// separately.
#[test]
fn compute_modules_run_the_workgroups_the_host_dispatches() {
    const OP_EXECUTION_MODE: u32 = 16;
    const LOCAL_SIZE: u32 = 17;
    for spec in MODULES.iter().filter(|m| m.stage == Stage::Compute) {
        let (x, y) = twinray_host::render::pipeline::workgroup(spec.name).expect("a compute module has a workgroup");
        for language in Language::ALL {
            let path = repo_root().join(spec.spirv_path(language));
            let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let words: Vec<u32> = bytes.chunks_exact(4).map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]])).collect();
            let mut sizes = Vec::new();
            let mut i = 5;
            while i < words.len() {
                let (count, opcode) = ((words[i] >> 16) as usize, words[i] & 0xffff);
                if opcode == OP_EXECUTION_MODE && words[i + 2] == LOCAL_SIZE {
                    sizes.push(words[i + 3..i + 6].to_vec());
                }
                i += count.max(1);
            }
            assert_eq!(sizes, [vec![x, y, 1]], "{} {}", language.name(), spec.name);
        }
    }
}
