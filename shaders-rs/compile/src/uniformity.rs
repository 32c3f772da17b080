//! Non-uniform descriptor indexing. Vulkan lets a stage index an array of descriptors with a
//! value that differs between the invocations running together (a texture per hit) only if
//! what the access reads is decorated `NonUniform`; without it the result is undefined, and
//! hardware that fetches one descriptor per group of invocations (AMD's, among others) reads
//! the wrong one. NVIDIA and lavapipe happen to read the right one, so a renderer tested there
//! never sees the fault.
//!
//! [`check`] finds such accesses in any module (a user's own from disk too): indices derived
//! from a value that may differ between invocations (built-ins such as the instance,
//! primitive or launch id, payloads, ray queries, or memory read at addresses derived from
//! them, or values chosen under branches on them) whose access lacks the decoration.
//! [`decorate`] adds the decoration, and the capabilities it needs, to every access of a
//! descriptor array at an index that is not a constant: rust-gpu's `RuntimeArray::index`
//! writes it, but its inliner drops it (docs/upstream/non-uniform.md).

use rspirv::binary::Assemble;
use rspirv::dr::{self, Instruction, Operand};
use rspirv::spirv::{Capability, Decoration, Op, Word};
use std::collections::{HashMap, HashSet};

/// An access of a descriptor array at an index that may differ between invocations, without
/// `NonUniform` on what it reads.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Fault {
    /// (descriptor set, binding) of the array.
    pub binding: (u32, u32),
    /// The access: `%ID = OpAccessChain` (ids as `spirv-dis` prints them).
    pub access: String,
    /// What the index is derived from, in words.
    pub source: String,
}

impl std::fmt::Display for Fault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} indexes the descriptor array at set {} binding {} with a value derived from {}, and what it reads is not decorated NonUniform: undefined on devices that fetch one descriptor per group of invocations (GLSL: nonuniformEXT; rust-gpu: twinray_compile::uniformity::decorate, docs/rust-stages.md)",
            self.access, self.binding.0, self.binding.1, self.source
        )
    }
}

/// The accesses of `bytes` (a SPIR-V module) that need `NonUniform` and lack it.
pub fn check(bytes: &[u8]) -> Result<Vec<Fault>, String> {
    let module = load(bytes)?;
    let facts = Facts::of(&module);
    let taint = Taint::of(&module, &facts);
    let decorated = facts.non_uniform.clone();
    let mut faults = Vec::new();
    for access in accesses(&facts, &module, &taint) {
        let Some(source) = taint.values.get(&access.index) else { continue };
        if let Some(missing) = access.reads.iter().find(|id| !decorated.contains(id)) {
            let op = if *missing == access.id { "OpAccessChain" } else { "OpLoad" };
            faults.push(Fault {
                binding: access.binding,
                access: format!("%{missing} = {op}"),
                source: source.clone(),
            });
        }
    }
    Ok(faults)
}

/// `bytes` with `NonUniform` on every access of a descriptor array at a non-constant index (and
/// on what is loaded through it), and the capabilities those decorations need.
pub fn decorate(bytes: &[u8]) -> Result<Vec<u8>, String> {
    let mut module = load(bytes)?;
    let facts = Facts::of(&module);
    let taint = Taint::of(&module, &facts);
    let mut needed = HashSet::new();
    let mut ids = Vec::new();
    for access in accesses(&facts, &module, &taint) {
        if facts.constants.contains(&access.index) {
            continue;
        }
        needed.insert(access.capability);
        ids.extend(access.reads.iter().copied().filter(|id| !facts.non_uniform.contains(id)));
    }
    ids.sort_unstable();
    ids.dedup();
    for id in ids {
        let operands = vec![Operand::IdRef(id), Operand::Decoration(Decoration::NonUniform)];
        module.annotations.push(Instruction::new(Op::Decorate, None, None, operands));
    }
    if !needed.is_empty() {
        needed.insert(Capability::ShaderNonUniform);
    }
    let declared: HashSet<Capability> = module
        .capabilities
        .iter()
        .filter_map(|c| match c.operands.first() {
            Some(Operand::Capability(cap)) => Some(*cap),
            _ => None,
        })
        .collect();
    let mut new: Vec<Capability> = needed.difference(&declared).copied().collect();
    new.sort_by_key(|c| *c as u32);
    for cap in new {
        module.capabilities.push(Instruction::new(Op::Capability, None, None, vec![Operand::Capability(cap)]));
    }
    Ok(module.assemble().iter().flat_map(|w| w.to_le_bytes()).collect())
}

pub(crate) fn load(bytes: &[u8]) -> Result<dr::Module, String> {
    if !bytes.len().is_multiple_of(4) {
        return Err(format!("{} bytes is not a SPIR-V module", bytes.len()));
    }
    let words: Vec<u32> = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    dr::load_words(words).map_err(|e| format!("reading the module: {e}"))
}

/// One access of a descriptor array.
struct Access {
    /// The access chain's result.
    id: Word,
    binding: (u32, u32),
    /// The index into the array.
    index: Word,
    /// The ids the decoration belongs on: the access chain, what is loaded through it and the
    /// images and chains made from those.
    reads: Vec<Word>,
    /// The capability its non-uniform indexing needs.
    capability: Capability,
}

/// Every access chain into an array of descriptors (the variable itself, or a parameter it
/// is passed as: rust-gpu leaves functions that take it), with the ids that read through it.
fn accesses(facts: &Facts, module: &dr::Module, taint: &Taint) -> Vec<Access> {
    let mut users: HashMap<Word, Vec<Word>> = HashMap::new();
    let body: Vec<&Instruction> =
        module.functions.iter().flat_map(|f| f.blocks.iter().flat_map(|b| b.instructions.iter())).collect();
    for i in &body {
        if let (Some(id), true) = (i.result_id, reads_through(i.class.opcode)) {
            if let Some(base) = i.operands.first().and_then(|o| o.id_ref_any()) {
                users.entry(base).or_default().push(id);
            }
        }
    }
    let mut accesses = Vec::new();
    for i in &body {
        let chain = matches!(i.class.opcode, Op::AccessChain | Op::InBoundsAccessChain);
        let (Some(id), true) = (i.result_id, chain) else { continue };
        let Some(base) = i.operands.first().and_then(|o| o.id_ref_any()) else { continue };
        let Some(base) = taint.roots(base).into_iter().find(|r| facts.bindings.contains_key(r)) else { continue };
        let (Some(binding), Some((class, pointer))) = (facts.bindings.get(&base), facts.variables.get(&base)) else {
            continue;
        };
        let Some(array) = facts.pointee(*pointer) else { continue };
        if !matches!(array.class.opcode, Op::TypeArray | Op::TypeRuntimeArray) {
            continue;
        }
        let Some(index) = i.operands.get(1).and_then(|o| o.id_ref_any()) else { continue };
        let element = array.operands.first().and_then(|o| o.id_ref_any()).unwrap_or(0);
        let element = match facts.types.get(&element) {
            Some(t) if t.class.opcode == Op::TypeSampledImage => t.operands[0].id_ref_any().unwrap_or(element),
            _ => element,
        };
        let mut reads = vec![id];
        let mut at = 0;
        while at < reads.len() && reads.len() < 64 {
            reads.extend(users.get(&reads[at]).into_iter().flatten().copied());
            at += 1;
        }
        let capability = facts.capability(element, *class);
        accesses.push(Access { id, binding: *binding, index, reads, capability });
    }
    accesses
}

/// Instructions whose result still reads the descriptor an access chain points at.
fn reads_through(op: Op) -> bool {
    matches!(op, Op::Load | Op::AccessChain | Op::InBoundsAccessChain | Op::CopyObject | Op::SampledImage | Op::Image)
}

use facts::Facts;
use taint::Taint;
mod facts;
mod taint;

#[cfg(test)]
mod tests;
