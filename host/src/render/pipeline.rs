//! The ray tracing pipeline of a scene's plan with a shader set: ray generation, the primary
//! miss shader, the shadow miss shader only if some light casts shadows, and the hit groups
//! of the plan (with the cutout any-hit stage for cutout objects); or, for `renderer =
//! "compute"`, the compute pipeline of the ray query renderer alone. Specialisation constants
//! carry the plan's sample count, shadow switch and shadow sampler, and the features the scene
//! uses, into every stage (each reads those it declares).

use super::layout::{stages_in_group_order, Layout, LayoutDraw};
use super::libraries::{Libraries, LibraryDesc};
use crate::error::{Error, Result};
use crate::scene::{HitGroup, PipelinePlan, EXPLAIN_QUERY, PROBE_QUERY, RENDER_COMPUTE};
use crate::sets::{capabilities, ShaderSet, Stage, StageModule};
use crate::util::activity;
use crate::vk::context::Context;
use crate::vk::pipeline::{GroupDesc, PipelineDesc, RtPipeline, StageDesc};
use ash::vk;
use std::sync::Arc;
use twinray_shared::bindings as b;
use twinray_shared::catalog::{DescriptorKind, LAYOUT};

/// A scene's pipeline and what the SBT and reports need to know of it.
pub struct ScenePipeline {
    pub rt: RtPipeline,
    /// The group of each record of each SBT region (raygen, miss, hit, callable).
    pub sbt_records: [Vec<u32>; 4],
    /// Of a probe's pipeline: the records of each witness pass ([`PROBE_WITNESSES`] the set
    /// has, in order), each hit group's record replaced by the group's witness.
    pub witness_records: Vec<[Vec<u32>; 4]>,
    /// Groups in the pipeline.
    pub group_count: u32,
    /// Names of the modules in the pipeline, in stage order (for tests and reports).
    pub modules: Vec<&'static str>,
    /// The workgroup size a compute pipeline is dispatched in; `None` for ray tracing.
    pub workgroup: Option<(u32, u32)>,
    /// The scene features its stages are specialised for (`PipelinePlan::features`).
    pub features: u32,
    /// Where ray generation's group lies in the pipeline's layout (`super::layout`).
    raygen_group: u32,
    /// The libraries it was linked from (none when made whole), in layout order.
    libraries: Vec<vk::Pipeline>,
    /// Those of them no context keeps, kept while it lives.
    _held: Vec<std::rc::Rc<RtPipeline>>,
}

/// The probe's witness closest-hit stages: the object-space ray the intersection stages
/// computed, and the one the driver hands a hit group. A probe's pipeline holds, besides the
/// scene's hit groups, a witness of each per witness stage: the same intersection and any-hit
/// stages with the witness as closest hit, which reports the ray. A pass of the probe over an
/// SBT of witnesses reads those rays back; the scene's own stages are not changed.
pub const PROBE_WITNESSES: [&str; 2] = ["probe_witness", "probe_witness_driver"];

/// The witness stages a pipeline of `set` with ray generation stage `raygen` over `plan` holds:
/// the ray tracing probe's, when the scene has hit groups, those the set has (a folder of
/// modules built before one existed lacks it, and probes without it; the driver's witness
/// alone is not taken, as it would be read as the stages').
fn witnesses(set: &ShaderSet, plan: &PipelinePlan, raygen: &str) -> Vec<&'static str> {
    if raygen != "probe" || plan.hit_groups.is_empty() || set.lacks(PROBE_WITNESSES[0]) {
        return Vec::new();
    }
    PROBE_WITNESSES.into_iter().filter(|w| !set.lacks(w)).collect()
}

/// (binding, type, stages) of every descriptor, from the shared layout.
pub fn descriptor_bindings() -> Vec<crate::vk::pipeline::Binding> {
    LAYOUT
        .iter()
        .map(|l| {
            let ty = match l.kind {
                DescriptorKind::AccelerationStructure => vk::DescriptorType::ACCELERATION_STRUCTURE_KHR,
                DescriptorKind::StorageImage => vk::DescriptorType::STORAGE_IMAGE,
                DescriptorKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
                DescriptorKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
                DescriptorKind::SampledImageArray => vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            };
            let count = if l.kind == DescriptorKind::SampledImageArray { b::TEXTURE_SLOTS } else { 1 };
            let stages = l.stages.iter().fold(vk::ShaderStageFlags::empty(), |f, s| f | stage_flag(*s));
            (l.binding, ty, count, stages)
        })
        .collect()
}

/// The Vulkan stage flag of a twinray stage.
pub fn stage_flag(stage: Stage) -> vk::ShaderStageFlags {
    match stage {
        Stage::Raygen => vk::ShaderStageFlags::RAYGEN_KHR,
        Stage::Miss => vk::ShaderStageFlags::MISS_KHR,
        Stage::Intersection => vk::ShaderStageFlags::INTERSECTION_KHR,
        Stage::ClosestHit => vk::ShaderStageFlags::CLOSEST_HIT_KHR,
        Stage::AnyHit => vk::ShaderStageFlags::ANY_HIT_KHR,
        Stage::Callable => vk::ShaderStageFlags::CALLABLE_KHR,
        Stage::Compute => vk::ShaderStageFlags::COMPUTE,
    }
}

/// The workgroup size of a compute module (`render_compute`, `probe_query`, `explain_query`), which the
/// host dispatches over its launch; `None` for the ray tracing stages.
pub fn workgroup(module: &str) -> Option<(u32, u32)> {
    match module {
        RENDER_COMPUTE => Some((b::RENDER_GROUP_SIZE, b::RENDER_GROUP_SIZE)),
        PROBE_QUERY | EXPLAIN_QUERY => Some((b::PROBE_GROUP_SIZE, 1)),
        _ => None,
    }
}

/// Module names of a plan's pipeline, each once, in stage order: the ray generation module
/// `raygen` ("raygen" renders, "probe" probes), misses, hit modules; or a compute module
/// (`render_compute` renders, `probe_query` probes) alone.
pub fn plan_modules(plan: &PipelinePlan, raygen: &'static str) -> Vec<&'static str> {
    if workgroup(raygen).is_some() {
        return vec![raygen];
    }
    let mut names = vec![raygen, "miss"];
    if plan.shadow_miss() {
        names.push("shadow_miss");
    }
    for group in &plan.hit_groups {
        names.extend(group.intersection_module());
        names.push(group.closest_hit_module());
        names.extend(group.any_hit_module());
    }
    names.extend(plan.callables());
    crate::scene::each_once(names)
}

/// The stages of a plan's pipeline, in stage order.
pub fn used_stages(plan: &PipelinePlan, raygen: &'static str) -> Vec<Stage> {
    let names = plan_modules(plan, raygen);
    Stage::ALL
        .into_iter()
        .filter(|stage| names.iter().any(|n| crate::sets::MODULES.iter().any(|m| m.name == *n && m.stage == *stage)))
        .collect()
}

impl ScenePipeline {
    /// The pipeline of `plan` with the modules of `set`, ray generation stage `raygen`: linked
    /// from libraries kept in `libraries`, or whole when that is `None`; laid out as `layout`
    /// draws (`super::layout`).
    pub fn new(
        ctx: &Arc<Context>,
        set: &ShaderSet,
        plan: &PipelinePlan,
        (raygen, layout): (&'static str, LayoutDraw),
        libraries: Option<&Libraries>,
    ) -> Result<Self> {
        let mut names = plan_modules(plan, raygen);
        let witness = witnesses(set, plan, raygen);
        names.extend(&witness);
        let modules = names.iter().map(|name| set.module(name)).collect::<Result<Vec<StageModule>>>()?;
        let origins: Vec<String> = modules.iter().map(|m| format!("{}={}", m.spec.name, m.origin)).collect();
        let doing = format!("creating the pipeline of {set} ({})", origins.join(", "));
        let _doing = activity::doing(doing.clone());
        let depth = set.recursion_depth();
        if depth > ctx.info.max_ray_recursion_depth {
            return Err(Error::Unsupported(format!(
                "shader set {set} declares recursion depth {depth}, more than {} allows ({})",
                ctx.info.name, ctx.info.max_ray_recursion_depth
            )));
        }
        // What the validation layer said of the modules fails here, before a trace can crash
        // on them (a module declaring a capability the device lacks crashed lavapipe).
        // Only a set with a stage from disk may have closest hits that shade.
        let shaded_hits = !set.all_builtin();
        let made = Self::from_modules(
            ctx,
            plan,
            (raygen, names, &modules),
            (witness, libraries, layout),
            (depth, shaded_hits),
        )
        .and_then(|made| ctx.check_validation().map(|()| made));
        made.map_err(|e| if e.is_stalled() { e } else { e.during(doing) })
    }

    fn from_modules(
        ctx: &Arc<Context>,
        plan: &PipelinePlan,
        (raygen, names, modules): (&'static str, Vec<&'static str>, &[StageModule]),
        (witness, libraries, draw): (Vec<&'static str>, Option<&Libraries>, LayoutDraw),
        (depth, shaded_hits): (u32, bool),
    ) -> Result<Self> {
        let specialised = Specialisation::of_plan(plan, shaded_hits);
        let (spec, spec_bytes) = (specialised.info(), specialised.bytes());
        // A compute pipeline has no groups and no SBT.
        let compute = workgroup(raygen).is_some();
        let in_sbt_order = if compute { Vec::new() } else { groups(plan, &names, &witness) };
        let layout = Layout::new(draw, in_sbt_order.len());
        let groups = layout.groups(&in_sbt_order);
        require_device_features(ctx, modules)?;
        let bindings = descriptor_bindings();
        let stages = stage_descs(modules, &spec);
        let (rt, linked, held) = if compute {
            // One stage, no groups, no SBT, nothing to link.
            (super::libraries::compute(ctx, &bindings, &stages[0], spec_bytes)?, Vec::new(), Vec::new())
        } else if let Some(libraries) = libraries {
            let descs: Vec<LibraryDesc> = groups.iter().map(|g| library(&stages, *g, (spec_bytes, depth))).collect();
            let linked = libraries.link(ctx, &bindings, &descs, depth)?;
            (linked.pipeline, linked.libraries, linked.held)
        } else {
            let (stages, groups) = stages_in_group_order(&stages, &groups);
            let desc =
                PipelineDesc { bindings: &bindings, stages: &stages, groups: &groups, max_recursion_depth: depth };
            (RtPipeline::new(ctx, &desc)?, Vec::new(), Vec::new())
        };
        let records = if compute { Default::default() } else { sbt_records(plan) };
        let witnessed = witness_records(&records, groups.len(), witness.len());
        Ok(ScenePipeline {
            rt,
            witness_records: witnessed.iter().map(|r| layout.records(r)).collect(),
            sbt_records: layout.records(&records),
            group_count: groups.len() as u32,
            modules: names,
            workgroup: workgroup(raygen),
            features: plan.features,
            raygen_group: if compute { 0 } else { layout.position(0) },
            libraries: linked,
            _held: held,
        })
    }

    /// What ray generation keeps across each trace call (see `RtPipeline::raygen_stack_bytes_of`).
    /// Of a linked pipeline, the ray generation library's figure: the same compiled stage,
    /// and the validation layer (1.3.239) counts a linked pipeline's groups as none.
    pub fn raygen_stack_bytes(&self) -> u64 {
        match self.libraries.get(self.raygen_group as usize) {
            Some(&raygen) => self.rt.library_raygen_stack_bytes(raygen),
            None => self.rt.raygen_stack_bytes_of(self.raygen_group),
        }
    }
}

/// The stage descriptions of `modules`, every stage specialised by `spec` (a stage reads the
/// constants it declares; Vulkan ignores the others).
pub fn stage_descs<'a>(modules: &'a [StageModule], spec: &'a vk::SpecializationInfo<'a>) -> Vec<StageDesc<'a>> {
    modules
        .iter()
        .map(|m| StageDesc {
            name: m.spec.name,
            stage: stage_flag(m.spec.stage),
            spirv: &m.spirv[..],
            entry: &m.entry,
            specialization: Some(spec),
        })
        .collect()
}

/// The specialisation of a pipeline's stages: whether any light casts shadows, M for M x M
/// samples per pixel, the shadow sampler (read by ray generation and compute stages), and the
/// features the scene uses (read by every stage that has code for one).
pub struct Specialisation {
    data: [u32; 5],
    entries: [vk::SpecializationMapEntry; 5],
}

impl Specialisation {
    /// Shadows, samples, the shadow sampler and the features as given; no closest hit that
    /// shades ([`Specialisation::shading_in_hits`] says otherwise).
    pub fn new(shadows: bool, samples_per_side: u32, shadow_sampler: u32, features: u32) -> Specialisation {
        let ids =
            [b::SPEC_SHADOWS, b::SPEC_SAMPLES_PER_SIDE, b::SPEC_SHADOW_SAMPLER, b::SPEC_FEATURES, b::SPEC_SHADED_HITS];
        let entry = |i: usize| vk::SpecializationMapEntry { constant_id: ids[i], offset: 4 * i as u32, size: 4 };
        Specialisation {
            data: [u32::from(shadows), samples_per_side, shadow_sampler, features, 0],
            entries: [entry(0), entry(1), entry(2), entry(3), entry(4)],
        }
    }

    /// What `plan` specialises, for a set whose closest hits may shade (`shaded_hits`).
    pub fn of_plan(plan: &PipelinePlan, shaded_hits: bool) -> Specialisation {
        Specialisation::new(plan.shadows, plan.samples_per_side, plan.shadow_sampler, plan.features)
            .shading_in_hits(shaded_hits)
    }

    /// This, with ray generation showing the colour of a hit its closest hit shaded
    /// (`bindings::MATERIAL_SHADED`) as it is where `shaded_hits`.
    pub fn shading_in_hits(mut self, shaded_hits: bool) -> Specialisation {
        self.data[4] = u32::from(shaded_hits);
        self
    }

    /// Each constant's id and value.
    pub fn pairs(&self) -> Vec<(u32, u32)> {
        self.entries.iter().zip(self.data).map(|(e, v)| (e.constant_id, v)).collect()
    }

    pub fn bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.data)
    }

    pub fn info(&self) -> vk::SpecializationInfo<'_> {
        vk::SpecializationInfo::default().map_entries(&self.entries).data(self.bytes())
    }
}

/// An error naming the module, what it declares and the device, when a module declares a
/// capability or extension the device does not have enabled (`sets::capabilities`): ray
/// queries where the device lacks VK_KHR_ray_query, or anything twinray does not turn on.
fn require_device_features(ctx: &Context, modules: &[StageModule]) -> Result<()> {
    for m in modules {
        let info =
            twinray_shared::spirv_info::parse(&m.spirv).map_err(|e| Error::Input(format!("{}: {e}", m.spec.name)))?;
        if let Some(missing) = capabilities::missing(m.spec.name, &m.origin, &info, &ctx.info) {
            let why = match m.spec.name {
                "raygen_query" => " (the scene sets shadow_method = \"query\")",
                RENDER_COMPUTE | PROBE_QUERY => " (the scene sets renderer = \"compute\")",
                EXPLAIN_QUERY => " (the scene sets renderer = \"compute\" or shadow_method = \"query\")",
                _ => "",
            };
            return Err(Error::DeviceLacks(format!("{missing}{why}")));
        }
    }
    Ok(())
}

/// The library of one group, for pipelines of recursion `depth`: its stages, renumbered from
/// 0 within it.
fn library<'a>(stages: &[StageDesc<'a>], group: GroupDesc, (spec_bytes, depth): (&'a [u8], u32)) -> LibraryDesc<'a> {
    // Each used stage in turn; the group's indices become positions in that list.
    let mut own = Vec::new();
    let mut renumber = |i: u32| {
        if i == vk::SHADER_UNUSED_KHR {
            return i;
        }
        own.push(i);
        own.len() as u32 - 1
    };
    let group = match group {
        GroupDesc::General(i) => GroupDesc::General(renumber(i)),
        GroupDesc::Triangles { closest_hit, any_hit } => {
            GroupDesc::Triangles { closest_hit: renumber(closest_hit), any_hit: renumber(any_hit) }
        }
        GroupDesc::Procedural { intersection, closest_hit, any_hit } => GroupDesc::Procedural {
            intersection: renumber(intersection),
            closest_hit: renumber(closest_hit),
            any_hit: renumber(any_hit),
        },
    };
    let stages: Vec<StageDesc> = own.iter().map(|&i| stages[i as usize]).collect();
    LibraryDesc { stages, group, spec_bytes, depth }
}

/// The group of each SBT record, by region: raygen, the misses, the hit groups (an instance's
/// SBT offset is its group's index in the plan), and for callable materials one record per
/// material kind, twinray's and the scene's own (the kind is the index `executeCallable` is
/// given), each the group of its kind's callable, or of the first callable for a kind no
/// material uses.
fn sbt_records(plan: &PipelinePlan) -> [Vec<u32>; 4] {
    let misses = if plan.shadow_miss() { 2 } else { 1 };
    let hits = 1 + misses;
    let first_callable = hits + plan.hit_groups.len() as u32;
    let callables = plan.callables();
    let callable_records = if callables.is_empty() {
        Vec::new()
    } else {
        (0..b::MATERIAL_KINDS + plan.own_callables.len() as u32)
            .map(|kind| {
                let name = crate::scene::material_callable(kind, &plan.own_callables);
                first_callable + callables.iter().position(|c| *c == name).unwrap_or(0) as u32
            })
            .collect()
    };
    [vec![0], (1..hits).collect(), (hits..first_callable).collect(), callable_records]
}

/// The records of each of `witnesses` witness passes: those of `sbt_records`, with the hit
/// region's records the pass's witness groups. They are the last of the pipeline's `groups`:
/// one per hit group, in order, for each witness stage in turn.
fn witness_records(
    [raygen, miss, hit, callable]: &[Vec<u32>; 4],
    groups: usize,
    witnesses: usize,
) -> Vec<[Vec<u32>; 4]> {
    let hits = hit.len() as u32;
    let first = (groups - hit.len() * witnesses) as u32;
    (0..witnesses as u32)
        .map(|k| [raygen.clone(), miss.clone(), (first + k * hits..first + (k + 1) * hits).collect(), callable.clone()])
        .collect()
}

/// SBT order: raygen, miss (`MISS_PRIMARY`), shadow miss (`MISS_SHADOW`), the hit groups in the
/// plan's order, the material callables, then for each of `witnesses` the witness of each hit
/// group.
fn groups(plan: &PipelinePlan, names: &[&'static str], witnesses: &[&'static str]) -> Vec<GroupDesc> {
    let index = |name: &str| names.iter().position(|n| *n == name).map_or(vk::SHADER_UNUSED_KHR, |i| i as u32);
    let mut groups = vec![GroupDesc::General(0), GroupDesc::General(index("miss"))];
    if plan.shadow_miss() {
        groups.push(GroupDesc::General(index("shadow_miss")));
    }
    let hit_group = |group: &HitGroup, closest_hit: &str| {
        let closest_hit = index(closest_hit);
        let any_hit = group.any_hit_module().map_or(vk::SHADER_UNUSED_KHR, index);
        match group.intersection_module() {
            Some(intersection) => GroupDesc::Procedural { intersection: index(intersection), closest_hit, any_hit },
            None => GroupDesc::Triangles { closest_hit, any_hit },
        }
    };
    groups.extend(plan.hit_groups.iter().map(|g| hit_group(g, g.closest_hit_module())));
    groups.extend(plan.callables().iter().map(|c| GroupDesc::General(index(c))));
    for witness in witnesses {
        groups.extend(plan.hit_groups.iter().map(|g| hit_group(g, witness)));
    }
    groups
}
