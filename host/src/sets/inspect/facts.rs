//! What a module declares that the liveness report needs: the size and spelling of each type,
//! which ids are module-level (types, constants, global variables: never saved across a call),
//! and where each value comes from (the source line rust-gpu or glslang left, its `OpName`).

use rspirv::dr::{self, Instruction, Operand};
use rspirv::spirv::{Op, StorageClass, Word};
use std::collections::{HashMap, HashSet};

/// NonSemantic.Shader.DebugInfo.100's `DebugSource` and `DebugLine` (glslang `-gVS`).
const DEBUG_SOURCE: u32 = 35;
const DEBUG_LINE: u32 = 103;

#[derive(Default)]
pub struct Facts {
    types: HashMap<Word, Instruction>,
    /// Integer constants, for array lengths.
    constants: HashMap<Word, u64>,
    /// Constants (specialisation constants too), undefs and extended instruction sets: what
    /// a value computed from alone is a constant too.
    pub constants_and_imports: HashSet<Word>,
    names: HashMap<Word, String>,
    /// Result id: "file:line" of the last `OpLine` (or `DebugLine`) before it.
    lines: HashMap<Word, String>,
    /// (block label, instruction index): the same, for instructions without a result.
    lines_at: HashMap<(Word, usize), String>,
    /// Function id: its name, when the module names it.
    pub function_names: HashMap<Word, String>,
}

impl Facts {
    pub fn of(module: &dr::Module) -> Facts {
        let mut facts = Facts::default();
        let strings: HashMap<Word, String> = module
            .debug_string_source
            .iter()
            .filter(|i| i.class.opcode == Op::String)
            .filter_map(|i| Some((i.result_id?, string(i.operands.first()?)?)))
            .collect();
        for i in &module.debug_names {
            if let (Op::Name, Some(Operand::IdRef(id)), Some(name)) =
                (i.class.opcode, i.operands.first(), i.operands.get(1).and_then(string))
            {
                facts.names.insert(*id, name);
            }
        }
        for i in &module.types_global_values {
            let Some(id) = i.result_id else { continue };
            if i.class.opcode != Op::Variable {
                facts.constants_and_imports.insert(id);
            }
            if i.result_type.is_none() {
                facts.types.insert(id, i.clone());
            } else if i.class.opcode == Op::Constant {
                if let Some(Operand::LiteralBit32(v)) = i.operands.first() {
                    facts.constants.insert(id, u64::from(*v));
                }
            }
        }
        facts.constants_and_imports.extend(module.ext_inst_imports.iter().filter_map(|i| i.result_id));
        let sources = debug_sources(module, &strings);
        for f in &module.functions {
            if let Some(id) = f.def.as_ref().and_then(|d| d.result_id) {
                if let Some(name) = facts.names.get(&id) {
                    facts.function_names.insert(id, name.clone());
                }
            }
            facts.note_lines(f, &strings, &sources);
        }
        facts
    }

    /// Remembers the source line of every result in `f`.
    fn note_lines(&mut self, f: &dr::Function, strings: &HashMap<Word, String>, sources: &HashMap<Word, String>) {
        for block in &f.blocks {
            let label = block.label.as_ref().and_then(|l| l.result_id).unwrap_or(0);
            let mut line: Option<String> = None;
            for (n, i) in block.instructions.iter().enumerate() {
                let op = i.class.opcode;
                match op {
                    Op::Line => {
                        let file = i.operands.first().and_then(Operand::id_ref_any).and_then(|s| strings.get(&s));
                        line = match (file, i.operands.get(1)) {
                            (Some(file), Some(Operand::LiteralBit32(n))) => Some(format!("{file}:{n}")),
                            _ => None,
                        };
                    }
                    Op::NoLine => line = None,
                    Op::ExtInst if ext_opcode(i) == Some(DEBUG_LINE) => {
                        let source = i.operands.get(2).and_then(Operand::id_ref_any).and_then(|s| sources.get(&s));
                        let n = i.operands.get(3).and_then(Operand::id_ref_any).and_then(|c| self.constants.get(&c));
                        line = source.zip(n).map(|(file, n)| format!("{file}:{n}"));
                    }
                    _ => {}
                }
                if let Some(line) = &line {
                    self.lines_at.insert((label, n), line.clone());
                    if let Some(id) = i.result_id {
                        self.lines.insert(id, line.clone());
                    }
                    // glslang declares variables before any line: a variable's is that of
                    // its first store.
                    if let (Op::Store, Some(target)) = (op, i.operands.first().and_then(Operand::id_ref_any)) {
                        self.lines.entry(target).or_insert_with(|| line.clone());
                    }
                }
            }
        }
    }

    /// Bytes a value of type `ty` occupies when a driver keeps it: its scalars' widths summed,
    /// booleans as 4 (a register). Pointers, images, samplers and acceleration structures are
    /// 0: a driver can recompute or reload them from their descriptors rather than save them.
    pub fn size(&self, ty: Word) -> u64 {
        let Some(t) = self.types.get(&ty) else { return 0 };
        let literal = |n: usize| match t.operands.get(n) {
            Some(Operand::LiteralBit32(v)) => u64::from(*v),
            _ => 0,
        };
        let id = |n: usize| t.operands.get(n).and_then(Operand::id_ref_any).unwrap_or(0);
        match t.class.opcode {
            Op::TypeBool => 4,
            Op::TypeInt | Op::TypeFloat => literal(0) / 8,
            Op::TypeVector | Op::TypeMatrix => literal(1) * self.size(id(0)),
            Op::TypeArray => self.constants.get(&id(1)).copied().unwrap_or(0) * self.size(id(0)),
            Op::TypeStruct => t.operands.iter().filter_map(Operand::id_ref_any).map(|m| self.size(m)).sum(),
            _ => 0,
        }
    }

    /// `ty` as a reader would write it: `f32`, `vec3<f32>`, `struct %12`, `ptr<Function, f32>`.
    pub fn spell(&self, ty: Word) -> String {
        let Some(t) = self.types.get(&ty) else { return format!("%{ty}") };
        let literal = |n: usize| match t.operands.get(n) {
            Some(Operand::LiteralBit32(v)) => *v,
            _ => 0,
        };
        let id = |n: usize| t.operands.get(n).and_then(Operand::id_ref_any).unwrap_or(0);
        match t.class.opcode {
            Op::TypeBool => "bool".into(),
            Op::TypeInt if literal(1) == 1 => format!("i{}", literal(0)),
            Op::TypeInt => format!("u{}", literal(0)),
            Op::TypeFloat => format!("f{}", literal(0)),
            Op::TypeVector => format!("vec{}<{}>", literal(1), self.spell(id(0))),
            Op::TypeMatrix => format!("mat{}<{}>", literal(1), self.spell(id(0))),
            Op::TypeArray => {
                format!("[{}; {}]", self.spell(id(0)), self.constants.get(&id(1)).copied().unwrap_or(0))
            }
            Op::TypeStruct => match self.names.get(&ty) {
                Some(name) => format!("struct {name}"),
                None => format!("struct %{ty}"),
            },
            Op::TypePointer => {
                format!("ptr<{:?}, {}>", self.storage(ty).unwrap_or(StorageClass::Generic), self.spell(id(1)))
            }
            op => format!("{op:?}").trim_start_matches("Type").to_string(),
        }
    }

    /// The storage class of pointer type `ty`.
    pub fn storage(&self, ty: Word) -> Option<StorageClass> {
        match self.types.get(&ty)?.operands.first()? {
            Operand::StorageClass(class) => Some(*class),
            _ => None,
        }
    }

    /// The type pointer type `ty` points to.
    pub fn pointee(&self, ty: Word) -> Option<Word> {
        let t = self.types.get(&ty)?;
        (t.class.opcode == Op::TypePointer).then(|| t.operands.get(1)?.id_ref_any()).flatten()
    }

    /// The source line of instruction `n` of the block labelled `label`, when the module has it.
    pub fn line_at(&self, label: Word, n: usize) -> Option<&String> {
        self.lines_at.get(&(label, n))
    }

    /// Where `id` comes from, in the words the module leaves: its source line and name where it
    /// has them.
    pub fn origin(&self, id: Word) -> Option<String> {
        match (self.lines.get(&id), self.names.get(&id)) {
            (Some(line), Some(name)) => Some(format!("{line} ({name})")),
            (Some(line), None) => Some(line.clone()),
            (None, Some(name)) => Some(format!("\"{name}\"")),
            (None, None) => None,
        }
    }
}

/// `DebugSource` id: its file's name.
fn debug_sources(module: &dr::Module, strings: &HashMap<Word, String>) -> HashMap<Word, String> {
    module
        .types_global_values
        .iter()
        .filter(|i| i.class.opcode == Op::ExtInst && ext_opcode(i) == Some(DEBUG_SOURCE))
        .filter_map(|i| Some((i.result_id?, strings.get(&i.operands.get(2)?.id_ref_any()?)?.clone())))
        .collect()
}

/// The instruction number of an `OpExtInst`.
fn ext_opcode(i: &Instruction) -> Option<u32> {
    match i.operands.get(1)? {
        Operand::LiteralExtInstInteger(n) => Some(*n),
        _ => None,
    }
}

fn string(o: &Operand) -> Option<String> {
    match o {
        Operand::LiteralString(s) => Some(s.clone()),
        _ => None,
    }
}
