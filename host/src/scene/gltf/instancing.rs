//! `EXT_mesh_gpu_instancing`: a node that draws its mesh many times, each copy placed by its
//! own translation, rotation and scale (one element each of the extension's accessors),
//! applied before the node's world transform. Each copy becomes an object of its own (a TLAS
//! instance sharing the mesh's BLAS), as the extension means it.

use super::accessors::check;
use super::quantized::{self, check_attribute, Attribute};
use glam::{Mat4, Quat, Vec3};
use gltf::accessor::{DataType, Dimensions};

pub const EXTENSION: &str = "EXT_mesh_gpu_instancing";

/// The world matrices of `node`'s copies, its world matrix being `world`: one per element of
/// its instancing accessors, `None` where it has no `EXT_mesh_gpu_instancing`. The accessors
/// are checked as the extension asks (types, one count for all) and against their views.
pub fn copies(
    node: &gltf::Node,
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    world: Mat4,
) -> Result<Option<Vec<Mat4>>, String> {
    let Some(ext) = node.extension_value(EXTENSION) else { return Ok(None) };
    let what = format!("node {}: {EXTENSION}", node.index());
    let attributes =
        ext.get("attributes").and_then(|a| a.as_object()).ok_or_else(|| format!("{what} has no attributes"))?;
    let accessor = |name: &str| -> Result<Option<gltf::Accessor>, String> {
        let Some(index) = attributes.get(name) else { return Ok(None) };
        let index = index.as_u64().ok_or_else(|| format!("{what}: {name} is not an accessor index"))? as usize;
        doc.accessors()
            .nth(index)
            .map(Some)
            .ok_or_else(|| format!("{what}: {name} names accessor {index}, past the list"))
    };
    let (t, r, s) = (accessor("TRANSLATION")?, accessor("ROTATION")?, accessor("SCALE")?);
    let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
    // With KHR_mesh_quantization, translations and scales may be signed bytes or shorts,
    // normalized or not: the types of a morph target's displacements.
    let quantized = doc.extensions_used().any(|e| e == super::quantized::EXTENSION);
    let vec3s = |a: &gltf::Accessor, semantic: &str| -> Result<Vec<Vec3>, String> {
        check_attribute(a, buffers, (&what, semantic), Attribute::Displacement, quantized)?;
        Ok(all_read(quantized::read::<3, _>(a, get), a, &what)?.into_iter().map(Vec3::from).collect())
    };
    let count = [&t, &r, &s].into_iter().flatten().map(|a| a.count()).next();
    let Some(count) = count else { return Err(format!("{what} has none of TRANSLATION, ROTATION and SCALE")) };
    if let Some(a) = [&t, &r, &s].into_iter().flatten().find(|a| a.count() != count) {
        return Err(format!(
            "{what}: accessor {} has {} elements, its other attributes {count} (one each)",
            a.index(),
            a.count()
        ));
    }
    let mut translations = vec![Vec3::ZERO; count];
    if let Some(a) = &t {
        translations = vec3s(a, "TRANSLATION")?;
    }
    let mut scales = vec![Vec3::ONE; count];
    if let Some(a) = &s {
        scales = vec3s(a, "SCALE")?;
    }
    let mut rotations = vec![Quat::IDENTITY; count];
    if let Some(a) = &r {
        check(a, buffers, &what, "ROTATION", &[Dimensions::Vec4], &[DataType::F32, DataType::I8, DataType::I16])?;
        rotations = rotations_of(a, get, &what)?;
    }
    let copies = (0..count)
        .map(|i| world * Mat4::from_scale_rotation_translation(scales[i], rotations[i], translations[i]))
        .collect();
    Ok(Some(copies))
}

/// Unit quaternions from `a`: floats, or normalized signed bytes or shorts (the extension's
/// three types), normalized again where a file's are not quite unit; a quaternion that is not
/// finite or has no length is an error.
fn rotations_of<'a, 's, F>(a: &gltf::Accessor<'a>, get: F, what: &str) -> Result<Vec<Quat>, String>
where
    F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
{
    let raw: Vec<[f32; 4]> = match a.data_type() {
        DataType::I8 => iter::<[i8; 4], _>(a, get).map(|q| q.map(|c| (f32::from(c) / 127.0).max(-1.0))).collect(),
        DataType::I16 => iter::<[i16; 4], _>(a, get).map(|q| q.map(|c| (f32::from(c) / 32767.0).max(-1.0))).collect(),
        _ => iter::<[f32; 4], _>(a, get).collect(),
    };
    let raw = all_read(raw, a, what)?;
    raw.into_iter()
        .enumerate()
        .map(|(i, q)| {
            let q = Quat::from_array(q);
            let length = q.length();
            if length.is_finite() && length > 1e-6 {
                Ok(q / length)
            } else {
                Err(format!("{what}: ROTATION {i} (accessor {}) is {q}, not a rotation", a.index()))
            }
        })
        .collect()
}

fn iter<'a, 's, T: gltf::accessor::Item + 's, F>(a: &gltf::Accessor<'a>, get: F) -> impl Iterator<Item = T> + 's
where
    F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
{
    gltf::accessor::Iter::<T>::new(a.clone(), get).into_iter().flatten()
}

fn all_read<T>(read: Vec<T>, a: &gltf::Accessor, what: &str) -> Result<Vec<T>, String> {
    if read.len() == a.count() {
        Ok(read)
    } else {
        Err(format!("{what}: accessor {} gave {} of its {} elements", a.index(), read.len(), a.count()))
    }
}
