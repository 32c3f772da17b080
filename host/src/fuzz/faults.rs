//! Edits that break a rule glTF sets between two fields, which edits of one value at random
//! seldom hit: a buffer view's stride below the element of an accessor that reads through it,
//! an accessor's offset that is not a multiple of its component, and an embedded PNG whose
//! header claims a huge image (a decompression bomb), an embedded PNG given metadata chunks,
//! the node graph's rules (`super::graph_faults`) and the rules on morphs, skins, animations,
//! cameras and accessors (`super::rig_faults`). Part of the `gltf` fuzz target's mutator
//! (`super::mutate`).

use super::rng::Rng;
use serde_json::Value;

/// Bytes of one component of glTF's `componentType`; 0 for a value glTF does not define.
fn component_bytes(component_type: u64) -> u64 {
    match component_type {
        5120 | 5121 => 1,
        5122 | 5123 => 2,
        5125 | 5126 => 4,
        _ => 0,
    }
}

/// Components of one element of an accessor `type`; 0 for a name glTF does not define.
fn components(kind: &str) -> u64 {
    match kind {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        "VEC4" | "MAT2" => 4,
        "MAT3" => 9,
        "MAT4" => 16,
        _ => 0,
    }
}

/// Breaks one such rule in `doc` or in `bin` (a GLB's binary chunk); false where the file has
/// nothing to break it on (no accessor with a view, no PNG).
pub fn break_rule(doc: &mut Value, bin: Option<&mut Vec<u8>>, rng: &mut Rng) -> bool {
    match rng.below(6) {
        0 => short_stride(doc, rng),
        1 => misaligned_offset(doc, rng),
        2 => bin.is_some_and(|b| huge_png(b, rng)),
        3 => bin.is_some_and(|b| metadata_chunk(b, rng)),
        4 => super::graph_faults::break_rule(doc, rng),
        _ => super::rig_faults::break_rule(doc, rng),
    }
}

/// A random accessor that reads through a buffer view: (its index, the view's, its
/// component's bytes, its element's bytes).
fn accessor_with_view(doc: &Value, rng: &mut Rng) -> Option<(usize, usize, u64, u64)> {
    let accessors = doc.get("accessors")?.as_array()?;
    let i = rng.below(accessors.len());
    let a = accessors.get(i)?;
    let view = a.get("bufferView")?.as_u64()? as usize;
    let component = component_bytes(a.get("componentType")?.as_u64()?);
    let element = component * components(a.get("type")?.as_str()?);
    (component > 0).then_some((i, view, component, element))
}

fn short_stride(doc: &mut Value, rng: &mut Rng) -> bool {
    let Some((_, view, _, element)) = accessor_with_view(doc, rng) else { return false };
    // Strides glTF allows (4 to 252, multiples of 4) below the element where there are any.
    let stride = if element > 4 { 4 * (1 + rng.below(((element - 1) / 4) as usize) as u64) } else { 1 };
    let Some(target) = doc.pointer_mut(&format!("/bufferViews/{view}")).and_then(Value::as_object_mut) else {
        return false;
    };
    target.insert("byteStride".into(), Value::from(stride));
    true
}

fn misaligned_offset(doc: &mut Value, rng: &mut Rng) -> bool {
    let Some((i, _, component, _)) = accessor_with_view(doc, rng) else { return false };
    let offset = component * rng.below(4) as u64 + 1 + rng.below(component.max(2) as usize - 1) as u64;
    let Some(target) = doc.pointer_mut(&format!("/accessors/{i}")).and_then(Value::as_object_mut) else {
        return false;
    };
    target.insert("byteOffset".into(), Value::from(offset));
    true
}

/// A PNG's header (IHDR) in `bin` made to claim a width and height up to 2^30 each, its
/// checksum made right again, as a bomb's is.
fn huge_png(bin: &mut [u8], rng: &mut Rng) -> bool {
    let Some(at) = bin.windows(4).position(|w| w == b"IHDR") else { return false };
    if bin.len() < at + 21 {
        return false;
    }
    let side = |rng: &mut Rng| [16384u32, 65535, 1 << 20, 1 << 30][rng.below(4)].to_be_bytes();
    let (w, h) = (side(rng), side(rng));
    bin[at + 4..at + 8].copy_from_slice(&w);
    bin[at + 8..at + 12].copy_from_slice(&h);
    // The chunk's CRC-32 covers its type and its 13 bytes of data.
    let crc = crc32(&bin[at..at + 17]);
    bin[at + 17..at + 21].copy_from_slice(&crc.to_be_bytes());
    true
}

/// An ancillary chunk inserted after a PNG's header (IHDR) in `bin`: a colour profile, text
/// (plain or compressed), or EXIF, its compressed parts a stored zlib stream of random bytes
/// (or, one time in four, not a zlib stream at all). The decoder never sees them: the loader
/// passes a PNG's picture chunks only (`scene::texture`). A GLB's chunk lengths are made right
/// by the caller (`mutate::join`), but buffer views past the PNG now point a little off, as
/// edits of the binary chunk do.
fn metadata_chunk(bin: &mut Vec<u8>, rng: &mut Rng) -> bool {
    let Some(at) = bin.windows(4).position(|w| w == b"IHDR") else { return false };
    let end = at + 4 + 13 + 4;
    if bin.len() < end || at < 4 {
        return false;
    }
    let kind: &[u8; 4] = [b"iCCP", b"zTXt", b"iTXt", b"tEXt", b"eXIf"][rng.below(5)];
    let payload: Vec<u8> = (0..1 + rng.below(64)).map(|_| rng.word() as u8).collect();
    let mut body = b"profile\0\0".to_vec();
    if rng.below(4) == 0 {
        body.extend(&payload);
    } else {
        // A stored block (BFINAL, BTYPE 00), LEN and NLEN, the bytes, their Adler-32.
        let len = payload.len() as u16;
        body.extend([0x78, 0x01, 0x01]);
        body.extend(len.to_le_bytes());
        body.extend((!len).to_le_bytes());
        body.extend(&payload);
        let (a, b) = payload.iter().fold((1u32, 0u32), |(a, b), &x| {
            let a = (a + u32::from(x)) % 65521;
            (a, (b + a) % 65521)
        });
        body.extend(((b << 16) | a).to_be_bytes());
    }
    let mut chunk = (body.len() as u32).to_be_bytes().to_vec();
    chunk.extend(kind);
    chunk.extend(&body);
    let crc = crc32(&chunk[4..]);
    chunk.extend(crc.to_be_bytes());
    bin.splice(end..end, chunk);
    true
}

/// CRC-32 (ISO 3309, as PNG uses it), bit by bit: a header's 17 bytes need no table.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_is_broken_where_the_file_has_what_it_needs() {
        let doc = r#"{"bufferViews": [{"buffer": 0, "byteLength": 48}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 4}]}"#;
        let doc: Value = serde_json::from_str(doc).unwrap();
        let (mut strides, mut offsets) = (Vec::new(), Vec::new());
        for seed in 0..64 {
            let mut d = doc.clone();
            assert!(short_stride(&mut d, &mut Rng::new(seed)));
            strides.push(d["bufferViews"][0]["byteStride"].as_u64().unwrap());
            let mut d = doc.clone();
            assert!(misaligned_offset(&mut d, &mut Rng::new(seed)));
            offsets.push(d["accessors"][0]["byteOffset"].as_u64().unwrap());
        }
        assert!(strides.iter().all(|&s| s < 12 && s % 4 == 0), "{strides:?}");
        assert!(offsets.iter().all(|&o| o % 4 != 0), "{offsets:?}");
        let mut png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x02\0\0\0\x02\x08\x06\0\0\0\0\0\0\0".to_vec();
        assert!(huge_png(&mut png, &mut Rng::new(1)));
        let width = u32::from_be_bytes(png[16..20].try_into().unwrap());
        assert!(width >= 16384, "{width}");
        assert!(!huge_png(&mut [0u8; 16], &mut Rng::new(1)));
        // A metadata chunk after the header, which the decoder's path drops again.
        let mut picture = Vec::new();
        image::GrayImage::new(2, 2).write_to(&mut std::io::Cursor::new(&mut picture), image::ImageFormat::Png).unwrap();
        for seed in 0..16 {
            let mut with = picture.clone();
            assert!(metadata_chunk(&mut with, &mut Rng::new(seed)));
            assert!(with.len() > picture.len());
            let mut budget = u64::MAX;
            let decoded = crate::scene::texture::decode("m.png", &with, false, &mut budget).unwrap();
            assert_eq!((decoded.width, decoded.height), (2, 2));
        }
        // The standard check value of CRC-32.
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }
}
