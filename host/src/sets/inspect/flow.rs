//! Liveness on one function's control-flow graph: a backward dataflow analysis over its SSA
//! values (phi operands live on the edge they come in by) and its variables (a read of any
//! part makes the variable live; only a store of the whole variable ends that), iterated to a
//! fixed point, so values carried around loops are found. And the function's natural loops,
//! from the back edges of a depth-first walk (SPIR-V's structured control flow is reducible).

use super::bits::Bits;
use rspirv::dr::{self, Instruction, Operand};
use rspirv::spirv::{Op, StorageClass, Word};
use std::collections::HashMap;

use super::facts::Facts;

/// What a function keeps, block by block.
pub struct Flow<'m> {
    pub function: &'m dr::Function,
    /// Tracked ids (values, variables, parameters), densely numbered.
    pub ids: Vec<Word>,
    index: HashMap<Word, usize>,
    /// Pointer id: the variable (or pointer parameter) it points into.
    roots: HashMap<Word, Word>,
    /// Private variables: every call may read them.
    privates: Vec<Word>,
    live_out: Vec<Bits>,
    pub loops: Vec<Loop>,
}

/// A natural loop.
pub struct Loop {
    /// The header block's label.
    pub header: Word,
    /// Blocks in the loop, by index.
    body: Vec<bool>,
    /// The values its header's phis carry from one iteration to the next.
    pub carried: Vec<Word>,
}

impl<'m> Flow<'m> {
    pub fn of(function: &'m dr::Function, facts: &Facts, privates: &[Word]) -> Flow<'m> {
        let mut flow = Flow {
            function,
            ids: Vec::new(),
            index: HashMap::new(),
            roots: HashMap::new(),
            privates: privates.to_vec(),
            live_out: Vec::new(),
            loops: Vec::new(),
        };
        flow.number(facts);
        let succs = successors(function);
        flow.solve(&succs);
        flow.loops = natural_loops(function, &succs);
        flow
    }

    /// Numbers every value, variable and parameter of the function; finds each pointer's root.
    fn number(&mut self, facts: &Facts) {
        for v in self.privates.clone() {
            self.track(v);
        }
        for p in &self.function.parameters {
            let Some(id) = p.result_id else { continue };
            self.track(id);
            if p.result_type.and_then(|t| facts.storage(t)) == Some(StorageClass::Function) {
                self.roots.insert(id, id);
            }
        }
        // Values computed from constants alone are constants a driver folds: not kept.
        let mut constant = facts.constants_and_imports.clone();
        for i in self.body() {
            let Some(id) = i.result_id else { continue };
            if matches!(i.class.opcode, Op::Label | Op::Undef) {
                continue;
            }
            let operands = i.operands.iter().filter_map(Operand::id_ref_any);
            if is_pure(i.class.opcode) && operands.clone().all(|o| constant.contains(&o)) {
                constant.insert(id);
                continue;
            }
            self.track(id);
            if i.class.opcode == Op::Variable {
                self.roots.insert(id, id);
            }
        }
        for &v in &self.privates {
            self.roots.insert(v, v);
        }
        // A pointer derived from a rooted one shares its root; ids may be used above where
        // they are laid out, so repeat until nothing is added.
        loop {
            let before = self.roots.len();
            for i in self.body() {
                let derived = matches!(
                    i.class.opcode,
                    Op::AccessChain | Op::InBoundsAccessChain | Op::PtrAccessChain | Op::CopyObject
                );
                let base = i.operands.first().and_then(Operand::id_ref_any);
                if let (true, Some(id), Some(root)) = (derived, i.result_id, base.and_then(|b| self.roots.get(&b))) {
                    let root = *root;
                    self.roots.insert(id, root);
                }
            }
            if self.roots.len() == before {
                break;
            }
        }
    }

    fn track(&mut self, id: Word) {
        if !self.index.contains_key(&id) {
            self.index.insert(id, self.ids.len());
            self.ids.push(id);
        }
    }

    fn body(&self) -> impl Iterator<Item = &'m Instruction> {
        self.function.blocks.iter().flat_map(|b| b.instructions.iter())
    }

    /// The variable a pointer points into, when it is one this function keeps.
    pub fn root(&self, pointer: Word) -> Option<Word> {
        self.roots.get(&pointer).copied()
    }

    /// Whether `id` is a pointer into a variable (counted as the variable, not by itself).
    pub fn is_pointer_into_variable(&self, id: Word) -> bool {
        self.roots.get(&id).is_some_and(|root| *root != id)
    }

    /// `live` before instruction `i`, given `live` after it.
    fn step(&self, i: &Instruction, live: &mut Bits) {
        let (uses, defs) = self.effects(i);
        for d in defs {
            live.remove(d);
        }
        for u in uses {
            live.insert(u);
        }
    }

    /// (used, defined) tracked indices of `i`; phi operands are the edges' business.
    fn effects(&self, i: &Instruction) -> (Vec<usize>, Vec<usize>) {
        let mut uses = Vec::new();
        let mut defs: Vec<usize> = i.result_id.and_then(|id| self.index.get(&id)).copied().into_iter().collect();
        let op = i.class.opcode;
        if op == Op::Phi {
            return (uses, defs);
        }
        for (n, operand) in i.operands.iter().enumerate() {
            let Some(id) = operand.id_ref_any() else { continue };
            let written = n == 0 && matches!(op, Op::Store | Op::CopyMemory);
            let addressed = n == 0 && matches!(op, Op::AccessChain | Op::InBoundsAccessChain | Op::PtrAccessChain);
            match self.roots.get(&id) {
                // A store of the whole variable ends its life; of a part, it reads nothing.
                Some(&root) if written => {
                    if root == id {
                        defs.extend(self.index.get(&root));
                    }
                }
                Some(_) if addressed => {}
                Some(&root) => {
                    uses.extend(self.index.get(&root));
                    if root != id {
                        uses.extend(self.index.get(&id));
                    }
                }
                None => uses.extend(self.index.get(&id)),
            }
        }
        if op == Op::FunctionCall {
            uses.extend(self.privates.iter().filter_map(|p| self.index.get(p)));
        }
        (uses, defs)
    }

    /// Solves live-out of every block to a fixed point.
    fn solve(&mut self, succs: &[Vec<usize>]) {
        let n = self.function.blocks.len();
        let empty = Bits::new(self.ids.len());
        let (mut gen, mut kill) = (vec![empty.clone(); n], vec![empty.clone(); n]);
        for (b, block) in self.function.blocks.iter().enumerate() {
            for i in block.instructions.iter().rev() {
                let (uses, defs) = self.effects(i);
                for d in defs {
                    gen[b].remove(d);
                    kill[b].insert(d);
                }
                for u in uses {
                    gen[b].insert(u);
                }
            }
        }
        let phi_uses = self.phi_uses(succs);
        self.live_out = vec![empty.clone(); n];
        let mut live_in = vec![empty; n];
        let mut changed = true;
        while changed {
            changed = false;
            for b in (0..n).rev() {
                let mut out = phi_uses[b].clone();
                for &s in &succs[b] {
                    out.union(&live_in[s]);
                }
                let mut inn = out.clone();
                inn.subtract(&kill[b]);
                inn.union(&gen[b]);
                if inn != live_in[b] || out != self.live_out[b] {
                    changed = true;
                    live_in[b] = inn;
                    self.live_out[b] = out;
                }
            }
        }
    }

    /// Per block: the values its successors' phis take from it.
    fn phi_uses(&self, succs: &[Vec<usize>]) -> Vec<Bits> {
        let labels = labels(self.function);
        let mut out = vec![Bits::new(self.ids.len()); self.function.blocks.len()];
        for (b, block) in self.function.blocks.iter().enumerate() {
            for i in block.instructions.iter().filter(|i| i.class.opcode == Op::Phi) {
                for pair in i.operands.chunks(2) {
                    let (Some(value), Some(from)) = (pair[0].id_ref_any(), pair.get(1).and_then(Operand::id_ref_any))
                    else {
                        continue;
                    };
                    if let (Some(&v), Some(&p)) = (self.index.get(&value), labels.get(&from)) {
                        debug_assert!(succs[p].contains(&b));
                        out[p].insert(v);
                    }
                }
            }
        }
        out
    }

    /// Tracked ids live just after instruction `at` of block `block` (what must survive it),
    /// not counting what `at` itself defines.
    pub fn live_after(&self, block: usize, at: usize) -> Vec<Word> {
        let mut live = self.live_out[block].clone();
        for i in self.function.blocks[block].instructions[at + 1..].iter().rev() {
            self.step(i, &mut live);
        }
        let own = self.function.blocks[block].instructions[at].result_id;
        live.iter().map(|n| self.ids[n]).filter(|id| Some(*id) != own).collect()
    }

    /// The loops around block `block`, outermost first.
    pub fn loops_around(&self, block: usize) -> Vec<&Loop> {
        let mut around: Vec<&Loop> = self.loops.iter().filter(|l| l.body[block]).collect();
        around.sort_by_key(|l| std::cmp::Reverse(l.body.iter().filter(|b| **b).count()));
        around
    }
}

/// Whether `op` computes its result from its operands alone (no memory, no invocation state).
fn is_pure(op: Op) -> bool {
    const IMPURE: [&str; 16] = [
        "Load",
        "Phi",
        "FunctionCall",
        "Variable",
        "FunctionParameter",
        "ArrayLength",
        "Atomic",
        "Image",
        "Sampled",
        "Ray",
        "Trace",
        "Report",
        "Execute",
        "Group",
        "Subgroup",
        "ReadClock",
    ];
    let name = format!("{op:?}");
    !IMPURE.iter().any(|p| name.starts_with(p))
}

fn labels(function: &dr::Function) -> HashMap<Word, usize> {
    function.blocks.iter().enumerate().filter_map(|(n, b)| Some((b.label.as_ref()?.result_id?, n))).collect()
}

/// Each block's successors, by index.
fn successors(function: &dr::Function) -> Vec<Vec<usize>> {
    let labels = labels(function);
    function
        .blocks
        .iter()
        .map(|b| {
            let Some(last) = b.instructions.last() else { return Vec::new() };
            let targets: Vec<Word> = match last.class.opcode {
                Op::Branch | Op::BranchConditional => last.operands.iter().filter_map(Operand::id_ref_any).collect(),
                // Selector, default, then (literal, label) pairs.
                Op::Switch => last.operands.iter().skip(1).filter_map(Operand::id_ref_any).collect(),
                _ => Vec::new(),
            };
            let mut out: Vec<usize> = targets.iter().filter_map(|t| labels.get(t).copied()).collect();
            out.dedup();
            out
        })
        .collect()
}

/// Natural loops: for each back edge (to a block on the walk's stack), its header and every
/// block that reaches the edge's tail without passing the header.
fn natural_loops(function: &dr::Function, succs: &[Vec<usize>]) -> Vec<Loop> {
    let n = succs.len();
    let mut preds = vec![Vec::new(); n];
    for (b, s) in succs.iter().enumerate() {
        for &t in s {
            preds[t].push(b);
        }
    }
    let (mut state, mut back) = (vec![0u8; n], Vec::new());
    let mut stack = vec![(0usize, 0usize)];
    if n > 0 {
        state[0] = 1;
    }
    while let Some((b, next)) = stack.pop() {
        if let Some(&t) = succs[b].get(next) {
            stack.push((b, next + 1));
            match state[t] {
                0 => {
                    state[t] = 1;
                    stack.push((t, 0));
                }
                1 => back.push((b, t)),
                _ => {}
            }
        } else {
            state[b] = 2;
        }
    }
    let mut loops: Vec<Loop> = Vec::new();
    for (tail, header) in back {
        let mut body = vec![false; n];
        body[header] = true;
        let mut work = vec![tail];
        while let Some(b) = work.pop() {
            if !body[b] {
                body[b] = true;
                work.extend(&preds[b]);
            }
        }
        let label = function.blocks[header].label.as_ref().and_then(|l| l.result_id).unwrap_or(0);
        if let Some(existing) = loops.iter_mut().find(|l| l.header == label) {
            existing.body.iter_mut().zip(&body).for_each(|(a, b)| *a |= *b);
            continue;
        }
        let carried = function.blocks[header]
            .instructions
            .iter()
            .filter(|i| i.class.opcode == Op::Phi)
            .filter_map(|i| i.result_id)
            .collect();
        loops.push(Loop { header: label, body, carried });
    }
    loops
}
