//! The glTF validator's rules on the node graph, checked before any node is placed: each node
//! has at most one parent, no node is its own ancestor, a scene lists only root nodes, and a
//! node gives its transform as a `matrix` or as translation, rotation and scale, not both.
//! A file that breaks one is not a glTF 2.0 file, and viewers differ on what it shows (which
//! parent's transform does a node with two take? which of a matrix and TRS wins?), so it is
//! refused with the node named rather than rendered one way without a word.

use gltf::json::Root;

/// Where a node stands while the graph is walked for cycles.
#[derive(Clone, Copy, PartialEq)]
enum Seen {
    Not,
    /// On the chain of parents being walked now.
    OnPath,
    /// Known to lead up to a root.
    Rooted,
}

/// The first rule `json`'s nodes and scenes break, said with the nodes named; `Ok` for none.
pub fn check(json: &Root) -> Result<(), String> {
    let nodes = &json.nodes;
    let mut parent: Vec<Option<usize>> = vec![None; nodes.len()];
    for (i, node) in nodes.iter().enumerate() {
        if node.matrix.is_some() && (node.translation.is_some() || node.rotation.is_some() || node.scale.is_some()) {
            return Err(format!(
                "node {i} has both a matrix and a translation, rotation or scale (glTF allows one or the other)"
            ));
        }
        for child in node.children.iter().flatten().map(|c| c.value()) {
            if child >= nodes.len() {
                return Err(format!("node {i} names child {child}, past its {} nodes", nodes.len()));
            }
            if let Some(p) = parent[child] {
                return Err(format!("node {child} is a child of both node {p} and node {i} (glTF allows one parent)"));
            }
            parent[child] = Some(i);
        }
    }
    cycles(&parent)?;
    for (s, scene) in json.scenes.iter().enumerate() {
        for n in scene.nodes.iter().map(|n| n.value()) {
            if let Some(p) = parent.get(n).copied().flatten() {
                return Err(format!("scene {s} lists node {n}, a child of node {p} (a scene lists root nodes only)"));
            }
        }
    }
    Ok(())
}

/// A node that is its own ancestor, named; each node's chain of parents is walked once.
fn cycles(parent: &[Option<usize>]) -> Result<(), String> {
    let mut seen = vec![Seen::Not; parent.len()];
    let mut path = Vec::new();
    for start in 0..parent.len() {
        let mut at = Some(start);
        while let Some(n) = at {
            match seen[n] {
                Seen::Rooted => break,
                Seen::OnPath => return Err(format!("node {n} is its own ancestor: the node hierarchy has a cycle")),
                Seen::Not => {
                    seen[n] = Seen::OnPath;
                    path.push(n);
                    at = parent[n];
                }
            }
        }
        for n in path.drain(..) {
            seen[n] = Seen::Rooted;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root(nodes: &str, scenes: &str) -> Root {
        let text = format!(r#"{{"asset": {{"version": "2.0"}}, "nodes": [{nodes}], "scenes": [{scenes}]}}"#);
        serde_json::from_str(&text).expect("json")
    }

    #[test]
    fn a_tree_passes_and_each_broken_rule_is_named() {
        let tree = r#"{"children": [1, 2]}, {"children": [3]}, {}, {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}"#;
        assert_eq!(check(&root(tree, r#"{"nodes": [0]}"#)), Ok(()));
        let two_parents = r#"{"children": [2]}, {"children": [2]}, {}"#;
        let e = check(&root(two_parents, r#"{"nodes": [0, 1]}"#)).unwrap_err();
        assert!(e.contains("node 2 is a child of both node 0 and node 1"), "{e}");
        // A loop of single parents, reached from no root, is still a cycle.
        let looped = r#"{}, {"children": [2]}, {"children": [3]}, {"children": [1]}"#;
        let e = check(&root(looped, r#"{"nodes": [0]}"#)).unwrap_err();
        assert!(e.contains("is its own ancestor"), "{e}");
        let both = r#"{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "scale": [1, 1, 1]}"#;
        let e = check(&root(both, r#"{"nodes": [0]}"#)).unwrap_err();
        assert!(e.contains("node 0 has both a matrix and"), "{e}");
        let e = check(&root(r#"{"children": [1]}, {}"#, r#"{"nodes": [1]}"#)).unwrap_err();
        assert!(e.contains("scene 0 lists node 1, a child of node 0"), "{e}");
    }

    /// A chain of 100,000 nodes is walked once, not once per node.
    #[test]
    fn a_long_chain_is_checked_in_linear_time() {
        let n = 100_000;
        let nodes: Vec<String> =
            (0..n).map(|i| if i + 1 < n { format!(r#"{{"children": [{}]}}"#, i + 1) } else { "{}".into() }).collect();
        let started = std::time::Instant::now();
        assert_eq!(check(&root(&nodes.join(","), r#"{"nodes": [0]}"#)), Ok(()));
        assert!(started.elapsed().as_secs_f64() < 5.0, "{:?}", started.elapsed());
    }
}
