//! What a module declares, read once: decorations, variables, types and constants, for the
//! uniformity check and its taint analysis (a module of its own so that neither imports the
//! other's parent back).

use rspirv::dr::{self, Instruction, Operand};
use rspirv::spirv::{BuiltIn, Capability, Decoration, Op, StorageClass, Word};
use std::collections::{HashMap, HashSet};

/// What the module declares: decorations, variables, types and constants.
#[derive(Default)]
pub(super) struct Facts {
    pub(super) builtins: HashMap<Word, BuiltIn>,
    pub(super) bindings: HashMap<Word, (u32, u32)>,
    pub(super) non_uniform: HashSet<Word>,
    /// Variable id: (storage class, pointer type).
    pub(super) variables: HashMap<Word, (StorageClass, Word)>,
    pub(super) types: HashMap<Word, Instruction>,
    pub(super) constants: HashSet<Word>,
}

impl Facts {
    pub(super) fn of(module: &dr::Module) -> Facts {
        let mut facts = Facts::default();
        for a in &module.annotations {
            let (Some(Operand::IdRef(id)), Some(Operand::Decoration(d))) = (a.operands.first(), a.operands.get(1))
            else {
                continue;
            };
            match (a.class.opcode, d, a.operands.get(2)) {
                (Op::Decorate, Decoration::BuiltIn, Some(Operand::BuiltIn(b))) => {
                    facts.builtins.insert(*id, *b);
                }
                (Op::Decorate, Decoration::DescriptorSet, Some(Operand::LiteralBit32(set))) => {
                    facts.bindings.entry(*id).or_insert((0, 0)).0 = *set;
                }
                (Op::Decorate, Decoration::Binding, Some(Operand::LiteralBit32(binding))) => {
                    facts.bindings.entry(*id).or_insert((0, 0)).1 = *binding;
                }
                (Op::Decorate, Decoration::NonUniform, _) => {
                    facts.non_uniform.insert(*id);
                }
                _ => {}
            }
        }
        let locals = module.functions.iter().flat_map(|f| f.blocks.iter().flat_map(|b| b.instructions.iter()));
        for i in module.types_global_values.iter().chain(locals) {
            let Some(id) = i.result_id else { continue };
            match i.class.opcode {
                Op::Variable => {
                    if let (Some(Operand::StorageClass(class)), Some(ty)) = (i.operands.first(), i.result_type) {
                        facts.variables.insert(id, (*class, ty));
                    }
                }
                op if is_constant(op) => {
                    facts.constants.insert(id);
                }
                op if i.result_type.is_none() && format!("{op:?}").starts_with("Type") => {
                    facts.types.insert(id, i.clone());
                }
                _ => {}
            }
        }
        facts
    }

    /// The type `pointer` points to.
    pub(super) fn pointee(&self, pointer: Word) -> Option<&Instruction> {
        let ty = self.types.get(&pointer)?;
        (ty.class.opcode == Op::TypePointer).then(|| self.types.get(&ty.operands.get(1)?.id_ref_any()?)).flatten()
    }

    /// The capability non-uniform indexing of an array of `element` needs, in storage `class`.
    pub(super) fn capability(&self, element: Word, class: StorageClass) -> Capability {
        let ty = self.types.get(&element);
        match ty.map(|t| t.class.opcode) {
            Some(Op::TypeImage) => match ty.and_then(|t| t.operands.get(5)) {
                Some(Operand::LiteralBit32(2)) => Capability::StorageImageArrayNonUniformIndexing,
                _ => Capability::SampledImageArrayNonUniformIndexing,
            },
            Some(Op::TypeStruct) if class == StorageClass::Uniform => Capability::UniformBufferArrayNonUniformIndexing,
            Some(Op::TypeStruct) => Capability::StorageBufferArrayNonUniformIndexing,
            _ => Capability::SampledImageArrayNonUniformIndexing,
        }
    }
}

pub(super) fn is_constant(op: Op) -> bool {
    matches!(
        op,
        Op::Constant
            | Op::ConstantTrue
            | Op::ConstantFalse
            | Op::ConstantNull
            | Op::ConstantComposite
            | Op::SpecConstant
            | Op::SpecConstantTrue
            | Op::SpecConstantFalse
            | Op::SpecConstantComposite
            | Op::SpecConstantOp
            | Op::Undef
    )
}

/// Built-ins the same for every invocation of a dispatch.
pub(super) const UNIFORM_BUILTINS: [BuiltIn; 5] = [
    BuiltIn::LaunchSizeKHR,
    BuiltIn::NumWorkgroups,
    BuiltIn::WorkgroupSize,
    BuiltIn::SubgroupSize,
    BuiltIn::NumSubgroups,
];
