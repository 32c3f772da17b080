//! A minimal SPIR-V reader: version, capabilities, entry points, descriptor bindings, and what a
//! module passes between stages (payloads, hit attributes, callable data, the rays it traces).
//! Enough to check that every module, committed or from disk, declares what the host expects.
//! It reads hostile bytes too (modules from disk, the fuzz target): nothing in it panics.

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
const OP_TYPE_BOOL: u32 = 20;
const OP_TYPE_INT: u32 = 21;
const OP_TYPE_FLOAT: u32 = 22;
const OP_TYPE_VECTOR: u32 = 23;
const OP_TYPE_MATRIX: u32 = 24;
const OP_TYPE_ARRAY: u32 = 28;
const OP_TYPE_STRUCT: u32 = 30;
const OP_TYPE_POINTER: u32 = 32;
const OP_CONSTANT: u32 = 43;
const OP_VARIABLE: u32 = 59;
const OP_BITCAST: u32 = 124;
const OP_TRACE_RAY: u32 = 4445;
const OP_EXECUTE_CALLABLE: u32 = 4446;
const OP_MODULE_PROCESSED: u32 = 330;
/// What may come before `OpModuleProcessed` in a module (SPIR-V's logical layout, sections 1
/// to 7): capabilities, extensions, imports, the memory model, entry points, execution modes
/// and the debug instructions.
const BEFORE_ANNOTATIONS: [u32; 14] = [17, 10, 11, 14, 15, 16, 331, 7, 4, 3, 2, 5, 6, OP_MODULE_PROCESSED];

/// Storage classes of what stages pass each other (SPV_KHR_ray_tracing): `CallableDataKHR`,
/// what a stage that calls a callable passes.
pub const STORAGE_CALLABLE_DATA: u32 = 5328;
/// `IncomingCallableDataKHR`: what a callable stage receives.
pub const STORAGE_INCOMING_CALLABLE_DATA: u32 = 5329;
/// `RayPayloadKHR`: what a stage that traces passes.
pub const STORAGE_RAY_PAYLOAD: u32 = 5338;
/// `HitAttributeKHR`: what an intersection stage reports to the hit stages.
pub const STORAGE_HIT_ATTRIBUTE: u32 = 5339;
/// `IncomingRayPayloadKHR`: what hit and miss stages receive.
pub const STORAGE_INCOMING_RAY_PAYLOAD: u32 = 5342;
const INTERFACE_STORAGE: [u32; 5] = [
    STORAGE_CALLABLE_DATA,
    STORAGE_INCOMING_CALLABLE_DATA,
    STORAGE_RAY_PAYLOAD,
    STORAGE_HIT_ATTRIBUTE,
    STORAGE_INCOMING_RAY_PAYLOAD,
];

/// What a module passes between stages. Sizes are the bytes of a type's scalars (no padding:
/// these storage classes have no explicit layout), `None` where the reader cannot tell.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Interface {
    /// (storage class, bytes) of every variable in a payload, attribute or callable class.
    pub variables: Vec<(u32, Option<u32>)>,
    /// Per `OpTraceRayKHR`: its miss index when a constant, and its payload's bytes.
    pub traces: Vec<(Option<u32>, Option<u32>)>,
    /// Per `OpExecuteCallableKHR`: its callable data's bytes.
    pub calls: Vec<Option<u32>>,
}

/// A type, as far as its size goes.
#[derive(Clone)]
enum Type {
    Scalar(u32),
    /// Element type and count (vectors, matrices and arrays; an array's count is a constant's
    /// id, resolved later).
    Repeat(u32, u32),
    ArrayOf(u32, u32),
    Struct(Vec<u32>),
    Pointer(u32),
}

/// Ids the interface needs, gathered in one pass.
#[derive(Default)]
struct Ids {
    types: BTreeMap<u32, Type>,
    constants: BTreeMap<u32, u32>,
    /// Bitcasts: result id to operand id (rust-gpu passes `MISS_PRIMARY as i32` that way).
    bitcasts: BTreeMap<u32, u32>,
    /// Variable id: (pointer type, storage class).
    variables: BTreeMap<u32, (u32, u32)>,
    /// (miss index id, payload id) of each trace; callable data id of each call.
    traces: Vec<(u32, u32)>,
    calls: Vec<u32>,
}

impl Ids {
    fn read(&mut self, opcode: u32, operands: &[u32]) {
        match (opcode, operands) {
            (OP_TYPE_BOOL, [id]) => self.type_(*id, Type::Scalar(4)),
            (OP_TYPE_INT | OP_TYPE_FLOAT, [id, width, ..]) => self.type_(*id, Type::Scalar(width / 8)),
            (OP_TYPE_VECTOR | OP_TYPE_MATRIX, [id, element, count]) => self.type_(*id, Type::Repeat(*element, *count)),
            (OP_TYPE_ARRAY, [id, element, length]) => self.type_(*id, Type::ArrayOf(*element, *length)),
            (OP_TYPE_STRUCT, [id, members @ ..]) => self.type_(*id, Type::Struct(members.to_vec())),
            (OP_TYPE_POINTER, [id, _, pointee]) => self.type_(*id, Type::Pointer(*pointee)),
            (OP_CONSTANT, [_, id, value, ..]) => {
                self.constants.insert(*id, *value);
            }
            (OP_BITCAST, [_, id, operand]) => {
                self.bitcasts.insert(*id, *operand);
            }
            (OP_VARIABLE, [pointer, id, class, ..]) if INTERFACE_STORAGE.contains(class) => {
                self.variables.insert(*id, (*pointer, *class));
            }
            (OP_TRACE_RAY, [_, _, _, _, _, miss, _, _, _, _, payload, ..]) => self.traces.push((*miss, *payload)),
            (OP_EXECUTE_CALLABLE, [_, data, ..]) => self.calls.push(*data),
            _ => {}
        }
    }

    fn type_(&mut self, id: u32, ty: Type) {
        self.types.insert(id, ty);
    }

    /// Bytes of type `id`'s scalars; `None` for what is not a sized type (or nests too deep,
    /// as a damaged module's cycle would).
    fn bytes(&self, id: u32, depth: u32) -> Option<u32> {
        if depth > 16 {
            return None;
        }
        match self.types.get(&id)? {
            Type::Scalar(bytes) => Some(*bytes),
            Type::Repeat(element, count) => self.bytes(*element, depth + 1)?.checked_mul(*count),
            Type::ArrayOf(element, length) => {
                self.bytes(*element, depth + 1)?.checked_mul(*self.constants.get(length)?)
            }
            Type::Struct(members) => {
                members.iter().try_fold(0u32, |sum, m| sum.checked_add(self.bytes(*m, depth + 1)?))
            }
            Type::Pointer(_) => None,
        }
    }

    /// The value of constant `id`, through bitcasts of it.
    fn constant(&self, id: u32) -> Option<u32> {
        let mut id = id;
        for _ in 0..4 {
            match (self.constants.get(&id), self.bitcasts.get(&id)) {
                (Some(value), _) => return Some(*value),
                (None, Some(operand)) => id = *operand,
                (None, None) => return None,
            }
        }
        None
    }

    /// Bytes of what variable `id` holds.
    fn variable_bytes(&self, id: u32) -> Option<u32> {
        let (pointer, _) = self.variables.get(&id)?;
        match self.types.get(pointer)? {
            Type::Pointer(pointee) => self.bytes(*pointee, 0),
            _ => None,
        }
    }

    fn interface(&self) -> Interface {
        Interface {
            variables: self.variables.iter().map(|(id, (_, class))| (*class, self.variable_bytes(*id))).collect(),
            traces: self
                .traces
                .iter()
                .map(|(miss, payload)| (self.constant(*miss), self.variable_bytes(*payload)))
                .collect(),
            calls: self.calls.iter().map(|data| self.variable_bytes(*data)).collect(),
        }
    }
}

/// What a module declares, as far as the host's checks go.
#[derive(Debug, Default, PartialEq, Eq)]
pub struct ModuleInfo {
    /// (major, minor) from the header.
    pub version: (u32, u32),
    /// Capability numbers as declared.
    pub capabilities: Vec<u32>,
    /// SPIR-V extensions as declared (`OpExtension`).
    pub extensions: Vec<String>,
    /// (execution model, name) of each entry point.
    pub entry_points: Vec<(u32, String)>,
    /// (descriptor set, binding) of every decorated variable, sorted.
    pub bindings: Vec<(u32, u32)>,
    /// Number of instructions in the module.
    pub instruction_count: usize,
    /// What it passes between stages.
    pub interface: Interface,
    /// The texts of its `OpModuleProcessed` instructions, in order.
    pub processed: Vec<String>,
}

impl ModuleInfo {
    /// The contract version the module records (`contract::RECORD_PREFIX`), if it records one.
    pub fn contract(&self) -> Option<&str> {
        self.processed.iter().find_map(|p| p.strip_prefix(crate::contract::RECORD_PREFIX))
    }
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
    let mut ids = Ids::default();
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
            (OP_EXTENSION, name) => info.extensions.push(literal_string(name)),
            (OP_MODULE_PROCESSED, text) => info.processed.push(literal_string(text)),
            (OP_ENTRY_POINT, [model, _function, name @ ..]) => info.entry_points.push((*model, literal_string(name))),
            (OP_DECORATE, [target, DECORATION_DESCRIPTOR_SET, value, ..]) => {
                sets.insert(*target, *value);
            }
            (OP_DECORATE, [target, DECORATION_BINDING, value, ..]) => {
                bindings.insert(*target, *value);
            }
            _ => ids.read(opcode, operands),
        }
        info.instruction_count += 1;
        at += count;
    }
    info.bindings = bindings.iter().map(|(id, b)| (sets.get(id).copied().unwrap_or(0), *b)).collect();
    info.bindings.sort_unstable();
    info.interface = ids.interface();
    Ok(info)
}

/// A checked module as its header and its instructions (each its words, opcode first), for the
/// rewrites below.
fn instructions(bytes: &[u8]) -> Result<(Vec<u32>, Vec<Vec<u32>>), String> {
    parse(bytes)?;
    let words: Vec<u32> = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    let mut instructions = Vec::new();
    let mut at = 5;
    while at < words.len() {
        let count = ((words[at] >> 16) as usize).max(1);
        instructions.push(words[at..(at + count).min(words.len())].to_vec());
        at += count;
    }
    Ok((words[..5].to_vec(), instructions))
}

/// A module's bytes from its header and instructions.
fn assemble(header: &[u32], instructions: &[Vec<u32>]) -> Vec<u8> {
    header.iter().chain(instructions.iter().flatten()).flat_map(|w| w.to_le_bytes()).collect()
}

fn opcode(instruction: &[u32]) -> u32 {
    instruction[0] & 0xffff
}

/// `bytes` without the `RayQueryKHR` capability and the `SPV_KHR_ray_query` extension when the
/// module has no ray query type (so uses no ray query instruction); unchanged otherwise.
pub fn without_unused_ray_query(bytes: &[u8]) -> Result<Vec<u8>, String> {
    let (header, mut instructions) = instructions(bytes)?;
    if instructions.iter().any(|i| opcode(i) == OP_TYPE_RAY_QUERY) {
        return Ok(bytes.to_vec());
    }
    let unused = |i: &Vec<u32>| match (opcode(i), &i[1..]) {
        (OP_CAPABILITY, [cap]) => *cap == CAPABILITY_RAY_QUERY,
        (OP_EXTENSION, name) => literal_string(name) == "SPV_KHR_ray_query",
        _ => false,
    };
    instructions.retain(|i| !unused(i));
    Ok(assemble(&header, &instructions))
}

/// `bytes` with each entry point named by its function alone: rust-gpu names an entry point
/// in a module by its path (`closest_hit::triangle_closest_hit`), twinray by the module's name.
pub fn with_plain_entry_names(bytes: &[u8]) -> Result<Vec<u8>, String> {
    let (header, mut instructions) = instructions(bytes)?;
    for instruction in instructions.iter_mut().filter(|i| opcode(i) == OP_ENTRY_POINT && i.len() > 3) {
        let name = literal_string(&instruction[3..]);
        let Some((_, plain)) = name.rsplit_once("::") else { continue };
        let name_words = string_words(&name).len();
        let rest = instruction[3 + name_words..].to_vec();
        let words = [&instruction[1..3], &string_words(plain)[..], &rest[..]].concat();
        *instruction = [vec![((words.len() as u32 + 1) << 16) | OP_ENTRY_POINT], words].concat();
    }
    Ok(assemble(&header, &instructions))
}

/// `bytes` recording `record` (`contract::record()`) in an `OpModuleProcessed` where the
/// logical layout puts it, any contract record it had before dropped.
pub fn with_record(bytes: &[u8], record: &str) -> Result<Vec<u8>, String> {
    let (header, mut instructions) = instructions(bytes)?;
    let old_record = |i: &Vec<u32>| {
        opcode(i) == OP_MODULE_PROCESSED && literal_string(&i[1..]).starts_with(crate::contract::RECORD_PREFIX)
    };
    instructions.retain(|i| !old_record(i));
    let place =
        instructions.iter().position(|i| !BEFORE_ANNOTATIONS.contains(&opcode(i))).unwrap_or(instructions.len());
    let text = string_words(record);
    instructions.insert(place, [vec![((text.len() as u32 + 1) << 16) | OP_MODULE_PROCESSED], text].concat());
    Ok(assemble(&header, &instructions))
}

/// `text` as a SPIR-V literal string: UTF-8, nul-terminated, packed four bytes to a word.
fn string_words(text: &str) -> Vec<u32> {
    let mut bytes = text.as_bytes().to_vec();
    bytes.push(0);
    bytes.resize(bytes.len().div_ceil(4) * 4, 0);
    bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
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
    fn entry_points_are_named_by_their_function() {
        let entry = |name: &str| {
            let words = string_words(name);
            [vec![((words.len() as u32 + 4) << 16) | OP_ENTRY_POINT, 5313, 7], words, vec![9]].concat()
        };
        let header = [MAGIC, 0x0001_0400, 0, 10, 0];
        let module = |name: &str| words_to_bytes(&[&header[..], &entry(name)].concat());
        let renamed = with_plain_entry_names(&module("closest_hit::triangle_closest_hit")).unwrap();
        assert_eq!(renamed, module("triangle_closest_hit"));
        assert_eq!(parse(&renamed).unwrap().entry_points[0].1, "triangle_closest_hit");
        // A plain name is kept as it is.
        assert_eq!(with_plain_entry_names(&module("miss")).unwrap(), module("miss"));
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

    /// The record goes after the debug section and before the first decoration, once, however
    /// often a module is stamped.
    #[test]
    fn records_the_contract_once_before_the_annotations() {
        let module =
            [MAGIC, 0x0001_0400, 0, 100, 0, (2 << 16) | OP_CAPABILITY, 4479, (4 << 16) | OP_DECORATE, 7, 33, 3];
        let stamped = with_record(&words_to_bytes(&module), "twinray-shared 0.1.0").unwrap();
        let again = with_record(&stamped, "twinray-shared 0.2.0").unwrap();
        let info = parse(&again).unwrap();
        assert_eq!(info.processed, ["twinray-shared 0.2.0"]);
        assert_eq!(info.contract(), Some("0.2.0"));
        assert_eq!(info.bindings, vec![(0, 3)]);
        let words: Vec<u32> = again.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        assert_eq!(words[7] & 0xffff, OP_MODULE_PROCESSED, "after the capability, before the decoration");
        assert_eq!(parse(&words_to_bytes(&module)).unwrap().contract(), None);
    }

    #[test]
    fn rejects_garbage() {
        assert!(parse(b"not spirv at all, clearly").is_err());
        assert!(parse(&words_to_bytes(&[MAGIC, 0x10400, 0, 1, 0, 5 << 16])).is_err());
    }
}
