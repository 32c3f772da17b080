//! Checks a compiled module against its spec (`catalog::ModuleSpec`): the SPIR-V version, the
//! entry point, the contract of what stages pass each other (`interface`), and the bindings.
//! Apart from the catalog so that the catalog imports nothing that imports it back.

use crate::bindings as b;
use crate::catalog::{spirv_version, Language, ModuleSpec, Stage, LAYOUT};
use crate::spirv_info::ModuleInfo;

/// Checks what a compiled module of `spec` in `language` declares: SPIR-V 1.4 to 1.6, the
/// language's entry point with the stage's execution model, only bindings of [`LAYOUT`]
/// that the stage can see, and the payloads, attributes and callable data of
/// [`crate::interface`], in twinray's pipelines (recursion depth 1).
pub fn check_declarations(spec: &ModuleSpec, info: &ModuleInfo, language: Language) -> Result<(), String> {
    check_module(spec, info, spec.entry_point(language), crate::interface::MAX_RECURSION_DEPTH)
}

/// As [`check_declarations`], for an entry point called `entry`, in pipelines of recursion
/// `depth`.
pub fn check_module(spec: &ModuleSpec, info: &ModuleInfo, entry: &str, depth: u32) -> Result<(), String> {
    if spirv_version(info.version).is_none() {
        return Err(format!("SPIR-V {}.{}, where twinray reads 1.4 to 1.6", info.version.0, info.version.1));
    }
    let want = (spec.stage.execution_model(), entry.to_string());
    if !info.entry_points.contains(&want) {
        return Err(format!("no {} entry point {entry:?} ({})", spec.stage.name(), describe_entries(info)));
    }
    // What the stage passes first: a stage that traces also binds the TLAS, and the
    // recursion depth is the cause to name.
    crate::interface::check(spec, info, depth)?;
    for &(set, binding) in &info.bindings {
        let layout = LAYOUT.iter().find(|l| set == b::DESCRIPTOR_SET && l.binding == binding);
        match layout {
            None => {
                return Err(format!(
                    "binds set {set} binding {binding}, which twinray_shared::bindings does not define"
                ))
            }
            Some(l) if !l.stages.contains(&spec.stage) => {
                return Err(format!("uses binding {binding}, which the {} stage cannot see", spec.stage.name()))
            }
            Some(_) => {}
        }
    }
    Ok(())
}

/// What entry points a module has, for error messages: `it has a miss entry point "main"`.
fn describe_entries(info: &ModuleInfo) -> String {
    if info.entry_points.is_empty() {
        return "it has none".into();
    }
    let list: Vec<String> = info
        .entry_points
        .iter()
        .map(|(model, name)| match Stage::ALL.iter().find(|s| s.execution_model() == *model) {
            Some(stage) => format!("a {} entry point {name:?}", stage.name()),
            None => format!("an entry point {name:?} of execution model {model}"),
        })
        .collect();
    format!("it has {}", list.join(", "))
}
