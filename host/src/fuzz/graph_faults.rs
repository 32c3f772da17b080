//! Edits that break the glTF validator's rules on the node graph, which edits of one value at
//! random seldom make whole: a node given a second parent, a cycle, a node with both a matrix
//! and a translation, rotation or scale, and a node hidden by a zero scale (valid glTF, drawn
//! as nothing). Part of the `gltf` fuzz target's mutator (`super::faults`).

use super::rng::Rng;
use serde_json::{json, Value};

/// Breaks one such rule in `doc`'s nodes; false where it has none.
pub fn break_rule(doc: &mut Value, rng: &mut Rng) -> bool {
    let Some(count) = doc.get("nodes").and_then(Value::as_array).map(Vec::len).filter(|&n| n > 0) else {
        return false;
    };
    let (a, b) = (rng.below(count), rng.below(count));
    match rng.below(4) {
        // `a` a child of `b` as well as of whatever held it (or of `b` twice over).
        0 => add_child(doc, b, a),
        // `a` and `b` each the other's child: a cycle (of one node where they are the same).
        1 => add_child(doc, a, b) && add_child(doc, b, a),
        2 => {
            let other =
                [("translation", json!([1, 2, 3])), ("rotation", json!([0, 0, 0, 1])), ("scale", json!([2, 2, 2]))];
            let (key, value) = other[rng.below(3)].clone();
            set(doc, a, "matrix", json!([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])) && set(doc, a, key, value)
        }
        _ => {
            let zero = rng.below(3);
            let scale: Vec<f64> = (0..3).map(|i| if i == zero || rng.below(4) == 0 { 0.0 } else { 1.0 }).collect();
            set(doc, a, "scale", json!(scale))
        }
    }
}

/// Appends node `child` to node `parent`'s children.
fn add_child(doc: &mut Value, parent: usize, child: usize) -> bool {
    let Some(node) = doc.pointer_mut(&format!("/nodes/{parent}")).and_then(Value::as_object_mut) else { return false };
    let children = node.entry("children").or_insert_with(|| json!([]));
    match children.as_array_mut() {
        Some(list) => {
            list.push(json!(child));
            true
        }
        None => false,
    }
}

/// Sets `key` of node `i` to `value`.
fn set(doc: &mut Value, i: usize, key: &str, value: Value) -> bool {
    let Some(node) = doc.pointer_mut(&format!("/nodes/{i}")).and_then(Value::as_object_mut) else { return false };
    node.insert(key.into(), value);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule, from a tree of three nodes, makes a file the loader's graph check refuses or
    /// a node hidden by a zero scale.
    #[test]
    fn each_rule_breaks_the_graph_or_hides_a_node() {
        let tree = json!({"nodes": [{"children": [1, 2]}, {"mesh": 0}, {"mesh": 0}], "scenes": [{"nodes": [0]}]});
        let mut kinds = std::collections::BTreeSet::new();
        for seed in 0..200 {
            let mut doc = tree.clone();
            assert!(break_rule(&mut doc, &mut Rng::new(seed)));
            let root: gltf::json::Root = serde_json::from_value(
                json!({"asset": {"version": "2.0"}, "nodes": doc["nodes"], "scenes": doc["scenes"]}),
            )
            .unwrap();
            let hidden = doc["nodes"]
                .as_array()
                .unwrap()
                .iter()
                .any(|n| n["scale"].as_array().is_some_and(|s| s.contains(&json!(0.0))));
            match crate::scene::gltf::check_graph(&root) {
                Err(e) => drop(kinds.insert(e.split(' ').skip(2).take(3).collect::<Vec<_>>().join(" "))),
                Ok(()) => assert!(hidden, "seed {seed}: {doc}"),
            }
        }
        assert!(kinds.len() >= 3, "{kinds:?}");
        assert!(!break_rule(&mut json!({"nodes": []}), &mut Rng::new(1)));
    }
}
