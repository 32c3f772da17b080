//! What stages pass each other, which no validator can check across modules: the payload a
//! ray is traced with and the one its miss and closest-hit stages read, the hit attribute an
//! intersection stage reports and its closest-hit stage reads, the callable data of material
//! callables; and who may trace at all. A mismatch is undefined behaviour in the driver (a
//! closest-hit stage that writes a larger payload than the ray carries writes past it), so
//! a module from disk that breaks the contract is refused before any driver sees it, and
//! `cargo xtask shaders` holds both built-in sets to it.

use crate::bindings::{MISS_PRIMARY, MISS_SHADOW};
use crate::catalog::{ModuleSpec, Stage};
use crate::layout::{HitPayload, MaterialCall, ShadowPayload};
use crate::spirv_info::{
    ModuleInfo, STORAGE_CALLABLE_DATA, STORAGE_HIT_ATTRIBUTE, STORAGE_INCOMING_CALLABLE_DATA,
    STORAGE_INCOMING_RAY_PAYLOAD,
};

/// Bytes of the payload primary rays carry ([`HitPayload`]).
pub const HIT_PAYLOAD_BYTES: u32 = size_of::<HitPayload>() as u32;
/// Bytes of the payload shadow rays carry ([`ShadowPayload`]).
pub const SHADOW_PAYLOAD_BYTES: u32 = size_of::<ShadowPayload>() as u32;
/// Bytes of the material callables' data ([`MaterialCall`]).
pub const MATERIAL_CALL_BYTES: u32 = size_of::<MaterialCall>() as u32;
/// Bytes of a procedural hit's attribute: the object-space normal, three floats.
pub const PROCEDURAL_ATTRIBUTE_BYTES: u32 = 12;
/// Bytes of a triangle hit's attribute: two barycentrics.
pub const TRIANGLE_ATTRIBUTE_BYTES: u32 = 8;
/// Recursion depth of twinray's pipelines: ray generation traces, and nothing it calls may
/// trace again. A crate that traces from its hit stages declares more
/// ([`crate::custom::abi`]'s `recursion_depth`), up to [`MAX_DECLARED_DEPTH`].
pub const MAX_RECURSION_DEPTH: u32 = 1;
/// The deepest recursion a crate may declare: Vulkan's `maxRayRecursionDepth` is at least 1
/// and at most 31 on the drivers twinray knows; a device with less refuses the set by name.
pub const MAX_DECLARED_DEPTH: u32 = 31;

/// What a module of `spec` must pass: the bytes of its incoming payload, hit attribute,
/// incoming and outgoing callable data (`None`: it must declare none of that class), and
/// whether it may trace.
struct Contract {
    payload_in: Option<u32>,
    attribute: Option<u32>,
    callable_in: Option<u32>,
    callable_out: Option<u32>,
    traces: bool,
}

fn contract(spec: &ModuleSpec) -> Option<Contract> {
    let none = Contract { payload_in: None, attribute: None, callable_in: None, callable_out: None, traces: false };
    let triangle = spec.name.starts_with("triangle_");
    Some(match spec.stage {
        Stage::Raygen | Stage::Compute => Contract { traces: true, ..none },
        Stage::Miss if spec.name == "shadow_miss" => Contract { payload_in: Some(SHADOW_PAYLOAD_BYTES), ..none },
        Stage::Miss => Contract { payload_in: Some(HIT_PAYLOAD_BYTES), ..none },
        Stage::Intersection => Contract { attribute: Some(PROCEDURAL_ATTRIBUTE_BYTES), ..none },
        Stage::ClosestHit => Contract {
            payload_in: Some(HIT_PAYLOAD_BYTES),
            attribute: Some(if triangle { TRIANGLE_ATTRIBUTE_BYTES } else { PROCEDURAL_ATTRIBUTE_BYTES }),
            callable_out: Some(MATERIAL_CALL_BYTES),
            ..none
        },
        Stage::Callable => Contract { callable_in: Some(MATERIAL_CALL_BYTES), ..none },
        // The cutout any-hit stage runs for primary and shadow rays, procedural and triangle
        // hits alike: it may read neither payload nor attribute, which spirv-val cannot see.
        Stage::AnyHit => return None,
    })
}

/// Checks what `info` passes against the contract of `spec`'s stage, in pipelines of recursion
/// `depth`: the error says what it passes and what the stages around it pass. From depth 2,
/// closest-hit and miss stages may trace too (Vulkan lets no other stage trace).
pub fn check(spec: &ModuleSpec, info: &ModuleInfo, depth: u32) -> Result<(), String> {
    let stage = spec.stage.name();
    if let Some(c) = contract(spec) {
        let expected = [
            (STORAGE_INCOMING_RAY_PAYLOAD, c.payload_in, "incoming payload", "the rays it serves carry"),
            (STORAGE_HIT_ATTRIBUTE, c.attribute, "hit attribute", "the hits it serves report"),
            (STORAGE_INCOMING_CALLABLE_DATA, c.callable_in, "incoming callable data", "its callers pass"),
            (STORAGE_CALLABLE_DATA, c.callable_out, "callable data", "the material callables read"),
        ];
        for (class, want, what, whose) in expected {
            for &(_, got) in info.interface.variables.iter().filter(|(c, _)| *c == class) {
                match want {
                    None => return Err(format!("it declares a {what}, which a {stage} stage of twinray has none of")),
                    Some(want) if got != Some(want) => {
                        return Err(format!("its {what} is {}, but {whose} {want} bytes", bytes(got)));
                    }
                    Some(_) => {}
                }
            }
        }
        let may_trace = c.traces || (depth > 1 && matches!(spec.stage, Stage::ClosestHit | Stage::Miss));
        if !may_trace && !info.interface.traces.is_empty() {
            let why = if depth > 1 {
                format!("a {stage} stage may not trace")
            } else {
                format!(
                    "only ray generation may trace (a trace from a {stage} stage is undefined behaviour; a crate \
                     whose hit stages trace declares its depth: `pub const RECURSION_DEPTH: u32 = 2;` in shared/src/lib.rs)"
                )
            };
            return Err(format!("it calls traceRay, but its set's pipelines have recursion depth {depth}: {why}"));
        }
    }
    for &(miss, payload) in &info.interface.traces {
        let want = match miss {
            Some(MISS_PRIMARY) => HIT_PAYLOAD_BYTES,
            Some(MISS_SHADOW) => SHADOW_PAYLOAD_BYTES,
            // A computed miss index: the payload must be one of the two.
            _ if payload == Some(HIT_PAYLOAD_BYTES) || payload == Some(SHADOW_PAYLOAD_BYTES) => continue,
            _ => HIT_PAYLOAD_BYTES,
        };
        if payload != Some(want) {
            let (kind, name) =
                if want == HIT_PAYLOAD_BYTES { ("primary", "HitPayload") } else { ("shadow", "ShadowPayload") };
            return Err(format!(
                "it traces a {kind} ray (miss index {}) with a payload of {}, but the stages that ray reaches \
                 read a {name} of {want} bytes",
                miss.map_or("computed".into(), |m| m.to_string()),
                bytes(payload)
            ));
        }
    }
    for &data in &info.interface.calls {
        if data != Some(MATERIAL_CALL_BYTES) {
            return Err(format!(
                "it calls a callable with {} of data, but the material callables read {MATERIAL_CALL_BYTES} bytes",
                bytes(data)
            ));
        }
    }
    Ok(())
}

fn bytes(size: Option<u32>) -> String {
    size.map_or("a type of unknown size".into(), |b| format!("{b} bytes"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog::module;
    use crate::spirv_info::{Interface, STORAGE_RAY_PAYLOAD};

    fn info(interface: Interface) -> ModuleInfo {
        ModuleInfo { interface, ..Default::default() }
    }

    #[test]
    fn payloads_must_match_the_rays_they_serve() {
        let chit = module("procedural_closest_hit").unwrap();
        let good = Interface {
            variables: vec![(STORAGE_INCOMING_RAY_PAYLOAD, Some(80)), (STORAGE_HIT_ATTRIBUTE, Some(12))],
            ..Default::default()
        };
        assert_eq!(check(&chit, &info(good), 1), Ok(()));
        let shadow = Interface { variables: vec![(STORAGE_INCOMING_RAY_PAYLOAD, Some(4))], ..Default::default() };
        let e = check(&chit, &info(shadow), 1).unwrap_err();
        assert!(e.contains("incoming payload is 4 bytes") && e.contains("80 bytes"), "{e}");
        let traces = Interface { traces: vec![(Some(MISS_SHADOW), Some(4))], ..Default::default() };
        assert!(check(&chit, &info(traces.clone()), 1).unwrap_err().contains("recursion depth 1"));
        assert_eq!(check(&chit, &info(traces.clone()), 2), Ok(()), "a crate of depth 2 shades in its closest hit");
        let wrong = Interface { traces: vec![(Some(MISS_SHADOW), Some(80))], ..Default::default() };
        assert!(check(&chit, &info(wrong), 2).unwrap_err().contains("traces a shadow ray"), "payloads still checked");
        let callable = module("flat_material").unwrap();
        let calls = Interface { variables: vec![(STORAGE_INCOMING_CALLABLE_DATA, Some(160))], ..traces };
        assert!(check(&callable, &info(calls), 2).unwrap_err().contains("a callable stage may not trace"));
    }

    #[test]
    fn ray_generation_traces_each_ray_with_its_payload() {
        let raygen = module("raygen").unwrap();
        let good = Interface {
            variables: vec![(STORAGE_RAY_PAYLOAD, Some(80)), (STORAGE_RAY_PAYLOAD, Some(4))],
            traces: vec![(Some(MISS_PRIMARY), Some(80)), (Some(MISS_SHADOW), Some(4))],
            calls: vec![],
        };
        assert_eq!(check(&raygen, &info(good), 1), Ok(()));
        // A primary ray traced with the shadow payload: the closest-hit stage writes past it.
        let swapped = Interface { traces: vec![(Some(MISS_PRIMARY), Some(4))], ..Default::default() };
        let e = check(&raygen, &info(swapped), 1).unwrap_err();
        assert!(e.contains("primary ray (miss index 0) with a payload of 4 bytes"), "{e}");
        let miss = module("shadow_miss").unwrap();
        let wrong = Interface { variables: vec![(STORAGE_INCOMING_RAY_PAYLOAD, Some(80))], ..Default::default() };
        assert!(check(&miss, &info(wrong), 1).is_err());
    }
}
