//! `NoContraction` on the error-free arithmetic of `twinray_shared::exact`. A driver may fuse
//! and reassociate floating-point operations that are not so decorated (SPIR-V 2.15), and the
//! routines there hold only if each operation is done as written: lavapipe folded the error
//! term of an exact difference away, and the Rust set's transform of a grazed instance lost ten
//! times what its GLSL twin (whose results are `precise`) kept. rust-gpu has no way to say it
//! (an `OpDecorate` in `asm!` is dropped), so the build adds it: to every floating-point
//! operation in the functions whose name (`OpName`, before the debug names are stripped)
//! begins with `twinray_shared::exact::NAME_PREFIX`. That module keeps its functions out of
//! line so that they are found, and the pass then lets the driver inline them again.

use rspirv::binary::Assemble;
use rspirv::dr::{Instruction, Operand};
use rspirv::spirv::{Decoration, FunctionControl, Op, Word};
use std::collections::HashSet;
use twinray_shared::exact::NAME_PREFIX;

/// The operations the decoration applies to: arithmetic a driver could fuse or reorder.
const ARITHMETIC: [Op; 8] =
    [Op::FAdd, Op::FSub, Op::FMul, Op::FDiv, Op::FNegate, Op::FRem, Op::FMod, Op::VectorTimesScalar];

/// `bytes` with `NoContraction` on every floating-point operation of the exact functions, and
/// how many operations it decorated.
pub fn decorate(bytes: &[u8]) -> Result<(Vec<u8>, usize), String> {
    let mut module = crate::uniformity::load(bytes)?;
    let exact: HashSet<Word> = module
        .debug_names
        .iter()
        .filter(|i| i.class.opcode == Op::Name)
        .filter_map(|i| match (i.operands.first(), i.operands.get(1)) {
            (Some(Operand::IdRef(id)), Some(Operand::LiteralString(name))) if name.starts_with(NAME_PREFIX) => {
                Some(*id)
            }
            _ => None,
        })
        .collect();
    let decorated: HashSet<Word> = module
        .annotations
        .iter()
        .filter(|i| {
            i.class.opcode == Op::Decorate && i.operands.get(1) == Some(&Operand::Decoration(Decoration::NoContraction))
        })
        .filter_map(|i| match i.operands.first() {
            Some(Operand::IdRef(id)) => Some(*id),
            _ => None,
        })
        .collect();
    // Out of line only to be found: `DontInline` would keep them so in the driver, where a call
    // in an intersection stage cost the H200 up to 20% and hung a probe's trace.
    for function in module.functions.iter_mut().filter(|f| f.def_id().is_some_and(|id| exact.contains(&id))) {
        if let Some(def) = function.def.as_mut() {
            if let Some(Operand::FunctionControl(control)) = def.operands.first_mut() {
                *control = FunctionControl::NONE;
            }
        }
    }
    let mut ids: Vec<Word> = module
        .functions
        .iter()
        .filter(|f| f.def_id().is_some_and(|id| exact.contains(&id)))
        .flat_map(|f| f.blocks.iter().flat_map(|b| b.instructions.iter()))
        .filter(|i| ARITHMETIC.contains(&i.class.opcode))
        .filter_map(|i| i.result_id)
        .filter(|id| !decorated.contains(id))
        .collect();
    ids.sort_unstable();
    for &id in &ids {
        let operands = vec![Operand::IdRef(id), Operand::Decoration(Decoration::NoContraction)];
        module.annotations.push(Instruction::new(Op::Decorate, None, None, operands));
    }
    let bytes = module.assemble().iter().flat_map(|w| w.to_le_bytes()).collect();
    Ok((bytes, ids.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    use rspirv::dr;
    use rspirv::spirv::{AddressingModel, Capability, MemoryModel};

    /// A module with two functions alike, kept out of line, one named in the exact module: only
    /// its arithmetic is decorated, once however often the pass runs, and only it may be inlined.
    #[test]
    fn only_the_exact_functions_arithmetic_is_decorated() {
        let mut b = dr::Builder::new();
        b.capability(Capability::Shader);
        b.capability(Capability::Linkage);
        b.memory_model(AddressingModel::Logical, MemoryModel::GLSL450);
        let float = b.type_float(32, None);
        let signature = b.type_function(float, vec![float, float]);
        let function = |b: &mut dr::Builder, name: &str, ops: usize| {
            let id = b.begin_function(float, None, FunctionControl::DONT_INLINE, signature).unwrap();
            let (x, y) = (b.function_parameter(float).unwrap(), b.function_parameter(float).unwrap());
            b.begin_block(None).unwrap();
            let mut value = b.f_add(float, None, x, y).unwrap();
            for _ in 1..ops {
                value = b.f_sub(float, None, value, y).unwrap();
            }
            b.ret_value(value).unwrap();
            b.end_function().unwrap();
            b.name(id, name);
        };
        function(&mut b, &format!("{NAME_PREFIX}point_at"), 3);
        function(&mut b, "twinray_shared::surface::other", 2);
        let bytes: Vec<u8> = b.module().assemble().iter().flat_map(|w| w.to_le_bytes()).collect();
        let (once, count) = decorate(&bytes).expect("decorated");
        assert_eq!(count, 3);
        let module = crate::uniformity::load(&once).expect("module");
        let controls: Vec<_> = module.functions.iter().map(|f| f.def.as_ref().map(|d| d.operands[0].clone())).collect();
        let control = |c| Some(Operand::FunctionControl(c));
        assert_eq!(controls, [control(FunctionControl::NONE), control(FunctionControl::DONT_INLINE)]);
        let (twice, again) = decorate(&once).expect("decorated again");
        assert_eq!((again, twice), (0, once));
    }
}
