//! The catalog of compiled shader modules: which stages exist, which module implements each,
//! its entry point in each language and where its SPIR-V is committed. The host resolves shader
//! sets from it; `cargo xtask shaders` builds and checks exactly these modules.

use crate::bindings as b;
use crate::spirv_info::ModuleInfo;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Language {
    Rust,
    Glsl,
}

/// The ray tracing stages twinray's pipelines use, in pipeline stage order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    Raygen,
    Miss,
    Intersection,
    ClosestHit,
}

impl Stage {
    pub const ALL: [Stage; 4] = [Stage::Raygen, Stage::Miss, Stage::Intersection, Stage::ClosestHit];

    pub fn name(self) -> &'static str {
        match self {
            Stage::Raygen => "raygen",
            Stage::Miss => "miss",
            Stage::Intersection => "intersection",
            Stage::ClosestHit => "closest_hit",
        }
    }

    /// The SPIR-V execution model a module for this stage must declare.
    pub fn execution_model(self) -> u32 {
        match self {
            Stage::Raygen => 5313,
            Stage::Intersection => 5314,
            Stage::ClosestHit => 5316,
            Stage::Miss => 5317,
        }
    }
}

impl Language {
    pub fn name(self) -> &'static str {
        match self {
            Language::Rust => "rust",
            Language::Glsl => "glsl",
        }
    }
}

/// One compiled module: `spirv/<language>/<name>.spv`, built from the Rust entry point `name`
/// or from `shaders-glsl/<glsl_source>`.
#[derive(Clone, Copy, Debug)]
pub struct ModuleSpec {
    pub name: &'static str,
    pub stage: Stage,
    pub glsl_source: &'static str,
}

/// Every module of both sets; `cargo xtask shaders` builds and checks exactly these. A pipeline
/// uses only those its scene needs.
pub const MODULES: [ModuleSpec; 15] = [
    ModuleSpec { name: "raygen", stage: Stage::Raygen, glsl_source: "raygen.rgen" },
    ModuleSpec { name: "probe", stage: Stage::Raygen, glsl_source: "probe.rgen" },
    ModuleSpec { name: "miss", stage: Stage::Miss, glsl_source: "miss.rmiss" },
    ModuleSpec { name: "shadow_miss", stage: Stage::Miss, glsl_source: "shadow.rmiss" },
    ModuleSpec { name: "sphere_intersection", stage: Stage::Intersection, glsl_source: "sphere.rint" },
    ModuleSpec { name: "plane_intersection", stage: Stage::Intersection, glsl_source: "plane.rint" },
    ModuleSpec { name: "box_intersection", stage: Stage::Intersection, glsl_source: "box.rint" },
    ModuleSpec { name: "cylinder_intersection", stage: Stage::Intersection, glsl_source: "cylinder.rint" },
    ModuleSpec { name: "cone_intersection", stage: Stage::Intersection, glsl_source: "cone.rint" },
    ModuleSpec { name: "torus_intersection", stage: Stage::Intersection, glsl_source: "torus.rint" },
    ModuleSpec { name: "sphere_naive_intersection", stage: Stage::Intersection, glsl_source: "sphere_naive.rint" },
    ModuleSpec { name: "cylinder_naive_intersection", stage: Stage::Intersection, glsl_source: "cylinder_naive.rint" },
    ModuleSpec { name: "torus_naive_intersection", stage: Stage::Intersection, glsl_source: "torus_naive.rint" },
    ModuleSpec { name: "procedural_closest_hit", stage: Stage::ClosestHit, glsl_source: "procedural.rchit" },
    ModuleSpec { name: "triangle_closest_hit", stage: Stage::ClosestHit, glsl_source: "triangle.rchit" },
];

/// The module called `name`.
pub fn module(name: &str) -> Option<ModuleSpec> {
    MODULES.iter().copied().find(|m| m.name == name)
}

impl ModuleSpec {
    /// The entry point's name in this language's module.
    pub fn entry_point(&self, language: Language) -> &'static str {
        match language {
            Language::Rust => self.name,
            Language::Glsl => "main",
        }
    }

    /// Path of the committed module, relative to the repository root.
    pub fn spirv_path(&self, language: Language) -> String {
        format!("spirv/{}/{}.spv", language.name(), self.name)
    }
}

impl Language {
    pub const ALL: [Language; 2] = [Language::Rust, Language::Glsl];
}

/// Every (descriptor set, binding) a module may declare: those of `crate::bindings`.
pub const KNOWN_BINDINGS: [(u32, u32); 12] = [
    (b::DESCRIPTOR_SET, b::BINDING_TLAS),
    (b::DESCRIPTOR_SET, b::BINDING_IMAGE),
    (b::DESCRIPTOR_SET, b::BINDING_FRAME),
    (b::DESCRIPTOR_SET, b::BINDING_OBJECTS),
    (b::DESCRIPTOR_SET, b::BINDING_PRIMITIVES),
    (b::DESCRIPTOR_SET, b::BINDING_MATERIALS),
    (b::DESCRIPTOR_SET, b::BINDING_LIGHTS),
    (b::DESCRIPTOR_SET, b::BINDING_HIT_IDS),
    (b::DESCRIPTOR_SET, b::BINDING_VERTICES),
    (b::DESCRIPTOR_SET, b::BINDING_INDICES),
    (b::DESCRIPTOR_SET, b::BINDING_PROBE_RAYS),
    (b::DESCRIPTOR_SET, b::BINDING_PROBE_RESULTS),
];

impl ModuleSpec {
    /// Checks what a compiled module declares: SPIR-V 1.4, this spec's entry point with the
    /// stage's execution model, and only bindings defined in `crate::bindings`.
    pub fn check_declarations(&self, info: &ModuleInfo, language: Language) -> Result<(), String> {
        if info.version != (1, 4) {
            return Err(format!("SPIR-V {}.{}, expected 1.4", info.version.0, info.version.1));
        }
        let want = (self.stage.execution_model(), self.entry_point(language).to_string());
        if !info.entry_points.contains(&want) {
            return Err(format!("no {} entry point {:?} (found {:?})", self.stage.name(), want.1, info.entry_points));
        }
        match info.bindings.iter().find(|b| !KNOWN_BINDINGS.contains(b)) {
            Some((set, binding)) => {
                Err(format!("binds set {set} binding {binding}, which twinray_shared::bindings does not define"))
            }
            None => Ok(()),
        }
    }
}
