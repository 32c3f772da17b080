//! Accessors checked before they are read: every element within its buffer view, the view
//! within its buffer, components aligned, sparse indices rising within the accessor. The
//! `gltf` crate's reader assumes all that (and panics on a stride shorter than an element), so
//! a malformed file is refused with the accessor named, never read out of bounds.

use crate::scene::mesh::MAX_MESH_TRIANGLES;
use gltf::accessor::{DataType, Dimensions};

/// Most elements one accessor may have: three vertices per triangle of the largest mesh.
const MAX_ELEMENTS: usize = 3 * MAX_MESH_TRIANGLES;

/// An accessor of a type `semantic` allows, with a count twinray takes, whose every element
/// lies within its buffer view at a stride no shorter than the element and an offset its
/// components align to, whose view lies within its buffer, and whose sparse indices (if any)
/// rise strictly within its count: all that the glTF spec asks of an accessor and the `gltf`
/// crate's reader assumes (it panics on a stride shorter than the element).
pub fn check(
    a: &gltf::Accessor,
    buffers: &[Vec<u8>],
    what: &str,
    semantic: &str,
    dimensions: &[Dimensions],
    types: &[DataType],
) -> Result<(), String> {
    let name = format!("{what}: {semantic} (accessor {})", a.index());
    if !dimensions.contains(&a.dimensions()) || !types.contains(&a.data_type()) {
        return Err(format!("{name} is {:?} of {:?}, which glTF does not allow there", a.dimensions(), a.data_type()));
    }
    if a.count() == 0 || a.count() > MAX_ELEMENTS {
        return Err(format!("{name} has {} elements (1 to {MAX_ELEMENTS})", a.count()));
    }
    let component = a.data_type().size();
    if let Some(sparse) = a.sparse() {
        let count = sparse.count();
        if count == 0 || count > a.count() {
            return Err(format!("{name} has {count} sparse elements (1 to its {} elements)", a.count()));
        }
        let (indices, values) = (sparse.indices(), sparse.values());
        let index_size = indices.index_type().size();
        within(&indices.view(), (indices.offset(), index_size), count, index_size, &name)?;
        within(&values.view(), (values.offset(), component), count, a.size(), &name)?;
        sparse_indices_rise(&indices, buffers, (count, a.count()), &name)?;
    }
    match a.view() {
        Some(view) => within(&view, (a.offset(), component), a.count(), a.size(), &name),
        None => Ok(()), // all zeros, or sparse only
    }
}

/// That `count` elements of `size` bytes from `offset` in `view` (at its stride, which is
/// no shorter than an element) lie within the view, and the view within its buffer; and that
/// the offset, in the view and in the buffer, is a multiple of the `align` bytes of a
/// component.
fn within(
    view: &gltf::buffer::View,
    (offset, align): (usize, usize),
    count: usize,
    size: usize,
    name: &str,
) -> Result<(), String> {
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "{name}: buffer view {} has a byteStride of {stride}, less than its {size}-byte elements",
            view.index()
        ));
    }
    if !offset.is_multiple_of(align) || !view.offset().wrapping_add(offset).is_multiple_of(align) {
        let at = view.offset().wrapping_add(offset);
        return Err(format!(
            "{name} starts at byte {offset} of buffer view {} (byte {at} of its buffer), not a multiple of its {align}-byte components",
            view.index()
        ));
    }
    let end = (count - 1).checked_mul(stride).and_then(|n| n.checked_add(offset)).and_then(|n| n.checked_add(size));
    if end.is_none_or(|end| end > view.length()) {
        return Err(format!("{name} reaches past the end of its buffer view {}", view.index()));
    }
    if view.offset().checked_add(view.length()).is_none_or(|end| end > view.buffer().length()) {
        return Err(format!("{name}: buffer view {} reaches past the end of its buffer", view.index()));
    }
    Ok(())
}

/// That the `count` sparse indices of an accessor of `elements` elements rise strictly and
/// stay below `elements`, as the glTF spec asks (the reader would write past the accessor or
/// substitute in an order the file did not mean). They lie within their view (`within`).
fn sparse_indices_rise(
    indices: &gltf::accessor::sparse::Indices,
    buffers: &[Vec<u8>],
    (count, elements): (usize, usize),
    name: &str,
) -> Result<(), String> {
    let view = indices.view();
    let size = indices.index_type().size();
    let start = view.offset() + indices.offset();
    let bytes = buffers.get(view.buffer().index()).and_then(|b| b.get(start..start + count * size));
    let bytes = bytes.ok_or_else(|| format!("{name}: its sparse indices lie past its buffer"))?;
    let mut last = None;
    for (k, chunk) in bytes.chunks_exact(size).enumerate() {
        let index = chunk.iter().rev().fold(0usize, |v, &b| (v << 8) | usize::from(b));
        if index >= elements {
            return Err(format!("{name}: sparse index {k} is {index}, past its {elements} elements"));
        }
        if last.is_some_and(|last| index <= last) {
            return Err(format!(
                "{name}: sparse index {k} is {index}, not above the one before (they must rise strictly)"
            ));
        }
        last = Some(index);
    }
    Ok(())
}
