//! Every committed module of both sets: SPIR-V 1.4, the entry point and execution model the
//! host asks for, only bindings from twinray_shared::bindings, the same bindings in both
//! languages, and each binding visible to the module's stage in the host's descriptor layout.

use twinray::render::pipeline::{descriptor_bindings, stage_flag};
use twinray::shaders::{Language, Stage, MODULES};
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
            if let Err(e) = spec.check_declarations(&info, language) {
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

#[test]
fn descriptor_layout_exposes_each_binding_to_the_stages_that_use_it() {
    let layout = descriptor_bindings();
    for spec in MODULES {
        for language in Language::ALL {
            for &(_, binding) in &read(&spec.spirv_path(language)).bindings {
                let entry = layout.iter().find(|(b, _, _)| *b == binding);
                let visible = entry.is_some_and(|(_, _, stages)| stages.contains(stage_flag(spec.stage)));
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
