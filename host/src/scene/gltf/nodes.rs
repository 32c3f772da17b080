//! A model's nodes placed and posed: each node's world matrix from its scene's roots, and
//! the meshes a node poses (morph targets, skins) under shape names of its own. A still
//! picture (`model`) and a clip's frames (`clip`) both place and pose through here.

use super::super::mesh::MeshData;
use super::{deform, geometry, shared};
use glam::Mat4;
use std::collections::BTreeMap;

/// Nodes deeper than this are refused: a hierarchy this deep is a cycle or an attack.
const MAX_DEPTH: usize = 256;

/// Every node under `node` (itself included) with its world matrix, depth first: its parent's
/// world matrix times its own local one, or the one `posed` gives it.
pub fn walk<'a>(
    node: gltf::Node<'a>,
    (parent, depth): (Mat4, usize),
    posed: &BTreeMap<usize, Mat4>,
    out: &mut Vec<(gltf::Node<'a>, Mat4)>,
) -> Result<(), String> {
    if depth > MAX_DEPTH {
        return Err(format!("node {} is {MAX_DEPTH} levels deep: its hierarchy has a cycle", node.index()));
    }
    let local =
        posed.get(&node.index()).copied().unwrap_or_else(|| Mat4::from_cols_array_2d(&node.transform().matrix()));
    let world = parent * local;
    for child in node.children() {
        walk(child, (world, depth + 1), posed, out)?;
    }
    out.push((node, world));
    Ok(())
}

/// The triangle primitives of `node`'s mesh posed by `pose`, added to `meshes` under their
/// names for the node (`posed_name`): a node's weights and joints are its own, so its posed
/// mesh is too.
pub fn posed_shapes(
    node: &gltf::Node,
    pose: &deform::Pose,
    (buffers, decoded): (&[Vec<u8>], &mut shared::Decoded),
    meshes: &mut BTreeMap<String, MeshData>,
) -> Result<(), String> {
    let Some(mesh) = node.mesh() else { return Ok(()) };
    for primitive in mesh.primitives() {
        let name = posed_name(&shape_name(&mesh, primitive.index()), node);
        let mut bad_normals = false;
        if let geometry::Outcome::Mesh(data) =
            geometry::primitive(&primitive, buffers, (decoded, Some(pose)), &name, &mut bad_normals)?
        {
            meshes.insert(name, data);
        }
    }
    Ok(())
}

/// The shape `shape` as node `node` poses it.
pub fn posed_name(shape: &str, node: &gltf::Node) -> String {
    format!("{shape} posed by node {}", node.index())
}

/// The shape of primitive `p` of `mesh`.
pub fn shape_name(mesh: &gltf::Mesh, p: usize) -> String {
    match mesh.name() {
        Some(name) => format!("mesh {} {name:?} primitive {p}", mesh.index()),
        None => format!("mesh {} primitive {p}", mesh.index()),
    }
}
