//! Salting a module: the same code with one debug instruction added (`OpModuleProcessed
//! "twinray copy N"`), so that a driver that recognises modules it has seen (by hash, in a
//! shader cache, in its own memory) compiles and places each copy on its own. The null
//! control of `compare` and `bench` times two such copies of one set.

/// Opcodes of the instructions before the annotations: capabilities, extensions, imports,
/// the memory model, entry points, execution modes and the debug section, which
/// `OpModuleProcessed` closes.
const PREAMBLE: [u32; 14] = [17, 10, 11, 14, 15, 16, 331, 7, 4, 3, 2, 5, 6, 330];
const OP_MODULE_PROCESSED: u32 = 330;
const HEADER_WORDS: usize = 5;

/// `spirv` with `OpModuleProcessed "twinray copy {copy}"` at the end of its debug section;
/// `None` when it is not whole SPIR-V words with a header and whole instructions.
pub fn salted(spirv: &[u8], copy: u32) -> Option<Vec<u8>> {
    if !spirv.len().is_multiple_of(4) {
        return None;
    }
    let words: Vec<u32> = spirv.chunks_exact(4).map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]])).collect();
    if words.len() < HEADER_WORDS || words[0] != 0x0723_0203 {
        return None;
    }
    let mut at = HEADER_WORDS;
    while at < words.len() && PREAMBLE.contains(&(words[at] & 0xffff)) {
        let count = (words[at] >> 16) as usize;
        if count == 0 || at + count > words.len() {
            return None;
        }
        at += count;
    }
    let mut text = format!("twinray copy {copy}").into_bytes();
    text.resize(text.len() / 4 * 4 + 4, 0); // NUL-terminated, padded to a word
    let operand: Vec<u32> = text.chunks_exact(4).map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]])).collect();
    let head = ((1 + operand.len() as u32) << 16) | OP_MODULE_PROCESSED;
    let out: Vec<u32> =
        words[..at].iter().copied().chain([head]).chain(operand).chain(words[at..].iter().copied()).collect();
    Some(out.iter().flat_map(|w| w.to_le_bytes()).collect())
}

#[cfg(test)]
mod tests {
    use super::salted;
    use twinray_shared::catalog::{Language, MODULES};

    #[test]
    fn every_built_in_module_salts_into_a_module_with_the_same_code() {
        for language in [Language::Rust, Language::Glsl] {
            for spec in MODULES.iter() {
                let spirv = super::super::builtin::spirv(language, spec.name).unwrap();
                let (one, two) = (salted(spirv, 1).unwrap(), salted(spirv, 2).unwrap());
                assert!(one != two && one.len() > spirv.len(), "{}", spec.name);
                let before = twinray_shared::spirv_info::parse(spirv).unwrap();
                let after = twinray_shared::spirv_info::parse(&one).unwrap();
                assert_eq!(after.instruction_count, before.instruction_count + 1, "{}", spec.name);
                // Everything but the added instruction is as it was.
                let added = one.len() - spirv.len();
                let at = (0..spirv.len()).find(|&i| one[i] != spirv[i]).unwrap();
                assert_eq!(one[..at], spirv[..at]);
                assert_eq!(one[at + added..], spirv[at..], "{}", spec.name);
            }
        }
    }

    #[test]
    fn refuses_what_is_not_spirv() {
        assert_eq!(salted(&[1, 2, 3], 1), None);
        assert_eq!(salted(&[0; 20], 1), None);
        let mut bad = 0x0723_0203u32.to_le_bytes().to_vec();
        bad.extend([0u8; 16]);
        bad.extend(((9u32 << 16) | 17).to_le_bytes()); // an instruction longer than the module
        assert_eq!(salted(&bad, 1), None);
    }
}
