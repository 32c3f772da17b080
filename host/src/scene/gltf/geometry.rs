//! A glTF primitive's triangles as a twinray mesh. Every accessor is checked before it is
//! read (`accessors`), so a malformed file is refused with the accessor named, never read out
//! of bounds.

use super::super::mesh::{checked, with_attributes, with_normals, MeshData, Polyhedron};
use super::super::shape::Normals;
use super::accessors::check;
use super::deform::Pose;
use super::quantized::{self, check_attribute, Attribute};
use super::shared::{kept, As, Decoded};
use glam::{Vec3, Vec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use std::rc::Rc;
use twinray_shared::layout::Vertex;

/// What became of a primitive.
pub enum Outcome {
    Mesh(MeshData),
    /// Not made of triangles (points or lines): its mode, for the notice.
    NotTriangles(Mode),
}

/// The triangles of `primitive` (`what` names it in errors), posed by `pose` where a node
/// morphs or skins it, with the file's normals where it has usable ones and flat normals
/// where it does not; `bad_normals` is set when it had normals that were not finite or had
/// no length. Its vertex accessors are read through `decoded` (once per model), and only the
/// vertices its indices name are kept.
pub fn primitive(
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    (decoded, pose): (&mut Decoded, Option<&Pose>),
    what: &str,
    bad_normals: &mut bool,
) -> Result<Outcome, String> {
    let mode = primitive.mode();
    if matches!(mode, Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip) {
        return Ok(Outcome::NotTriangles(mode));
    }
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    let position = primitive.get(&gltf::Semantic::Positions).ok_or_else(|| format!("{what} has no POSITION"))?;
    let quantized = decoded.quantized;
    let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
    let vec3s = |a: &gltf::Accessor, semantic: &str, attribute| {
        check_attribute(a, buffers, (what, semantic), attribute, quantized)?;
        let read: Vec<Vec4> = quantized::read::<3, _>(a, get).into_iter().map(|p| Vec3::from(p).extend(0.0)).collect();
        read_all(read.len(), a, what, semantic)?;
        Ok(read)
    };
    let all = decoded.get(position.index(), As::Position, || vec3s(&position, "POSITION", Attribute::Position))?;
    let count = all.len();
    let mut order = indices(primitive, &reader, buffers, count, what)?;
    // Every attribute, modelled or not, has one element per vertex (the glTF validator's rule):
    // with fewer, which value would the others get?
    for (semantic, accessor) in primitive.attributes() {
        same_count(accessor.count(), count, what, &semantic.to_string())?;
    }
    let normals = match primitive.get(&gltf::Semantic::Normals) {
        Some(n) => Some(decoded.get(n.index(), As::Normal, || vec3s(&n, "NORMAL", Attribute::Normal))?),
        None => None,
    };
    let (all, normals) = match pose {
        Some(pose) => {
            let (p, n) =
                pose.apply(primitive, (buffers, quantized), (&all, normals.as_deref().map(Vec::as_slice)), what)?;
            (Rc::new(p), n.map(Rc::new))
        }
        None => (all, normals),
    };
    let used = decoded.compact(&mut order, count);
    let used = used.as_deref();
    // Each list is dropped once read and none is copied whole: for a primitive of two million
    // triangles (a 48 MB file), holding the indices, the attributes and the Vec4s twice takes
    // the load's peak from 175 MB to 288 MB.
    let p = Polyhedron { positions: kept_xyz(&all, used), triangles: triangles(mode, order) };
    checked(&p, what)?;
    let normals = normals.and_then(|all| {
        let normals = kept_xyz(&all, used);
        let usable = normals.iter().all(|n| n.is_finite() && n.length() > 1e-6);
        *bad_normals |= !usable;
        usable.then_some(normals)
    });
    let attributes = attributes(primitive, buffers, decoded, (count, used), what)?;
    let mesh = match normals {
        Some(normals) => {
            let at = |k: usize| attributes.as_ref().map_or((Vec4::ZERO, Vec4::ONE), |a| a[k]);
            let vertices = (p.positions.iter().zip(&normals).enumerate())
                .map(|(k, (p, n))| {
                    let (uv, color) = at(k);
                    Vertex { normal: n.normalize().extend(0.0), uv, color, ..Vertex::at(*p) }
                })
                .collect();
            drop((normals, p.positions));
            MeshData { vertices, indices: flat_indices(p.triangles) }
        }
        None => {
            let mesh = with_normals(&p, Normals::Flat);
            match attributes {
                Some(attributes) => with_attributes(mesh, &p, &attributes, true),
                None => mesh,
            }
        }
    };
    Ok(Outcome::Mesh(mesh))
}

/// The xyz of the elements of `all` that `used` keeps (all of them where it is `None`).
fn kept_xyz(all: &[Vec4], used: Option<&[u32]>) -> Vec<Vec3> {
    kept(all, used).map(Vec4::truncate).collect()
}

/// Triangles' corners end to end, in the same allocation.
fn flat_indices(triangles: Vec<[u32; 3]>) -> Vec<u32> {
    bytemuck::allocation::cast_vec(triangles)
}

/// The vertex order of `primitive`: its indices (checked: in range, no restart value), or
/// its `count` vertices in turn.
fn indices<'a, 's, F>(
    primitive: &gltf::Primitive,
    reader: &gltf::mesh::Reader<'a, 's, F>,
    buffers: &[Vec<u8>],
    count: usize,
    what: &str,
) -> Result<Vec<u32>, String>
where
    F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
{
    let Some(indices) = primitive.indices() else { return Ok((0..count as u32).collect()) };
    check(&indices, buffers, what, "indices", &[Dimensions::Scalar], &[DataType::U8, DataType::U16, DataType::U32])?;
    let order: Vec<u32> = reader.read_indices().map(|i| i.into_u32().collect()).unwrap_or_default();
    read_all(order.len(), &indices, what, "indices")?;
    if let Some(i) = order.iter().find(|&&i| i as usize >= count) {
        return Err(format!("{what} indexes vertex {i}, past its {count} vertices"));
    }
    // The largest value of the index type restarts a strip in other APIs: glTF forbids it.
    let bits = 8 * indices.data_type().size();
    let restart = u32::MAX >> (32 - bits);
    if order.contains(&restart) {
        return Err(format!(
            "{what}: indices (accessor {}) hold {restart}, the primitive restart value of {bits}-bit indices, which glTF forbids",
            indices.index()
        ));
    }
    Ok(order)
}

/// Each kept vertex's texture coordinates (TEXCOORD_0 in xy, TEXCOORD_1 in zw; 0 where
/// absent) and colour (COLOR_0, alpha 1 for RGB; white where absent), normalized integers as
/// floats; the accessors hold `count` vertices, of which `used` are kept. `None` where the
/// primitive has none of these (every vertex's are the defaults).
fn attributes(
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    decoded: &mut Decoded,
    (count, used): (usize, Option<&[u32]>),
    what: &str,
) -> Result<Option<Vec<(Vec4, Vec4)>>, String> {
    let named = [gltf::Semantic::TexCoords(0), gltf::Semantic::TexCoords(1), gltf::Semantic::Colors(0)];
    if named.iter().all(|s| primitive.get(s).is_none()) {
        return Ok(None);
    }
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    let mut out = vec![(Vec4::ZERO, Vec4::ONE); used.map_or(count, <[u32]>::len)];
    let normalized = [DataType::F32, DataType::U8, DataType::U16];
    for set in 0..2u32 {
        let semantic = format!("TEXCOORD_{set}");
        let Some(a) = primitive.get(&gltf::Semantic::TexCoords(set)) else { continue };
        let quantized = decoded.quantized;
        let all = decoded.get(a.index(), As::TexCoord, || {
            check_attribute(&a, buffers, (what, &semantic), Attribute::TexCoord, quantized)?;
            let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
            let uv: Vec<Vec4> = quantized::read::<2, _>(&a, get)
                .into_iter()
                .map(|[u, v]| Vec4::new(finite(u), finite(v), 0.0, 0.0))
                .collect();
            read_all(uv.len(), &a, what, &semantic)?;
            Ok(uv)
        })?;
        for (o, uv) in out.iter_mut().zip(kept(&all, used)) {
            o.0 = if set == 0 { Vec4::new(uv.x, uv.y, o.0.z, o.0.w) } else { Vec4::new(o.0.x, o.0.y, uv.x, uv.y) };
        }
    }
    if let Some(a) = primitive.get(&gltf::Semantic::Colors(0)) {
        let all = decoded.get(a.index(), As::Color, || {
            check(&a, buffers, what, "COLOR_0", &[Dimensions::Vec3, Dimensions::Vec4], &normalized)?;
            let colors: Vec<Vec4> = reader
                .read_colors(0)
                .map(|c| c.into_rgba_f32().map(|c| Vec4::from(c.map(|x| finite(x).clamp(0.0, 1.0)))).collect())
                .unwrap_or_default();
            read_all(colors.len(), &a, what, "COLOR_0")?;
            Ok(colors)
        })?;
        for (o, c) in out.iter_mut().zip(kept(&all, used)) {
            o.1 = c;
        }
    }
    Ok(Some(out))
}

/// A non-finite attribute value as 0: a texture coordinate of NaN would sample nothing
/// defined, and the two sets would differ on it.
fn finite(x: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

fn same_count(read: usize, positions: usize, what: &str, semantic: &str) -> Result<(), String> {
    if read != positions {
        return Err(format!("{what}: {semantic} has {read} elements, its POSITION {positions}"));
    }
    Ok(())
}

/// The triangles of a triangle list, strip or fan, as the spec orders them; a list's in the
/// allocation of its indices.
fn triangles(mode: Mode, mut order: Vec<u32>) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (2..order.len())
            .map(|i| {
                let (a, b, c) = (order[i - 2], order[i - 1], order[i]);
                if i % 2 == 0 {
                    [a, b, c]
                } else {
                    [b, a, c]
                }
            })
            .collect(),
        Mode::TriangleFan => (2..order.len()).map(|i| [order[i - 1], order[i], order[0]]).collect(),
        _ => {
            order.truncate(order.len() / 3 * 3);
            order.shrink_to_fit();
            bytemuck::allocation::try_cast_vec(order)
                .unwrap_or_else(|(_, order)| order.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
        }
    }
}

/// That `read` elements came out of accessor `a`: all of them, or the data was not there.
fn read_all(read: usize, a: &gltf::Accessor, what: &str, semantic: &str) -> Result<(), String> {
    if read != a.count() {
        return Err(format!(
            "{what}: {semantic} (accessor {}) gave {read} of its {} elements: its data is missing or out of bounds",
            a.index(),
            a.count()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_become_triangles_as_the_spec_orders_them() {
        assert_eq!(triangles(Mode::Triangles, vec![0, 1, 2, 3, 4, 5, 6]), [[0, 1, 2], [3, 4, 5]]);
        assert_eq!(triangles(Mode::TriangleStrip, vec![0, 1, 2, 3]), [[0, 1, 2], [2, 1, 3]]);
        assert_eq!(triangles(Mode::TriangleFan, vec![0, 1, 2, 3]), [[1, 2, 0], [2, 3, 0]]);
        assert!(triangles(Mode::TriangleFan, vec![0, 1]).is_empty());
    }
}
