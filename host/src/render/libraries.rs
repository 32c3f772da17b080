//! Pipelines linked from libraries (`VK_KHR_pipeline_library`): ray generation, each miss
//! stage and each hit group compiled once into a library, and a scene's pipeline linked from
//! them in shader binding table order. A [`Libraries`] keeps what it compiled, keyed by the
//! exact SPIR-V and specialisation of each library, so every set and per-stage mix built
//! through it compiles each module once; on a device whose context keeps libraries
//! (`Context::keeps_libraries`), [`Libraries::of`] finds those of every pipeline the context
//! linked before.

use crate::error::Result;
use crate::util::checksum::Fnv;
use crate::vk::context::Context;
use crate::vk::pipeline::{GroupDesc, Interface, PipelineDesc, RtPipeline, StageDesc};
use ash::vk;
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;
use std::sync::Arc;
use twinray_shared::interface as contract;

/// What every library and linked pipeline of twinray's agree on: the payloads' and hit
/// attributes' largest sizes (the primary payload; a procedural hit's object-space normal) and
/// recursion depth 1. A crate that declares a deeper recursion gets its own ([`interface`]).
pub const INTERFACE: Interface = Interface {
    max_payload_bytes: contract::HIT_PAYLOAD_BYTES,
    max_hit_attribute_bytes: contract::PROCEDURAL_ATTRIBUTE_BYTES,
    max_recursion_depth: contract::MAX_RECURSION_DEPTH,
};

/// [`INTERFACE`] with recursion `depth`.
pub fn interface(depth: u32) -> Interface {
    Interface { max_recursion_depth: depth, ..INTERFACE }
}

/// One library: its stages and its one group, indices into those stages.
pub(crate) struct LibraryDesc<'a> {
    pub stages: Vec<StageDesc<'a>>,
    pub group: GroupDesc,
    /// The specialisation data of its stages (part of its identity).
    pub spec_bytes: &'a [u8],
    /// The recursion depth of the pipelines it is linked into (part of its identity).
    pub depth: u32,
}

/// A linked pipeline and the libraries it was linked from.
pub(crate) struct Linked {
    pub pipeline: RtPipeline,
    /// Its libraries in its groups' order.
    pub libraries: Vec<vk::Pipeline>,
    /// Those of them this `Libraries` owns (none that the context keeps), kept alive with it.
    pub held: Vec<Rc<RtPipeline>>,
}

/// The libraries compiled so far, shared by every pipeline linked through this (and, where
/// the context keeps them, by every pipeline linked on the context).
#[derive(Default)]
pub struct Libraries {
    made: RefCell<HashMap<u64, Rc<RtPipeline>>>,
    compiled: Cell<usize>,
    /// Libraries go to the context (`Context::kept`), not to `made`.
    in_context: bool,
}

impl Libraries {
    /// Libraries for pipelines of `ctx`: those the context keeps where it keeps them, else
    /// this one's own.
    pub fn of(ctx: &Context) -> Self {
        Libraries { in_context: ctx.keeps_libraries(), ..Self::default() }
    }

    /// Libraries compiled through this so far (each module and specialisation once).
    pub fn compiled(&self) -> usize {
        self.compiled.get()
    }

    /// The pipeline linked from `libraries` (in SBT group order), compiling those not made
    /// before.
    pub(crate) fn link(
        &self,
        ctx: &Arc<Context>,
        bindings: &[crate::vk::pipeline::Binding],
        libraries: &[LibraryDesc],
        depth: u32,
    ) -> Result<Linked> {
        let (mut raw, mut held) = (Vec::new(), Vec::new());
        for desc in libraries {
            let (library, own) = self.library(ctx, bindings, desc)?;
            raw.push(library);
            held.extend(own);
        }
        Ok(Linked { pipeline: RtPipeline::link(ctx, bindings, &raw, interface(depth))?, libraries: raw, held })
    }

    /// The library `desc` describes, made unless this or the context has it; with the
    /// pipeline that owns it when this does.
    fn library(
        &self,
        ctx: &Arc<Context>,
        bindings: &[crate::vk::pipeline::Binding],
        desc: &LibraryDesc,
    ) -> Result<(vk::Pipeline, Option<Rc<RtPipeline>>)> {
        let key = key(desc);
        if let Some(made) = self.made.borrow().get(&key) {
            return Ok((made.raw, Some(made.clone())));
        }
        let pipeline = PipelineDesc {
            bindings,
            stages: &desc.stages,
            groups: std::slice::from_ref(&desc.group),
            max_recursion_depth: desc.depth,
        };
        let make = || RtPipeline::library(ctx, &pipeline, interface(desc.depth));
        if self.in_context {
            let (kept, made) = ctx.kept.get_or_make(key, || make().map(RtPipeline::into_kept))?;
            self.compiled.set(self.compiled.get() + usize::from(made));
            return Ok((kept.raw, None));
        }
        let library = Rc::new(make()?);
        self.compiled.set(self.compiled.get() + 1);
        self.made.borrow_mut().insert(key, library.clone());
        Ok((library.raw, Some(library)))
    }
}

/// The identity of a library: its group's shape, its stages and the specialisation data.
fn key(desc: &LibraryDesc) -> u64 {
    let mut hash = Fnv::default();
    hash.eat(format!("{:?}", desc.group).as_bytes());
    eat_stages(&mut hash, &desc.stages, desc.spec_bytes);
    hash.eat(&desc.depth.to_le_bytes());
    hash.value()
}

/// Each stage's kind, name, entry point and exact SPIR-V, and the specialisation data.
fn eat_stages(hash: &mut Fnv, stages: &[StageDesc], spec_bytes: &[u8]) {
    for s in stages {
        hash.eat(&s.stage.as_raw().to_le_bytes());
        hash.eat(s.name.as_bytes());
        hash.eat(s.entry.to_bytes_with_nul());
        hash.eat(&(s.spirv.len() as u64).to_le_bytes());
        hash.eat(s.spirv);
        hash.eat(&[u8::from(s.specialization.is_some())]);
    }
    hash.eat(spec_bytes);
}

/// The compute pipeline of `stage` (specialised by `spec_bytes`) over `bindings`: on a device
/// whose context keeps libraries, the one it made before for the same code, made once. Lavapipe
/// took 1 to 2 s to make a ray-query compute pipeline for each render under the validation
/// layer, where a ray tracing pipeline's libraries are made once a context.
pub fn compute(
    ctx: &Arc<Context>,
    bindings: &[crate::vk::pipeline::Binding],
    stage: &StageDesc,
    spec_bytes: &[u8],
) -> Result<RtPipeline> {
    if !ctx.keeps_libraries() {
        return RtPipeline::compute(ctx, bindings, stage);
    }
    let mut hash = Fnv::default();
    hash.eat(b"compute");
    eat_stages(&mut hash, std::slice::from_ref(stage), spec_bytes);
    let make = || RtPipeline::compute(ctx, bindings, stage).map(RtPipeline::into_kept);
    let (kept, _) = ctx.kept.get_or_make(hash.value(), make)?;
    Ok(RtPipeline::lent(ctx, kept, vk::PipelineBindPoint::COMPUTE))
}
