//! KHR_mesh_quantization: vertex attributes stored as integers. A file that declares it may
//! give `POSITION` as bytes or shorts, signed or not, normalized or not (a morph target's
//! position displacements signed only); `NORMAL` (and its displacements) as normalized signed
//! bytes or shorts; `TEXCOORD_n` as bytes or shorts of either sign, normalized or not. Each value is
//! read as glTF says: normalized signed integers as `max(c / max, -1)`, unsigned as
//! `c / max`, others as the integer itself (a node's scale and offset then place them). A
//! file that does not declare the extension may use only what glTF itself allows.

use super::accessors::check;
use gltf::accessor::{DataType, Dimensions};

pub const EXTENSION: &str = "KHR_mesh_quantization";

/// Which attribute an accessor holds, for the types it may have.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Attribute {
    Position,
    /// A morph target's position displacements: signed only.
    Displacement,
    Normal,
    TexCoord,
}

/// The component types `attribute` may have, and whether each must be normalized (`Some`)
/// or may be either (`None`).
fn allowed(attribute: Attribute, quantized: bool) -> Vec<(DataType, Option<bool>)> {
    use DataType::{F32, I16, I8, U16, U8};
    let mut types = vec![(F32, Some(false))];
    match (attribute, quantized) {
        (Attribute::TexCoord, false) => types.extend([(U8, Some(true)), (U16, Some(true))]),
        (Attribute::Position | Attribute::TexCoord, true) => {
            types.extend([(I8, None), (U8, None), (I16, None), (U16, None)])
        }
        (Attribute::Displacement, true) => types.extend([(I8, None), (I16, None)]),
        (Attribute::Normal, true) => types.extend([(I8, Some(true)), (I16, Some(true))]),
        (_, false) => {}
    }
    types
}

/// Checks accessor `a` as `accessors::check` does, of the types `attribute` may have in a
/// file that does (`quantized`) or does not declare the extension, normalized where it must
/// be; `what` and `semantic` name it in the error.
pub fn check_attribute(
    a: &gltf::Accessor,
    buffers: &[Vec<u8>],
    (what, semantic): (&str, &str),
    attribute: Attribute,
    quantized: bool,
) -> Result<(), String> {
    let dimensions = if attribute == Attribute::TexCoord { Dimensions::Vec2 } else { Dimensions::Vec3 };
    let types = allowed(attribute, quantized);
    let data_types: Vec<DataType> = types.iter().map(|t| t.0).collect();
    check(a, buffers, what, semantic, &[dimensions], &data_types)?;
    let must = types.iter().find(|t| t.0 == a.data_type()).and_then(|t| t.1);
    if must.is_some_and(|n| n != a.normalized()) {
        let said = if a.normalized() { "normalized" } else { "not normalized" };
        let more = if quantized { "" } else { " (KHR_mesh_quantization allows more)" };
        return Err(format!(
            "{what}: {semantic} (accessor {}) is {:?} {said}, which glTF does not allow there{more}",
            a.index(),
            a.data_type()
        ));
    }
    Ok(())
}

/// The elements of accessor `a` (checked), `N` components each, as floats.
pub fn read<'a, 's, const N: usize, F>(a: &gltf::Accessor<'a>, get: F) -> Vec<[f32; N]>
where
    F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
    [f32; N]: gltf::accessor::Item,
    [i8; N]: gltf::accessor::Item,
    [u8; N]: gltf::accessor::Item,
    [i16; N]: gltf::accessor::Item,
    [u16; N]: gltf::accessor::Item,
{
    let normalized = a.normalized();
    fn each<'a, 's, T, const N: usize, F>(a: &gltf::Accessor<'a>, get: F, f: impl Fn(T) -> f32) -> Vec<[f32; N]>
    where
        F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
        [T; N]: gltf::accessor::Item,
    {
        let items = gltf::accessor::Iter::<[T; N]>::new(a.clone(), get).into_iter().flatten();
        items.map(|v| v.map(&f)).collect()
    }
    let scaled = |max: f32| move |c: f32| if normalized { (c / max).max(-1.0) } else { c };
    match a.data_type() {
        DataType::I8 => each(a, get, |c: i8| scaled(127.0)(f32::from(c))),
        DataType::U8 => each(a, get, |c: u8| scaled(255.0)(f32::from(c))),
        DataType::I16 => each(a, get, |c: i16| scaled(32767.0)(f32::from(c))),
        DataType::U16 => each(a, get, |c: u16| scaled(65535.0)(f32::from(c))),
        _ => each(a, get, |c: f32| c),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_attribute_allows_the_types_of_gltf_and_of_the_extension() {
        let has = |attribute, quantized, t, normalized: bool| {
            allowed(attribute, quantized).iter().any(|&(a, n)| a == t && n.is_none_or(|n| n == normalized))
        };
        assert!(has(Attribute::Position, false, DataType::F32, false));
        assert!(!has(Attribute::Position, false, DataType::I16, false));
        assert!(
            has(Attribute::Position, true, DataType::I16, false) && has(Attribute::Position, true, DataType::U8, true)
        );
        assert!(has(Attribute::Normal, true, DataType::I8, true) && !has(Attribute::Normal, true, DataType::I8, false));
        assert!(!has(Attribute::Normal, true, DataType::U8, true));
        assert!(
            has(Attribute::Displacement, true, DataType::I8, false)
                && !has(Attribute::Displacement, true, DataType::U16, false)
        );
        assert!(!has(Attribute::Displacement, false, DataType::I8, false));
        assert!(
            has(Attribute::TexCoord, false, DataType::U16, true)
                && !has(Attribute::TexCoord, false, DataType::I16, true)
        );
        assert!(
            has(Attribute::TexCoord, true, DataType::I16, false) && has(Attribute::TexCoord, true, DataType::U8, false)
        );
    }
}
