//! A minimal SPIR-V reader: version, capabilities, entry points and descriptor bindings.
//! Enough to check that every committed module declares what the host expects.

use std::collections::BTreeMap;

const MAGIC: u32 = 0x0723_0203;
const OP_CAPABILITY: u32 = 17;
const OP_ENTRY_POINT: u32 = 15;
const OP_DECORATE: u32 = 71;
const OP_EXTENSION: u32 = 10;
/// `OpTypeRayQueryKHR`, the type every ray query instruction works on.
const OP_TYPE_RAY_QUERY: u32 = 4472;
/// The `RayQueryKHR` capability (the same number as the opcode above).
pub const CAPABILITY_RAY_QUERY: u32 = 4472;
const DECORATION_BINDING: u32 = 33;
const DECORATION_DESCRIPTOR_SET: u32 = 34;

#[derive(Debug, Default, PartialEq, Eq)]
pub struct ModuleInfo {
    /// (major, minor) from the header.
    pub version: (u32, u32),
    /// Capability numbers as declared.
    pub capabilities: Vec<u32>,
    /// (execution model, name) of each entry point.
    pub entry_points: Vec<(u32, String)>,
    /// (descriptor set, binding) of every decorated variable, sorted.
    pub bindings: Vec<(u32, u32)>,
    /// Number of instructions in the module.
    pub instruction_count: usize,
}

/// Reads `bytes` as a little-endian SPIR-V module.
pub fn parse(bytes: &[u8]) -> Result<ModuleInfo, String> {
    if !bytes.len().is_multiple_of(4) || bytes.len() < 20 {
        return Err(format!("{} bytes is not a SPIR-V module", bytes.len()));
    }
    let words: Vec<u32> = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    if words[0] != MAGIC {
        return Err(format!("bad magic number {:#010x}", words[0]));
    }
    let mut info = ModuleInfo { version: ((words[1] >> 16) & 0xff, (words[1] >> 8) & 0xff), ..Default::default() };
    let mut sets = BTreeMap::new();
    let mut bindings = BTreeMap::new();
    let mut at = 5;
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let opcode = words[at] & 0xffff;
        let operands = words
            .get(at + 1..at + count)
            .filter(|_| count > 0)
            .ok_or_else(|| format!("truncated instruction at word {at}"))?;
        match (opcode, operands) {
            (OP_CAPABILITY, [cap, ..]) => info.capabilities.push(*cap),
            (OP_ENTRY_POINT, [model, _function, name @ ..]) => info.entry_points.push((*model, literal_string(name))),
            (OP_DECORATE, [target, DECORATION_DESCRIPTOR_SET, value, ..]) => {
                sets.insert(*target, *value);
            }
            (OP_DECORATE, [target, DECORATION_BINDING, value, ..]) => {
                bindings.insert(*target, *value);
            }
            _ => {}
        }
        info.instruction_count += 1;
        at += count;
    }
    info.bindings = bindings.iter().map(|(id, b)| (sets.get(id).copied().unwrap_or(0), *b)).collect();
    info.bindings.sort_unstable();
    Ok(info)
}

/// `bytes` without the `RayQueryKHR` capability and the `SPV_KHR_ray_query` extension when the
/// module has no ray query type (so uses no ray query instruction); unchanged otherwise.
pub fn without_unused_ray_query(bytes: &[u8]) -> Result<Vec<u8>, String> {
    parse(bytes)?;
    let words: Vec<u32> = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    let mut instructions = Vec::new();
    let mut at = 5;
    while at < words.len() {
        let count = ((words[at] >> 16) as usize).max(1);
        instructions.push(&words[at..(at + count).min(words.len())]);
        at += count;
    }
    let opcode = |i: &[u32]| i[0] & 0xffff;
    if instructions.iter().any(|i| opcode(i) == OP_TYPE_RAY_QUERY) {
        return Ok(bytes.to_vec());
    }
    let unused = |i: &&[u32]| match (opcode(i), &i[1..]) {
        (OP_CAPABILITY, [cap]) => *cap == CAPABILITY_RAY_QUERY,
        (OP_EXTENSION, name) => literal_string(name) == "SPV_KHR_ray_query",
        _ => false,
    };
    let kept = words[..5].iter().chain(instructions.iter().filter(|i| !unused(i)).flat_map(|i| i.iter()));
    Ok(kept.flat_map(|w| w.to_le_bytes()).collect())
}

/// A nul-terminated UTF-8 string packed four bytes to a word.
fn literal_string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|&b| b != 0).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words_to_bytes(words: &[u32]) -> Vec<u8> {
        words.iter().flat_map(|w| w.to_le_bytes()).collect()
    }

    #[test]
    fn reads_entry_points_and_bindings() {
        let name = u32::from_le_bytes(*b"main");
        let module = [
            MAGIC,
            0x0001_0400,
            0,
            100,
            0,
            (2 << 16) | OP_CAPABILITY,
            4479,
            (5 << 16) | OP_ENTRY_POINT,
            5313,
            1,
            name,
            0,
            (4 << 16) | OP_DECORATE,
            7,
            DECORATION_DESCRIPTOR_SET,
            0,
            (4 << 16) | OP_DECORATE,
            7,
            DECORATION_BINDING,
            3,
        ];
        let info = parse(&words_to_bytes(&module)).unwrap();
        assert_eq!(info.version, (1, 4));
        assert_eq!(info.capabilities, vec![4479]);
        assert_eq!(info.entry_points, vec![(5313, "main".to_string())]);
        assert_eq!(info.bindings, vec![(0, 3)]);
    }

    /// A module that declares ray queries without a ray query type loses the declaration;
    /// one with the type keeps it.
    #[test]
    fn drops_an_unused_ray_query_capability() {
        let ext = |name: &[u8; 20]| -> Vec<u32> {
            let mut w = vec![(6 << 16) | OP_EXTENSION];
            w.extend(name.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])));
            w
        };
        let mut module = vec![MAGIC, 0x0001_0400, 0, 100, 0, (2 << 16) | OP_CAPABILITY, 4479];
        module.extend([(2 << 16) | OP_CAPABILITY, CAPABILITY_RAY_QUERY]);
        module.extend(ext(b"SPV_KHR_ray_query\0\0\0"));
        module.extend(ext(b"SPV_KHR_ray_tracing\0"));
        let trimmed = parse(&without_unused_ray_query(&words_to_bytes(&module)).unwrap()).unwrap();
        assert_eq!(trimmed.capabilities, vec![4479]);
        assert_eq!(trimmed.instruction_count, 2, "the ray tracing extension stays");
        module.extend([(2 << 16) | OP_TYPE_RAY_QUERY, 9]);
        let kept = without_unused_ray_query(&words_to_bytes(&module)).unwrap();
        assert_eq!(kept, words_to_bytes(&module));
    }

    #[test]
    fn rejects_garbage() {
        assert!(parse(b"not spirv at all, clearly").is_err());
        assert!(parse(&words_to_bytes(&[MAGIC, 0x10400, 0, 1, 0, 5 << 16])).is_err());
    }
}
