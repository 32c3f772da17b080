//! Morph targets and skins, posed on the host: a node's mesh with its weights and joints
//! applied to every vertex before its acceleration structure is built, so both sets and the
//! f64 reference trace the same posed triangles. The arithmetic is in f64 (each vertex
//! rounded to f32 once, at the end), from the file's f32 data and the nodes' matrices.
//!
//! Morph targets first, as glTF orders them: a vertex's position is its own plus each
//! target's displacement times the target's weight, its normal likewise (then normalized).
//! Then the skin: a vertex moves by the sum of its joints' matrices (each joint's world matrix
//! times its inverse bind matrix) weighted by its weights, its normal by that sum's inverse
//! transpose; a skinned mesh is placed in the world by its joints alone, the node's own
//! transform ignored, as the specification says.

use super::accessors::check;
use super::quantized::{self, check_attribute, Attribute};
use glam::{DMat3, DMat4, DVec3, Mat4, Vec4};
use gltf::accessor::{DataType, Dimensions};
use std::collections::BTreeMap;

/// How a node poses its mesh: its morph target weights (none where the mesh has no
/// targets) and, where it is skinned, its joints' matrices.
pub struct Pose {
    pub weights: Vec<f64>,
    pub joints: Option<Vec<DMat4>>,
}

impl Pose {
    /// The pose of `node`'s mesh, or `None` where nothing moves (no skin, no animated weights,
    /// every weight 0).
    /// Its weights are those the animation set (`animated`), else the node's, else the
    /// mesh's, else 0; its joints' world matrices are in `worlds`.
    pub fn of(
        node: &gltf::Node,
        animated: &BTreeMap<usize, Vec<f32>>,
        worlds: &BTreeMap<usize, Mat4>,
        buffers: &[Vec<u8>],
    ) -> Result<Option<Pose>, String> {
        let Some(mesh) = node.mesh() else { return Ok(None) };
        let targets = mesh.primitives().map(|p| p.morph_targets().len()).max().unwrap_or(0);
        let weights: Vec<f64> = match animated.get(&node.index()) {
            Some(w) => w.iter().map(|&w| f64::from(w)).collect(),
            None => {
                node.weights().or(mesh.weights()).map_or_else(Vec::new, |w| w.iter().map(|&w| f64::from(w)).collect())
            }
        };
        let weights = (0..targets).map(|i| weights.get(i).copied().unwrap_or(0.0)).collect::<Vec<_>>();
        let joints = node.skin().map(|skin| joint_matrices(&skin, worlds, buffers)).transpose()?;
        // Weights an animation drives pose the mesh even where they are all 0 now: a clip
        // poses it again at other times (`clip`).
        let moves = joints.is_some() || animated.contains_key(&node.index()) || weights.iter().any(|&w| w != 0.0);
        Ok(moves.then_some(Pose { weights, joints }))
    }

    /// `positions` and `normals` (all the vertices of `primitive`'s accessors, as
    /// `geometry` reads them) posed; `what` names the primitive in errors.
    pub fn apply(
        &self,
        primitive: &gltf::Primitive,
        (buffers, quantized): (&[Vec<u8>], bool),
        (positions, normals): (&[Vec4], Option<&[Vec4]>),
        what: &str,
    ) -> Result<(Vec<Vec4>, Option<Vec<Vec4>>), String> {
        let wide = |v: &[Vec4]| v.iter().map(|p| p.truncate().as_dvec3()).collect::<Vec<DVec3>>();
        let mut p = wide(positions);
        let mut n = normals.map(wide);
        self.morph(primitive, (buffers, quantized), (&mut p, n.as_mut()), what)?;
        if let Some(joints) = &self.joints {
            skin(primitive, buffers, joints, (&mut p, n.as_mut()), what)?;
        }
        let narrow = |v: Vec<DVec3>| v.into_iter().map(|p| p.as_vec3().extend(0.0)).collect::<Vec<Vec4>>();
        Ok((narrow(p), n.map(narrow)))
    }

    /// Adds each target's displacements, times its weight, to the positions and normals.
    fn morph(
        &self,
        primitive: &gltf::Primitive,
        (buffers, quantized): (&[Vec<u8>], bool),
        (positions, mut normals): (&mut [DVec3], Option<&mut Vec<DVec3>>),
        what: &str,
    ) -> Result<(), String> {
        let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
        // Each displacement accessor read alone, after its check: the `gltf` crate's reader of
        // morph targets opens every attribute of a target, `TANGENT` too, which is not checked.
        let read =
            |a: &gltf::Accessor| quantized::read::<3, _>(a, get).into_iter().map(|d| DVec3::from(d.map(f64::from)));
        for (t, (target, &w)) in primitive.morph_targets().zip(&self.weights).enumerate() {
            if w == 0.0 {
                continue;
            }
            if let Some(a) = target.positions() {
                check_attribute(
                    &a,
                    buffers,
                    (what, &format!("target {t} POSITION")),
                    Attribute::Displacement,
                    quantized,
                )?;
                add(positions, read(&a), w, (&a, what))?;
            }
            if let (Some(a), Some(normals)) = (target.normals(), normals.as_deref_mut()) {
                check_attribute(&a, buffers, (what, &format!("target {t} NORMAL")), Attribute::Normal, quantized)?;
                add(normals, read(&a), w, (&a, what))?;
            }
        }
        Ok(())
    }
}

/// `values[i] += weight * d` for each of the displacements `read` from accessor `a`, which
/// must give one per vertex.
fn add(
    values: &mut [DVec3],
    read: impl Iterator<Item = DVec3>,
    weight: f64,
    (a, what): (&gltf::Accessor, &str),
) -> Result<(), String> {
    let mut count = 0;
    for (v, d) in values.iter_mut().zip(read) {
        *v += weight * d;
        count += 1;
    }
    if count != values.len() {
        return Err(format!(
            "{what}: morph target accessor {} gave {count} displacements for {} vertices",
            a.index(),
            values.len()
        ));
    }
    Ok(())
}

/// Each joint of `skin`: its world matrix times its inverse bind matrix (identity where the
/// skin gives none).
fn joint_matrices(
    skin: &gltf::Skin,
    worlds: &BTreeMap<usize, Mat4>,
    buffers: &[Vec<u8>],
) -> Result<Vec<DMat4>, String> {
    let what = format!("skin {}", skin.index());
    let inverse: Vec<DMat4> = match skin.inverse_bind_matrices() {
        Some(a) => {
            check(&a, buffers, &what, "inverseBindMatrices", &[Dimensions::Mat4], &[DataType::F32])?;
            let reader = skin.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
            let read = reader.read_inverse_bind_matrices().into_iter().flatten();
            read.map(|m| Mat4::from_cols_array_2d(&m).as_dmat4()).collect()
        }
        None => Vec::new(),
    };
    skin.joints()
        .enumerate()
        .map(|(j, joint)| {
            let world = worlds
                .get(&joint.index())
                .ok_or_else(|| format!("{what}: joint {j} (node {}) is not in the scene drawn", joint.index()))?;
            Ok(world.as_dmat4() * inverse.get(j).copied().unwrap_or(DMat4::IDENTITY))
        })
        .collect()
}

/// Moves each vertex by its joints' matrices weighted by its weights (every JOINTS_n with its
/// WEIGHTS_n), its normal by the inverse transpose of that sum.
fn skin(
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    joints: &[DMat4],
    (positions, normals): (&mut [DVec3], Option<&mut Vec<DVec3>>),
    what: &str,
) -> Result<(), String> {
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    let mut blended = vec![DMat4::ZERO; positions.len()];
    for set in 0.. {
        let (Some(j), Some(w)) =
            (primitive.get(&gltf::Semantic::Joints(set)), primitive.get(&gltf::Semantic::Weights(set)))
        else {
            break;
        };
        let weights = [DataType::F32, DataType::U8, DataType::U16];
        check(&j, buffers, what, &format!("JOINTS_{set}"), &[Dimensions::Vec4], &[DataType::U8, DataType::U16])?;
        check(&w, buffers, what, &format!("WEIGHTS_{set}"), &[Dimensions::Vec4], &weights)?;
        let ids: Vec<[u16; 4]> = reader.read_joints(set).map(|r| r.into_u16().collect()).unwrap_or_default();
        let ws: Vec<[f32; 4]> = reader.read_weights(set).map(|r| r.into_f32().collect()).unwrap_or_default();
        if ids.len() != positions.len() || ws.len() != positions.len() {
            return Err(format!("{what}: JOINTS_{set} or WEIGHTS_{set} does not give one element per vertex"));
        }
        for (b, (ids, ws)) in blended.iter_mut().zip(ids.iter().zip(&ws)) {
            for (&joint, &weight) in ids.iter().zip(ws) {
                // Joint indices are checked against the skin (`rules::check_data`).
                let m = joints.get(usize::from(joint)).copied().unwrap_or(DMat4::ZERO);
                *b += m * f64::from(weight);
            }
        }
    }
    for (p, b) in positions.iter_mut().zip(&blended) {
        *p = b.transform_point3(*p);
    }
    if let Some(normals) = normals {
        for (n, b) in normals.iter_mut().zip(&blended) {
            let m = DMat3::from_mat4(*b);
            // A matrix with no inverse (weights summing to 0) leaves no normal to speak of: the
            // geometry's check of the normals then falls back to flat ones.
            *n = m.inverse().transpose() * *n;
        }
    }
    Ok(())
}
