//! Which values of a module may differ between the invocations running together: a forward
//! dataflow over the whole module to a fixed point. A value is non-uniform if it is read from
//! a built-in that varies per invocation, a payload, hit attribute or callable data, a stage
//! input, or a ray query; if it is computed from a non-uniform value (through phis, calls and
//! returns too); if it is loaded through a non-uniform pointer, or from memory a non-uniform
//! value was stored to; or if a branch on a non-uniform condition chose it (phis at the
//! branch's merge, stores and returns inside it). Memory is tracked per variable, not per
//! element or point in the program: it may call a value non-uniform that is not, never the
//! other way round.

use super::facts::{Facts, UNIFORM_BUILTINS};
use rspirv::dr::{self, Instruction, Operand};
use rspirv::spirv::{Op, StorageClass, Word};
use std::collections::hash_map::Entry;
use std::collections::{HashMap, HashSet};

/// The module's non-uniform values, each with where it comes from in words.
#[derive(Default)]
pub(super) struct Taint {
    pub(super) values: HashMap<Word, String>,
    /// Variables a non-uniform value may be stored in.
    memory: HashMap<Word, String>,
    /// Functions that may return a non-uniform value.
    returns: HashMap<Word, String>,
    /// Pointer id to what it was made from (access chains, parameters' arguments).
    bases: HashMap<Word, Vec<Word>>,
    changed: bool,
}

impl Taint {
    pub(super) fn of(module: &dr::Module, facts: &Facts) -> Taint {
        let mut taint = Taint::default();
        for (id, (class, _)) in &facts.variables {
            if let Some(source) = source_of(facts, *id, *class) {
                taint.memory.insert(*id, source);
            }
        }
        // Each pass only adds; a module of N ids settles within N passes.
        let limit = module.header.as_ref().map_or(1 << 20, |h| h.bound as usize) + 2;
        for _ in 0..limit {
            taint.changed = false;
            for function in &module.functions {
                taint.function(module, function);
            }
            if !taint.changed {
                break;
            }
        }
        taint
    }

    fn mark(&mut self, id: Word, source: &str) {
        self.changed |= first(&mut self.values, id, source);
    }

    fn mark_memory(&mut self, pointer: Word, source: &str) {
        for root in self.roots(pointer) {
            self.changed |= first(&mut self.memory, root, source);
        }
    }

    fn mark_return(&mut self, function: Word, source: &str) {
        self.changed |= first(&mut self.returns, function, source);
    }

    /// The variables (or unknown pointers) `pointer` may point into.
    pub(super) fn roots(&self, pointer: Word) -> Vec<Word> {
        let (mut seen, mut todo, mut roots) = (HashSet::new(), vec![pointer], Vec::new());
        while let Some(p) = todo.pop() {
            if !seen.insert(p) {
                continue;
            }
            match self.bases.get(&p) {
                Some(bases) => todo.extend(bases),
                None => roots.push(p),
            }
        }
        roots
    }

    fn any_tainted(&self, ids: impl IntoIterator<Item = Word>) -> Option<String> {
        ids.into_iter().find_map(|id| self.values.get(&id).cloned())
    }

    fn function(&mut self, module: &dr::Module, function: &dr::Function) {
        let id = function.def.as_ref().and_then(|d| d.result_id).unwrap_or(0);
        let labels: HashMap<Word, usize> =
            function.blocks.iter().enumerate().filter_map(|(n, b)| Some((b.label_id()?, n))).collect();
        for (n, block) in function.blocks.iter().enumerate() {
            for i in &block.instructions {
                self.instruction(module, id, i);
            }
            self.branch(function, &labels, n, id);
        }
    }

    fn instruction(&mut self, module: &dr::Module, function: Word, i: &Instruction) {
        let ids = || i.operands.iter().filter_map(|o| o.id_ref_any());
        match i.class.opcode {
            Op::Load => {
                let pointer = ids().next().unwrap_or(0);
                let from = self
                    .values
                    .get(&pointer)
                    .cloned()
                    .or_else(|| self.roots(pointer).iter().find_map(|r| self.memory.get(r).cloned()));
                if let (Some(id), Some(source)) = (i.result_id, from) {
                    self.mark(id, &source);
                }
            }
            Op::Store => {
                let (pointer, value) = (ids().next().unwrap_or(0), ids().nth(1).unwrap_or(0));
                if let Some(source) = self.values.get(&value).cloned() {
                    self.mark_memory(pointer, &source);
                }
            }
            Op::CopyMemory | Op::CopyMemorySized => {
                let (target, from) = (ids().next().unwrap_or(0), ids().nth(1).unwrap_or(0));
                if let Some(source) = self.roots(from).iter().find_map(|r| self.memory.get(r).cloned()) {
                    self.mark_memory(target, &source);
                }
            }
            Op::FunctionCall => self.call(module, i),
            Op::ReturnValue => {
                if let Some(source) = self.any_tainted(ids()) {
                    self.mark_return(function, &source);
                }
            }
            op => {
                let Some(id) = i.result_id else { return };
                if matches!(op, Op::AccessChain | Op::InBoundsAccessChain | Op::PtrAccessChain | Op::CopyObject) {
                    let base = ids().next().unwrap_or(0);
                    if i.result_type.is_some() && !self.bases.get(&id).is_some_and(|b| b.contains(&base)) {
                        self.bases.entry(id).or_default().push(base);
                    }
                }
                let source = if format!("{op:?}").starts_with("RayQuery") {
                    Some("a ray query".to_string())
                } else if format!("{op:?}").starts_with("Atomic") {
                    Some("an atomic operation".to_string())
                } else {
                    self.any_tainted(ids())
                };
                if let Some(source) = source {
                    self.mark(id, &source);
                }
            }
        }
    }

    /// A call: non-uniform arguments make their parameters so, pointer parameters point where
    /// their arguments do, and a callee that may return a non-uniform value makes the result so.
    fn call(&mut self, module: &dr::Module, i: &Instruction) {
        let mut ids = i.operands.iter().filter_map(|o| o.id_ref_any());
        let callee = ids.next().unwrap_or(0);
        let args: Vec<Word> = ids.collect();
        let Some(f) = module.functions.iter().find(|f| f.def.as_ref().and_then(|d| d.result_id) == Some(callee)) else {
            return;
        };
        for (param, arg) in f.parameters.iter().filter_map(|p| p.result_id).zip(args) {
            if !self.bases.get(&param).is_some_and(|b| b.contains(&arg)) {
                self.bases.entry(param).or_default().push(arg);
                self.changed = true;
            }
            if let Some(source) = self.values.get(&arg).cloned() {
                self.mark(param, &source);
            }
        }
        if let (Some(id), Some(source)) = (i.result_id, self.returns.get(&callee).cloned()) {
            self.mark(id, &source);
        }
    }

    /// A conditional branch or switch on a non-uniform value: what its construct chooses
    /// differs between invocations too.
    fn branch(&mut self, function: &dr::Function, labels: &HashMap<Word, usize>, n: usize, id: Word) {
        let block = &function.blocks[n];
        let Some(last) = block.instructions.last() else { return };
        let condition = match last.class.opcode {
            Op::BranchConditional | Op::Switch => last.operands.first().and_then(|o| o.id_ref_any()),
            _ => None,
        };
        let Some(source) = condition.and_then(|c| self.values.get(&c).cloned()) else { return };
        let merge = block
            .instructions
            .iter()
            .rev()
            .nth(1)
            .filter(|m| matches!(m.class.opcode, Op::SelectionMerge | Op::LoopMerge));
        let merge = merge.and_then(|m| m.operands.first()?.id_ref_any());
        let targets = last.operands.iter().skip(1).filter_map(|o| match o {
            Operand::IdRef(label) => Some(*label),
            _ => None,
        });
        // The blocks inside the construct: reachable from the targets without its merge (to
        // the function's end where the branch names no merge: a loop's exit).
        let mut inside = HashSet::new();
        let mut todo: Vec<Word> = targets.collect();
        while let Some(label) = todo.pop() {
            if Some(label) == merge || !inside.insert(label) {
                continue;
            }
            let Some(&at) = labels.get(&label) else { continue };
            let b = &function.blocks[at];
            if let Some(end) = b.instructions.last() {
                todo.extend(end.operands.iter().filter_map(|o| match (end.class.opcode, o) {
                    (Op::Branch | Op::BranchConditional | Op::Switch, Operand::IdRef(l)) => Some(*l),
                    _ => None,
                }));
            }
        }
        let chosen = inside.iter().copied().chain(merge);
        for label in chosen.collect::<Vec<_>>() {
            let Some(&at) = labels.get(&label) else { continue };
            for i in &function.blocks[at].instructions {
                match (i.class.opcode, i.result_id) {
                    (Op::Phi, Some(phi)) => self.mark(phi, &source),
                    (Op::Store, _) if inside.contains(&label) => {
                        let pointer = i.operands.first().and_then(|o| o.id_ref_any()).unwrap_or(0);
                        self.mark_memory(pointer, &source);
                    }
                    (Op::ReturnValue, _) if inside.contains(&label) => self.mark_return(id, &source),
                    _ => {}
                }
            }
        }
    }
}

/// Records `source` for `key` unless it has one: whether it was new.
fn first(map: &mut HashMap<Word, String>, key: Word, source: &str) -> bool {
    match map.entry(key) {
        Entry::Vacant(e) => {
            e.insert(source.to_string());
            true
        }
        Entry::Occupied(_) => false,
    }
}

/// Where a variable's contents vary between invocations, in words; `None` where they do not.
fn source_of(facts: &Facts, id: Word, class: StorageClass) -> Option<String> {
    match class {
        StorageClass::Input => match facts.builtins.get(&id) {
            Some(b) if UNIFORM_BUILTINS.contains(b) => None,
            Some(b) => Some(format!("the built-in {b:?}")),
            None => Some("a stage input".into()),
        },
        StorageClass::IncomingRayPayloadKHR | StorageClass::RayPayloadKHR => Some("a ray payload".into()),
        StorageClass::HitAttributeKHR => Some("the hit attributes".into()),
        StorageClass::IncomingCallableDataKHR | StorageClass::CallableDataKHR => Some("callable data".into()),
        _ => None,
    }
}
