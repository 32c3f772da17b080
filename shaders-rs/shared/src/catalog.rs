//! The catalog of compiled shader modules: which stages exist, which module implements each,
//! its entry point in each language and where its SPIR-V is committed. The host resolves shader
//! sets from it; `cargo xtask shaders` builds and checks exactly these modules.

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

/// Every module of both sets; `cargo xtask shaders` builds and checks exactly these.
pub const MODULES: [ModuleSpec; 4] = [
    ModuleSpec { name: "raygen", stage: Stage::Raygen, glsl_source: "raygen.rgen" },
    ModuleSpec { name: "miss", stage: Stage::Miss, glsl_source: "miss.rmiss" },
    ModuleSpec { name: "sphere_intersection", stage: Stage::Intersection, glsl_source: "sphere.rint" },
    ModuleSpec { name: "sphere_closest_hit", stage: Stage::ClosestHit, glsl_source: "sphere.rchit" },
];

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
