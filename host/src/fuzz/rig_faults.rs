//! Edits that break the glTF validator's rules on morph targets, skins, animations, cameras,
//! accessors and texture coordinates (`scene::gltf::rules`), which edits of one value at random
//! seldom make whole: they pair two fields (a weight per target, an output per key, a matrix per
//! joint). Part of the `gltf` fuzz target's mutator (`super::faults`).

use super::rng::Rng;
use serde_json::{json, Value};

/// Breaks one such rule in `doc`; false where it has nothing to break it on.
pub fn break_rule(doc: &mut Value, rng: &mut Rng) -> bool {
    match rng.below(8) {
        0 => push_to(doc, &pick(doc, "/meshes", rng).map(|m| format!("{m}/weights")), json!(0.5)),
        1 => push_to(doc, &pick(doc, "/nodes", rng).map(|n| format!("{n}/weights")), json!(1.0)),
        2 => extra_target(doc, rng),
        3 => more_joints(doc, rng),
        4 => animation_fault(doc, rng),
        5 => {
            let ortho = json!({"type": "orthographic", "orthographic": {"xmag": 0, "ymag": 1, "znear": 0, "zfar": 10}});
            push_to(doc, &Some("/cameras".into()), ortho)
        }
        6 => set(doc, pick(doc, "/accessors", rng), "normalized", json!(true)),
        _ => {
            let material = pick(doc, "/materials", rng).map(|m| format!("{m}/pbrMetallicRoughness/baseColorTexture"));
            set(doc, material, "texCoord", json!(1 + rng.below(3)))
        }
    }
}

/// The pointer of a random element of the array at `pointer`.
fn pick(doc: &Value, pointer: &str, rng: &mut Rng) -> Option<String> {
    let n = doc.pointer(pointer)?.as_array()?.len();
    (n > 0).then(|| format!("{pointer}/{}", rng.below(n)))
}

/// Appends `value` to the array at `pointer`, making it where its parent is an object.
fn push_to(doc: &mut Value, pointer: &Option<String>, value: Value) -> bool {
    let Some(pointer) = pointer else { return false };
    let (parent, key) = pointer.rsplit_once('/').unwrap_or(("", pointer));
    let Some(parent) = doc.pointer_mut(parent).and_then(Value::as_object_mut) else { return false };
    match parent.entry(key).or_insert_with(|| json!([])).as_array_mut() {
        Some(list) => {
            list.push(value);
            true
        }
        None => false,
    }
}

/// Sets `key` of the object at `pointer`.
fn set(doc: &mut Value, pointer: Option<String>, key: &str, value: Value) -> bool {
    let Some(object) = pointer.and_then(|p| doc.pointer_mut(&p)).and_then(Value::as_object_mut) else { return false };
    object.insert(key.into(), value);
    true
}

/// A mesh given a copy of one of its primitives with one morph target more (its own POSITION
/// as the target's): primitives of one mesh with unequal counts of targets.
fn extra_target(doc: &mut Value, rng: &mut Rng) -> bool {
    let Some(mesh) = pick(doc, "/meshes", rng) else { return false };
    let Some(primitive) = pick(doc, &format!("{mesh}/primitives"), rng) else { return false };
    let Some(mut copy) = doc.pointer(&primitive).cloned() else { return false };
    let Some(position) = copy.pointer("/attributes/POSITION").cloned() else { return false };
    let Some(object) = copy.as_object_mut() else { return false };
    match object.entry("targets").or_insert_with(|| json!([])).as_array_mut() {
        Some(targets) => targets.push(json!({"POSITION": position})),
        None => return false,
    }
    push_to(doc, &Some(format!("{mesh}/primitives")), copy)
}

/// A skin given joints beyond its inverse bind matrices (or, where it has none, beyond its
/// meshes' joint indices' reach only if they name them): the node list grows by a node.
fn more_joints(doc: &mut Value, rng: &mut Rng) -> bool {
    let Some(skin) = pick(doc, "/skins", rng) else { return false };
    let Some(node) = pick(doc, "/nodes", rng).and_then(|n| n.rsplit('/').next()?.parse::<u64>().ok()) else {
        return false;
    };
    push_to(doc, &Some(format!("{skin}/joints")), json!(node))
}

/// An animation's channel doubled (two on one property), or its sampler made a cubic spline
/// (three outputs per key: the count no longer fits), or its output made its input (a scalar
/// where the property has more).
fn animation_fault(doc: &mut Value, rng: &mut Rng) -> bool {
    let Some(animation) = pick(doc, "/animations", rng) else { return false };
    let Some(channel) = pick(doc, &format!("{animation}/channels"), rng) else { return false };
    let Some(copy) = doc.pointer(&channel).cloned() else { return false };
    let sampler = copy.get("sampler").and_then(Value::as_u64).map(|s| format!("{animation}/samplers/{s}"));
    match rng.below(3) {
        0 => push_to(doc, &Some(format!("{animation}/channels")), copy),
        1 => set(doc, sampler, "interpolation", json!("CUBICSPLINE")),
        _ => {
            let input = sampler.as_ref().and_then(|s| doc.pointer(&format!("{s}/input")).cloned());
            input.is_some_and(|input| set(doc, sampler, "output", input))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each edit of a valid model that morphs, is skinned and animated makes a file the loader
    /// refuses in one line, or now and then leaves it valid (a weight pushed onto a mesh that had
    /// none and no targets is refused, but a texCoord on a model without textures is not read),
    /// and refusals name at least five kinds of object.
    #[test]
    fn each_edit_breaks_a_rule_of_a_rigged_model() {
        let text = crate::scene::gltf::tests::rules::rigged_model();
        let valid: Value = serde_json::from_str(&text).unwrap();
        let mut kinds = std::collections::BTreeSet::new();
        for seed in 0..120 {
            let mut doc = valid.clone();
            if !break_rule(&mut doc, &mut Rng::new(seed)) {
                continue;
            }
            let bytes = serde_json::to_vec(&doc).unwrap();
            if let Err(e) = crate::scene::gltf::parse(&bytes, std::path::Path::new("/nonexistent")) {
                assert!(!e.contains('\n'), "seed {seed}: {e}");
                kinds.insert(e.split(' ').next().unwrap_or_default().to_string());
            }
        }
        assert!(kinds.len() >= 5, "{kinds:?}");
    }
}
