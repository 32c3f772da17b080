//! The `gltf` fuzz target's structure-aware mutator: a glTF file is a JSON document and, in a
//! GLB, a binary chunk, so a mutation edits one of the two and writes the container back
//! whole (chunk lengths and padding right). Byte flips alone spend nearly every input on JSON
//! that no longer parses; these reach the loader's checks of counts, offsets, strides,
//! indices, URIs and images. The same mutator drives libFuzzer (`fuzz/fuzz_targets/gltf.rs`)
//! and, from a fixed seed, the short run that `cargo test` makes (`app/tests/fuzz_seeds.rs`).

pub use super::rng::Rng;
use serde_json::{Map, Value};

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Numbers a loader must treat with care: limits of the integer types, glTF's component and
/// target enums, and values no count or offset should hold.
const NUMBERS: &[f64] = &[
    0.0,
    1.0,
    -1.0,
    2.0,
    3.0,
    4.0,
    7.0,
    255.0,
    256.0,
    65535.0,
    65536.0,
    2147483647.0,
    4294967295.0,
    4294967296.0,
    1e9,
    1e30,
    -1e30,
    0.5,
    1e-30,
    18446744073709551615.0,
    5120.0,
    5121.0,
    5122.0,
    5123.0,
    5125.0,
    5126.0,
    34962.0,
    34963.0,
];

/// Strings that change what an accessor, image or URI means, or lead out of the model's folder.
const STRINGS: &[&str] = &[
    "SCALAR",
    "VEC2",
    "VEC3",
    "VEC4",
    "MAT2",
    "MAT3",
    "MAT4",
    "",
    "../model.bin",
    "../../etc/hostname",
    "/etc/hostname",
    "..",
    "sub/../../x.bin",
    "%2e%2e/x.bin",
    "file:///etc/hostname",
    "data:application/octet-stream;base64,AAAAAAAAAAAAAAAA",
    "data:image/png;base64,iVBORw0KGgo=",
    "image/png",
    "image/jpeg",
    "image/webp",
    "KHR_texture_transform",
    "KHR_materials_emissive_strength",
    "KHR_draco_mesh_compression",
    "OPAQUE",
    "MASK",
    "BLEND",
];

/// Keys of the glTF schema a mutation may add where they were absent.
const KEYS: &[&str] = &[
    "byteStride",
    "byteOffset",
    "byteLength",
    "count",
    "sparse",
    "indices",
    "values",
    "uri",
    "bufferView",
    "componentType",
    "normalized",
    "type",
    "min",
    "max",
    "extras",
    "extensions",
    "mode",
    "material",
    "targets",
    "matrix",
    "translation",
    "rotation",
    "scale",
    "children",
    "mesh",
    "source",
    "sampler",
    "texCoord",
    "alphaMode",
    "alphaCutoff",
    "mimeType",
];

/// A glTF file's two parts: its JSON and, in a GLB, its binary chunk (`None` for a .gltf).
pub fn split(bytes: &[u8]) -> Option<(Vec<u8>, Option<Vec<u8>>)> {
    if !bytes.starts_with(GLB_MAGIC) {
        return Some((bytes.to_vec(), None));
    }
    let word = |at: usize| Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
    let json_len = word(12)? as usize;
    (word(16)? == CHUNK_JSON).then_some(())?;
    let json = bytes.get(20..20usize.checked_add(json_len)?)?.to_vec();
    let bin_at = 20 + json_len;
    let bin = match (word(bin_at), word(bin_at + 4)) {
        (Some(len), Some(CHUNK_BIN)) => bytes.get(bin_at + 8..bin_at + 8 + len as usize)?.to_vec(),
        _ => Vec::new(),
    };
    Some((json, Some(bin)))
}

/// A GLB of `json` and `bin`, each chunk padded to 4 bytes as the format requires.
pub fn join(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + if bin.is_empty() { 0 } else { 8 + bin_len };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(GLB_MAGIC);
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_len as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    out.extend_from_slice(json);
    out.resize(out.len() + pad(json.len()), b' ');
    if !bin.is_empty() {
        out.extend_from_slice(&(bin_len as u32).to_le_bytes());
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(bin);
        out.resize(out.len() + pad(bin.len()), 0);
    }
    out
}

/// One mutation of a glTF file (JSON or GLB). Mostly an edit of one value of its JSON; one time
/// in five a rule between two fields broken (`super::faults`); else its binary chunk, or the
/// whole input when its JSON does not parse, goes to `bytes`, a byte-level mutator
/// (libFuzzer's own under the fuzzer, [`flip_bytes`] in the test).
pub fn gltf(input: &[u8], rng: &mut Rng, bytes: &mut dyn FnMut(&mut Vec<u8>, &mut Rng)) -> Vec<u8> {
    let parsed = split(input).and_then(|(json, bin)| Some((serde_json::from_slice::<Value>(&json).ok()?, bin)));
    let Some((mut doc, bin)) = parsed else {
        let mut whole = input.to_vec();
        bytes(&mut whole, rng);
        return whole;
    };
    let mut bin = bin;
    let way = rng.below(5);
    if let (Some(chunk), 0) = (&mut bin, way) {
        bytes(chunk, rng);
    } else if way != 1 || !super::faults::break_rule(&mut doc, bin.as_mut(), rng) {
        for _ in 0..1 + rng.below(3) {
            edit(&mut doc, rng);
        }
    }
    let json = serde_json::to_vec(&doc).unwrap_or_default();
    match bin {
        Some(chunk) => join(&json, &chunk),
        None => json,
    }
}

/// A byte-level mutation for runs without libFuzzer: flip, overwrite, cut or repeat bytes.
pub fn flip_bytes(data: &mut Vec<u8>, rng: &mut Rng) {
    if data.is_empty() {
        data.push(rng.word() as u8);
        return;
    }
    let at = rng.below(data.len());
    match rng.below(4) {
        0 => data[at] ^= 1 << rng.below(8),
        1 => {
            let end = (at + 1 + rng.below(8)).min(data.len());
            let fill = [0x00, 0xff, 0x7f, 0x80][rng.below(4)];
            data[at..end].fill(fill);
        }
        2 => data.truncate(at),
        _ => {
            let end = (at + 1 + rng.below(64)).min(data.len());
            let piece = data[at..end].to_vec();
            data.splice(at..at, piece);
        }
    }
}

/// Edits one value of the document: a number or string from the lists above, an array's
/// element removed or repeated, an object's key removed or added, a value of another JSON type,
/// or a copy of another value of the document.
fn edit(doc: &mut Value, rng: &mut Rng) {
    let mut paths = Vec::new();
    collect(doc, String::new(), &mut paths);
    let path = &paths[rng.below(paths.len())];
    let donor = doc.pointer(&paths[rng.below(paths.len())]).cloned().unwrap_or(Value::Null);
    let Some(value) = doc.pointer_mut(path) else { return };
    match rng.below(8) {
        0 => *value = donor,
        1 => *value = other_type(rng),
        _ => match value {
            Value::Number(_) => *value = number(rng),
            Value::String(_) => *value = Value::String(STRINGS[rng.below(STRINGS.len())].to_string()),
            Value::Array(items) => edit_array(items, rng),
            Value::Object(map) => edit_object(map, donor, rng),
            _ => *value = other_type(rng),
        },
    }
}

fn collect(value: &Value, path: String, out: &mut Vec<String>) {
    match value {
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                collect(item, format!("{path}/{i}"), out);
            }
        }
        Value::Object(map) => {
            for (key, item) in map {
                let escaped = key.replace('~', "~0").replace('/', "~1");
                collect(item, format!("{path}/{escaped}"), out);
            }
        }
        _ => {}
    }
    out.push(path);
}

fn number(rng: &mut Rng) -> Value {
    // Half the time a small integer: the strides, offsets, counts and indices a loader must
    // check against each other are small (a byteStride of 4 under a 12-byte element).
    if rng.below(2) == 0 {
        return Value::from(rng.below(17) as i64);
    }
    let n = NUMBERS[rng.below(NUMBERS.len())];
    let n = if rng.below(4) == 0 { n + rng.below(5) as f64 - 2.0 } else { n };
    if n.fract() == 0.0 && n.abs() < 9.0e15 {
        Value::from(n as i64)
    } else {
        serde_json::Number::from_f64(n).map_or(Value::Null, Value::Number)
    }
}

fn other_type(rng: &mut Rng) -> Value {
    match rng.below(6) {
        0 => Value::Null,
        1 => Value::Bool(rng.below(2) == 0),
        2 => number(rng),
        3 => Value::String(STRINGS[rng.below(STRINGS.len())].to_string()),
        4 => Value::Array(vec![number(rng), number(rng)]),
        _ => Value::Object(Map::new()),
    }
}

fn edit_array(items: &mut Vec<Value>, rng: &mut Rng) {
    if items.is_empty() {
        items.push(number(rng));
        return;
    }
    let at = rng.below(items.len());
    match rng.below(3) {
        0 => {
            items.remove(at);
        }
        1 => items.insert(at, items[at].clone()),
        _ => items.truncate(at),
    }
}

fn edit_object(map: &mut Map<String, Value>, donor: Value, rng: &mut Rng) {
    if !map.is_empty() && rng.below(2) == 0 {
        let key = map.keys().nth(rng.below(map.len())).cloned().unwrap_or_default();
        map.remove(&key);
    } else {
        let value = if rng.below(2) == 0 { donor } else { number(rng) };
        map.insert(KEYS[rng.below(KEYS.len())].to_string(), value);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_glb_splits_and_joins_back_to_the_same_parts() {
        let glb = join(br#"{"asset":{"version":"2.0"}}"#, &[1, 2, 3, 4, 5]);
        assert_eq!(glb.len() % 4, 0);
        let (json, bin) = split(&glb).unwrap();
        assert_eq!(serde_json::from_slice::<Value>(&json).unwrap()["asset"]["version"], "2.0");
        assert_eq!(&bin.unwrap()[..5], &[1, 2, 3, 4, 5]);
    }

    #[test]
    fn mutations_keep_the_json_parsing_and_depend_only_on_the_seed() {
        let input = br#"{"asset":{"version":"2.0"},"accessors":[{"count":3,"type":"VEC3","componentType":5126}]}"#;
        let run = |seed| gltf(input, &mut Rng::new(seed), &mut flip_bytes);
        let changed = (0..50).filter(|&seed| run(seed) != input.to_vec()).count();
        assert!(changed > 40, "only {changed} of 50 mutations changed the file");
        for seed in 0..50 {
            assert_eq!(run(seed), run(seed));
            serde_json::from_slice::<Value>(&run(seed)).expect("a JSON edit keeps the JSON valid");
        }
    }
}
