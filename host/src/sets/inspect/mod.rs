//! What a stage keeps alive across each trace call: for every `OpTraceRayKHR` and
//! `OpExecuteCallableKHR` a module's entry points reach, the values and variables live across
//! it (what a driver must save before the call and restore after), where each comes from, and
//! the loops around the call. `twinray inspect` reports it beside the stack size the driver
//! gives each stage.
//!
//! The analysis (`flow`) is liveness on each function's control-flow graph. A call inside a
//! function another calls is reached through every call path from the entry point: what the
//! callers keep across their calls is kept across the trace too. [`normalise`] first puts a
//! module in the form a driver's compiler works on (functions inlined, local variables turned
//! into SSA values by SPIRV-Tools), so that glslang's unoptimised output and rust-gpu's are
//! measured alike.

mod bits;
mod facts;
mod flow;
#[cfg(test)]
mod tests;

use facts::Facts;
use flow::Flow;
use rspirv::dr::{self, Instruction, Operand};
use rspirv::spirv::{Op, StorageClass, Word};
use serde::Serialize;
use std::collections::HashMap;
use std::io::Write;
use std::process::{Command, Stdio};

/// One value or variable live across a call.
#[derive(Clone, Debug, Serialize)]
pub struct Live {
    pub id: Word,
    /// "value" (an SSA value) or "variable" (memory of the function: a variable or a pointer
    /// parameter, or a private global).
    pub kind: &'static str,
    /// Its type (a variable's: what it holds).
    pub ty: String,
    pub bytes: u64,
    /// The instruction that makes it: `OpPhi`, `OpLoad`, `OpVariable`, ...
    pub made_by: String,
    /// The source line and name the module left for it, if any.
    pub origin: Option<String>,
    /// The function it belongs to.
    pub function: String,
}

/// A loop around a call.
#[derive(Clone, Debug, Serialize)]
pub struct LoopInfo {
    /// The label of its header block.
    pub header: Word,
    pub function: String,
    pub origin: Option<String>,
    /// Values its header's phis carry from one iteration to the next, and their bytes.
    pub carried: usize,
    pub carried_bytes: u64,
}

/// One trace or callable call, reached by one call path from an entry point.
#[derive(Clone, Debug, Serialize)]
pub struct Site {
    /// `OpTraceRayKHR` or `OpExecuteCallableKHR` (or their NV forms).
    pub call: String,
    /// The call's source line where the module has it, else its block.
    pub at: String,
    /// The functions from the entry point to the call, outermost first.
    pub path: Vec<String>,
    /// Outermost first, the callers' loops before the callee's.
    pub loops: Vec<LoopInfo>,
    /// Largest first.
    pub live: Vec<Live>,
    pub bytes: u64,
}

/// The calls one entry point reaches.
#[derive(Clone, Debug, Serialize)]
pub struct Entry {
    pub name: String,
    /// Its execution model (`RayGenerationKHR`, `ClosestHitKHR`, ...).
    pub model: String,
    pub sites: Vec<Site>,
}

impl Entry {
    /// The most bytes any of its calls keeps.
    pub fn max_bytes(&self) -> u64 {
        self.sites.iter().map(|s| s.bytes).max().unwrap_or(0)
    }
}

/// SPIRV-Tools passes that put a module in the form a driver's compiler analyses: one function
/// per entry point, local variables as SSA values (arrays indexed at run time stay variables).
/// None of them moves code across a call or changes a loop's shape. Branches on constants go
/// first, as every driver drops them: rust-gpu leaves core's `if false { panic }` checks, which
/// would otherwise become return flags carried through the loops.
pub const NORMALISE_PASSES: [&str; 10] = [
    "--eliminate-dead-branches",
    "--merge-return",
    "--inline-entry-points-exhaustive",
    "--eliminate-dead-functions",
    "--eliminate-dead-branches",
    "--scalar-replacement=0",
    "--eliminate-local-single-block",
    "--eliminate-local-single-store",
    "--ssa-rewrite",
    "--eliminate-dead-code-aggressive",
];

/// What specialising a module adds before [`NORMALISE_PASSES`]: every specialisation constant
/// made the plain constant the pipeline gives it (or its default), and the expressions of them
/// that glslang leaves as `OpSpecConstantOp` folded, so that the branches on them go as a
/// driver's would.
const SPECIALISE_PASSES: [&str; 2] = ["--freeze-spec-const", "--fold-spec-const-op-composite"];

/// What specialising adds after [`NORMALISE_PASSES`]: rust-gpu tests a specialisation constant
/// with plain instructions inside the function, which only constant propagation folds.
const SPECIALISED_CLEANUP: [&str; 3] = ["--ccp", "--eliminate-dead-branches", "--eliminate-dead-code-aggressive"];

/// `bytes` through [`NORMALISE_PASSES`] (`spirv-opt`, which `cargo xtask setup` installs);
/// first specialised, if `spec` holds (constant id, value) pairs, as a pipeline that passes
/// those values would be.
pub fn normalise(bytes: &[u8], spec: &[(u32, u32)]) -> Result<Vec<u8>, String> {
    let env = twinray_shared::catalog::target_env(bytes);
    let mut command = Command::new("spirv-opt");
    command.arg(format!("--target-env={env}"));
    if !spec.is_empty() {
        let values: Vec<String> = spec.iter().map(|(id, value)| format!("{id}:{value}")).collect();
        command.arg(format!("--set-spec-const-default-value={}", values.join(" "))).args(SPECIALISE_PASSES);
    }
    command.args(NORMALISE_PASSES);
    if !spec.is_empty() {
        command.args(SPECIALISED_CLEANUP);
    }
    let mut child = command
        .args(["-", "-o", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("spirv-opt did not start ({e}): run `cargo xtask setup`, or pass --raw"))?;
    let mut stdin = child.stdin.take().ok_or("spirv-opt has no input")?;
    let input = bytes.to_vec();
    let feeder = std::thread::spawn(move || stdin.write_all(&input));
    let out = child.wait_with_output().map_err(|e| format!("spirv-opt: {e}"))?;
    let _ = feeder.join();
    if !out.status.success() || out.stdout.is_empty() {
        let said = String::from_utf8_lossy(&out.stderr);
        return Err(format!("spirv-opt could not normalise the module: {}", said.lines().next().unwrap_or("")));
    }
    Ok(out.stdout)
}

/// Every entry point of the module `bytes`, with the calls it reaches and what is live across
/// each.
pub fn inspect(bytes: &[u8]) -> Result<Vec<Entry>, String> {
    if bytes.len() < 20 || !bytes.len().is_multiple_of(4) {
        return Err(format!("{} bytes is not a SPIR-V module", bytes.len()));
    }
    let words: Vec<u32> = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    if words[0] != rspirv::spirv::MAGIC_NUMBER {
        return Err("not a SPIR-V module (no magic number)".into());
    }
    let module = dr::load_words(words).map_err(|e| format!("reading the module: {e}"))?;
    let study = Study::new(&module);
    let mut entries = Vec::new();
    for e in &module.entry_points {
        let (Some(Operand::ExecutionModel(model)), Some(function), Some(Operand::LiteralString(name))) =
            (e.operands.first(), e.operands.get(1).and_then(Operand::id_ref_any), e.operands.get(2))
        else {
            continue;
        };
        let mut sites = Vec::new();
        study.walk(function, &Frame::default(), &mut sites);
        entries.push(Entry { name: name.clone(), model: format!("{model:?}"), sites });
    }
    Ok(entries)
}

/// What callers keep across the calls that lead to a function.
#[derive(Clone, Default)]
struct Frame {
    path: Vec<String>,
    live: Vec<Live>,
    loops: Vec<LoopInfo>,
    /// A pointer parameter of the function: the caller's variable it points into.
    params: HashMap<Word, Word>,
    depth: usize,
}

/// The module, its facts, and each function's liveness.
struct Study<'m> {
    facts: Facts,
    flows: HashMap<Word, Flow<'m>>,
    /// Every instruction that makes an id: in functions, parameters and private globals.
    makers: HashMap<Word, &'m Instruction>,
}

impl<'m> Study<'m> {
    fn new(module: &'m dr::Module) -> Study<'m> {
        let facts = Facts::of(module);
        let privates: Vec<&Instruction> = module
            .types_global_values
            .iter()
            .filter(|i| i.class.opcode == Op::Variable)
            .filter(|i| matches!(i.operands.first(), Some(Operand::StorageClass(StorageClass::Private))))
            .collect();
        let private_ids: Vec<Word> = privates.iter().filter_map(|i| i.result_id).collect();
        let mut makers: HashMap<Word, &Instruction> =
            privates.iter().filter_map(|i| Some((i.result_id?, *i))).collect();
        let mut flows = HashMap::new();
        for f in &module.functions {
            let Some(id) = f.def.as_ref().and_then(|d| d.result_id) else { continue };
            let all = f.parameters.iter().chain(f.blocks.iter().flat_map(|b| b.instructions.iter()));
            makers.extend(all.filter_map(|i| Some((i.result_id?, i))));
            flows.insert(id, Flow::of(f, &facts, &private_ids));
        }
        Study { facts, flows, makers }
    }

    fn function_name(&self, id: Word) -> String {
        self.facts.function_names.get(&id).cloned().unwrap_or_else(|| format!("%{id}"))
    }

    /// Every call site reachable from `function`, with `frame` from its callers.
    fn walk(&self, function: Word, frame: &Frame, sites: &mut Vec<Site>) {
        // SPIR-V forbids recursion; a hostile module may still have it.
        let Some(flow) = self.flows.get(&function).filter(|_| frame.depth < 64) else { return };
        let name = self.function_name(function);
        for (b, block) in flow.function.blocks.iter().enumerate() {
            let label = block.label.as_ref().and_then(|l| l.result_id).unwrap_or(0);
            for (n, i) in block.instructions.iter().enumerate() {
                let op = i.class.opcode;
                let is_call = matches!(
                    op,
                    Op::TraceRayKHR
                        | Op::ExecuteCallableKHR
                        | Op::TraceNV
                        | Op::ExecuteCallableNV
                        | Op::TraceRayMotionNV
                );
                if !is_call && op != Op::FunctionCall {
                    continue;
                }
                let mut inner = frame.clone();
                inner.path.push(name.clone());
                inner.live.extend(self.live(flow, &name, flow.live_after(b, n), &frame.params));
                inner.loops.extend(flow.loops_around(b).into_iter().map(|l| self.loop_info(l, &name)));
                if is_call {
                    sites.push(self.site(i, (label, n), inner));
                } else if let Some(callee) = i.operands.first().and_then(Operand::id_ref_any) {
                    inner.params = self.arguments(flow, callee, i, &frame.params);
                    inner.depth += 1;
                    self.walk(callee, &inner, sites);
                }
            }
        }
    }

    /// Pointer parameters of `callee`, mapped to the variables `call` passes them.
    fn arguments(
        &self,
        flow: &Flow,
        callee: Word,
        call: &Instruction,
        outer: &HashMap<Word, Word>,
    ) -> HashMap<Word, Word> {
        let Some(target) = self.flows.get(&callee) else { return HashMap::new() };
        let params = target.function.parameters.iter().filter_map(|p| p.result_id);
        let args = call.operands.iter().skip(1).filter_map(Operand::id_ref_any);
        params
            .zip(args)
            .filter_map(|(p, a)| {
                let root = flow.root(a)?;
                Some((p, outer.get(&root).copied().unwrap_or(root)))
            })
            .collect()
    }

    fn site(&self, call: &Instruction, (label, n): (Word, usize), frame: Frame) -> Site {
        let mut live = frame.live;
        live.sort_by(|a, b| b.bytes.cmp(&a.bytes).then(a.id.cmp(&b.id)));
        live.dedup_by_key(|l| l.id);
        let at = self.facts.line_at(label, n).cloned().unwrap_or_else(|| format!("block %{label}"));
        Site {
            call: format!("Op{:?}", call.class.opcode),
            at,
            path: frame.path,
            loops: frame.loops,
            bytes: live.iter().map(|l| l.bytes).sum(),
            live,
        }
    }

    /// The ids of `flow` live across a call, described; a pointer parameter is described as
    /// the caller's variable it points into, so that it is counted once.
    fn live(&self, flow: &Flow, function: &str, ids: Vec<Word>, params: &HashMap<Word, Word>) -> Vec<Live> {
        ids.into_iter()
            .filter(|id| !flow.is_pointer_into_variable(*id))
            .filter_map(|id| self.describe(params.get(&id).copied().unwrap_or(id), function))
            .collect()
    }

    fn describe(&self, id: Word, function: &str) -> Option<Live> {
        let maker = self.makers.get(&id)?;
        let ty = maker.result_type?;
        let variable = maker.class.opcode == Op::Variable
            || (maker.class.opcode == Op::FunctionParameter && self.facts.storage(ty) == Some(StorageClass::Function));
        let held = if variable { self.facts.pointee(ty).unwrap_or(ty) } else { ty };
        Some(Live {
            id,
            kind: if variable { "variable" } else { "value" },
            ty: self.facts.spell(held),
            bytes: self.facts.size(held),
            made_by: format!("Op{:?}", maker.class.opcode),
            origin: self.facts.origin(id),
            function: function.to_string(),
        })
    }

    fn loop_info(&self, l: &flow::Loop, function: &str) -> LoopInfo {
        let carried = l.carried.iter().filter_map(|id| self.describe(*id, function));
        let bytes: Vec<u64> = carried.map(|c| c.bytes).collect();
        LoopInfo {
            header: l.header,
            function: function.to_string(),
            origin: l
                .carried
                .first()
                .and_then(|p| self.facts.origin(*p))
                .or_else(|| self.facts.line_at(l.header, 0).cloned()),
            carried: bytes.len(),
            carried_bytes: bytes.iter().sum(),
        }
    }
}
