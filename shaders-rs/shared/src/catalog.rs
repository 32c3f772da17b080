//! The catalog of compiled shader modules: which stages exist, which module implements each,
//! its entry point in each language and where its SPIR-V is committed. The host resolves shader
//! sets from it; `cargo xtask shaders` builds and checks exactly these modules.

use crate::bindings as b;
use crate::spirv_info::ModuleInfo;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
/// The language a module of a built-in set is written in.
pub enum Language {
    /// Rust, compiled by rust-gpu.
    Rust,
    /// GLSL, compiled by glslang.
    Glsl,
}

/// The stages twinray's pipelines use: the ray tracing stages, in pipeline stage order, and
/// the compute stage of the renderer that traces with ray queries alone (`renderer = "compute"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Ray generation: launches the rays, one invocation per pixel or probe ray.
    Raygen,
    /// Miss: what a ray that hits nothing returns.
    Miss,
    /// Intersection: a procedural shape's test of a ray against its box.
    Intersection,
    /// Closest hit: the shading of the nearest hit.
    ClosestHit,
    /// Any hit: whether a candidate hit counts (alpha-tested geometry).
    AnyHit,
    /// Callable: a material's shading, called from a closest hit.
    Callable,
    /// Compute: the renderer that traces with ray queries.
    Compute,
}

impl Stage {
    /// Every stage, in pipeline stage order.
    pub const ALL: [Stage; 7] = [
        Stage::Raygen,
        Stage::Miss,
        Stage::Intersection,
        Stage::ClosestHit,
        Stage::AnyHit,
        Stage::Callable,
        Stage::Compute,
    ];

    /// The stage's name as shader sets and reports write it (`raygen`, `closest_hit`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Stage::Raygen => "raygen",
            Stage::Miss => "miss",
            Stage::Intersection => "intersection",
            Stage::ClosestHit => "closest_hit",
            Stage::AnyHit => "any_hit",
            Stage::Callable => "callable",
            Stage::Compute => "compute",
        }
    }

    /// The SPIR-V execution model a module for this stage must declare.
    pub fn execution_model(self) -> u32 {
        match self {
            Stage::Raygen => 5313,
            Stage::Intersection => 5314,
            Stage::AnyHit => 5315,
            Stage::ClosestHit => 5316,
            Stage::Miss => 5317,
            Stage::Callable => 5318,
            Stage::Compute => 5,
        }
    }
}

impl Language {
    /// The language's name as shader sets write it: `rust` or `glsl`.
    pub fn name(self) -> &'static str {
        match self {
            Language::Rust => "rust",
            Language::Glsl => "glsl",
        }
    }
}

/// Where a module's GLSL twin comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlslSource {
    /// A stage file of the GLSL twins.
    File(&'static str),
    /// A stage file of the GLSL twins compiled with a preprocessor macro defined (`-D`).
    Variant {
        /// The stage file.
        file: &'static str,
        /// The macro defined.
        define: &'static str,
    },
    /// The intersection stage of a registered shape: `shapes/SHAPE.glsl` of the GLSL twins with
    /// `intersection_main.glsl` around its `SHAPE_intersect` (or `SHAPE_naive_intersect`);
    /// `cargo xtask shaders` writes the few lines that join them ([`ModuleSpec::glsl_wrapper`]).
    Shape {
        /// The shape's name in the registry (`sphere`, `torus`, ...).
        shape: &'static str,
        /// The hit kind its intersection stage reports.
        hit_kind: u32,
        /// Whether this is the textbook (`naive`) form kept for comparison.
        naive: bool,
    },
}

/// One compiled module: `<language>/<name>.spv` in twinray's built-in sets, built from the Rust entry point `name`
/// or from its GLSL source.
#[derive(Clone, Copy, Debug)]
pub struct ModuleSpec {
    /// The module's name: its file `NAME.spv`, and its Rust entry point.
    pub name: &'static str,
    /// The stage it implements.
    pub stage: Stage,
    /// Where its GLSL twin comes from.
    pub glsl: GlslSource,
}

/// Expands the shape registry's lines to `MODULES`: the fixed modules, then one intersection
/// module per shape (and one per naive variant).
macro_rules! module_table {
    ($($shape:literal => $module:ident ($kind:literal): $entry:ident $(, naive $naive:ident)?;)*) => {
        /// Every module of both sets; `cargo xtask shaders` builds and checks exactly these. A
        /// pipeline uses only those its scene needs. The intersection modules come from the
        /// shape registry ([`crate::procedural_shapes`]).
        pub const MODULES: &[ModuleSpec] = &[
            ModuleSpec { name: "raygen", stage: Stage::Raygen, glsl: GlslSource::File("raygen.rgen") },
            ModuleSpec { name: "raygen_query", stage: Stage::Raygen, glsl: GlslSource::File("raygen_query.rgen") },
            ModuleSpec { name: "probe", stage: Stage::Raygen, glsl: GlslSource::File("probe.rgen") },
            ModuleSpec { name: "render_compute", stage: Stage::Compute, glsl: GlslSource::File("render.comp") },
            ModuleSpec { name: "probe_query", stage: Stage::Compute, glsl: GlslSource::File("probe_query.comp") },
            ModuleSpec { name: "miss", stage: Stage::Miss, glsl: GlslSource::File("miss.rmiss") },
            ModuleSpec { name: "shadow_miss", stage: Stage::Miss, glsl: GlslSource::File("shadow.rmiss") },
            $(
                ModuleSpec {
                    name: stringify!($entry),
                    stage: Stage::Intersection,
                    glsl: GlslSource::Shape { shape: $shape, hit_kind: $kind, naive: false },
                },
                $(ModuleSpec {
                    name: stringify!($naive),
                    stage: Stage::Intersection,
                    glsl: GlslSource::Shape { shape: $shape, hit_kind: $kind, naive: true },
                },)?
            )*
            ModuleSpec {
                name: "procedural_closest_hit",
                stage: Stage::ClosestHit,
                glsl: GlslSource::File("procedural.rchit"),
            },
            ModuleSpec { name: "triangle_closest_hit", stage: Stage::ClosestHit, glsl: GlslSource::File("triangle.rchit") },
            ModuleSpec {
                name: "procedural_closest_hit_callable",
                stage: Stage::ClosestHit,
                glsl: GlslSource::Variant { file: "procedural.rchit", define: "CALLABLE_MATERIALS" },
            },
            ModuleSpec {
                name: "triangle_closest_hit_callable",
                stage: Stage::ClosestHit,
                glsl: GlslSource::Variant { file: "triangle.rchit", define: "CALLABLE_MATERIALS" },
            },
            ModuleSpec {
                name: "procedural_closest_hit_flat",
                stage: Stage::ClosestHit,
                glsl: GlslSource::Variant { file: "procedural.rchit", define: "FLAT_MATERIAL" },
            },
            ModuleSpec {
                name: "triangle_closest_hit_flat",
                stage: Stage::ClosestHit,
                glsl: GlslSource::Variant { file: "triangle.rchit", define: "FLAT_MATERIAL" },
            },
            ModuleSpec { name: "flat_material", stage: Stage::Callable, glsl: GlslSource::File("flat_material.rcall") },
            ModuleSpec { name: "checker_material", stage: Stage::Callable, glsl: GlslSource::File("checker_material.rcall") },
            ModuleSpec { name: "cutout_any_hit", stage: Stage::AnyHit, glsl: GlslSource::File("cutout.rahit") },
            ModuleSpec {
                name: "triangle_cutout_any_hit",
                stage: Stage::AnyHit,
                glsl: GlslSource::File("triangle_cutout.rahit"),
            },
            ModuleSpec { name: "probe_witness", stage: Stage::ClosestHit, glsl: GlslSource::File("probe_witness.rchit") },
            ModuleSpec {
                name: "probe_witness_driver",
                stage: Stage::ClosestHit,
                glsl: GlslSource::Variant { file: "probe_witness.rchit", define: "DRIVER_RAY" },
            },
            ModuleSpec { name: "explain", stage: Stage::Raygen, glsl: GlslSource::File("explain.rgen") },
            ModuleSpec { name: "explain_query", stage: Stage::Compute, glsl: GlslSource::File("explain_query.comp") },
        ];
    };
}

crate::procedural_shapes!(module_table);

/// A SPIR-V version twinray reads: the Vulkan version a device needs to run it, and the
/// environment SPIRV-Tools (`spirv-val`, `spirv-opt`) checks it for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpirvVersion {
    /// (major, minor) of the SPIR-V version.
    pub spirv: (u32, u32),
    /// (major, minor) of the Vulkan version a device needs to run it.
    pub vulkan: (u32, u32),
    /// SPIRV-Tools' `--target-env` for it (`vulkan1.1spv1.4`, ...).
    pub target_env: &'static str,
}

/// The SPIR-V versions twinray reads: 1.4, what `cargo xtask shaders` builds, and 1.5 and 1.6,
/// what glslang and shaderc write for `--target-env vulkan1.2` and `vulkan1.3`.
pub const SPIRV_VERSIONS: [SpirvVersion; 3] = [
    SpirvVersion { spirv: (1, 4), vulkan: (1, 2), target_env: "vulkan1.1spv1.4" },
    SpirvVersion { spirv: (1, 5), vulkan: (1, 2), target_env: "vulkan1.2" },
    SpirvVersion { spirv: (1, 6), vulkan: (1, 3), target_env: "vulkan1.3" },
];

/// What twinray knows of SPIR-V `version`; `None` for one it does not read.
pub fn spirv_version(version: (u32, u32)) -> Option<SpirvVersion> {
    SPIRV_VERSIONS.iter().copied().find(|v| v.spirv == version)
}

/// The SPIR-V version of a module's `bytes`, from its header (0.0 where there is none).
pub fn header_version(bytes: &[u8]) -> (u32, u32) {
    let word = bytes.get(4..8).map_or(0, |w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]));
    ((word >> 16) & 0xff, (word >> 8) & 0xff)
}

/// The SPIRV-Tools environment to check a module's `bytes` for: its version's, or 1.4's where
/// twinray does not read its version (the module checks refuse it, naming the version).
pub fn target_env(bytes: &[u8]) -> &'static str {
    spirv_version(header_version(bytes)).unwrap_or(SPIRV_VERSIONS[0]).target_env
}

/// The arguments of SPIRV-Tools' `spirv-val` for the modules twinray builds: SPIR-V 1.4 for
/// Vulkan 1.1 (what `cargo xtask shaders` writes and checks).
pub const SPIRV_VAL_ARGS: [&str; 2] = ["--target-env", SPIRV_VERSIONS[0].target_env];

/// The module called `name`.
pub fn module(name: &str) -> Option<ModuleSpec> {
    MODULES.iter().copied().find(|m| m.name == name)
}

/// The intersection module of a crate's own shape `shape` ([`crate::custom`]): `SHAPE_intersection`,
/// whose GLSL twin is `shapes/SHAPE.glsl` with `SHAPE_intersect`, as a built-in shape's is. Its
/// names are leaked: a run reads a crate's shapes once and keeps them.
pub fn own_intersection(shape: &str, hit_kind: u32) -> ModuleSpec {
    let name: &'static str = Box::leak(format!("{shape}_intersection").into_boxed_str());
    let shape: &'static str = Box::leak(shape.to_string().into_boxed_str());
    ModuleSpec { name, stage: Stage::Intersection, glsl: GlslSource::Shape { shape, hit_kind, naive: false } }
}

/// The callable module of a crate's own material `material` ([`crate::custom`]):
/// `MATERIAL_material`, whose GLSL twin is the stage file `MATERIAL_material.rcall`. Its
/// names are leaked, as [`own_intersection`]'s are.
pub fn own_material(material: &str) -> ModuleSpec {
    let name: &'static str = Box::leak(format!("{material}_material").into_boxed_str());
    let file: &'static str = Box::leak(format!("{name}.rcall").into_boxed_str());
    ModuleSpec { name, stage: Stage::Callable, glsl: GlslSource::File(file) }
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

    /// The GLSL file that glslang compiles for this module, relative to the GLSL twins' folder: the
    /// stage file, or for a shape the wrapper `cargo xtask shaders` writes.
    pub fn glsl_file(&self) -> String {
        match self.glsl {
            GlslSource::File(file) | GlslSource::Variant { file, .. } => file.to_string(),
            GlslSource::Shape { .. } => format!("{}.rint", self.name),
        }
    }

    /// For a shape's intersection module: the GLSL stage that puts `intersection_main.glsl`
    /// around the shape's function, to be compiled with the GLSL twins' folder on the include path.
    pub fn glsl_wrapper(&self) -> Option<String> {
        let GlslSource::Shape { shape, hit_kind, naive } = self.glsl else { return None };
        let function = if naive { format!("{shape}_naive_intersect") } else { format!("{shape}_intersect") };
        // The naive routines keep the textbook transform: no bound (intersection_main.glsl).
        let bound = if naive { String::new() } else { format!("#define SHAPE_BOUND {shape}_bound\n") };
        Some(format!(
            "#version 460\n\
             // Generated by `cargo xtask shaders` from the shape registry: the twin of the Rust entry\n\
             // point twinray_stages::{name}.\n\
             #extension GL_EXT_ray_tracing : require\n\
             #extension GL_GOOGLE_include_directive : require\n\
             #include \"twinray_layout.glsl\"\n\
             #include \"shapes/{shape}.glsl\"\n\
             #define SHAPE_INTERSECT {function}\n\
             #define SHAPE_HIT_KIND {hit_kind}u\n\
             {bound}\
             #include \"intersection_main.glsl\"\n",
            name = self.name
        ))
    }
}

impl Language {
    /// Both languages, Rust first.
    pub const ALL: [Language; 2] = [Language::Rust, Language::Glsl];
}

/// What a descriptor of the set is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DescriptorKind {
    /// The top-level acceleration structure.
    AccelerationStructure,
    /// A storage image (the rendered image).
    StorageImage,
    /// A uniform buffer.
    UniformBuffer,
    /// A storage buffer.
    StorageBuffer,
    /// An array of [`crate::bindings::TEXTURE_SLOTS`] combined image samplers.
    SampledImageArray,
}

/// One binding of the descriptor set: its number, what it holds and the stages that see it.
#[derive(Clone, Copy, Debug)]
pub struct BindingSpec {
    /// Its binding number (`bindings::BINDING_*`).
    pub binding: u32,
    /// What it holds.
    pub kind: DescriptorKind,
    /// The stages that may use it.
    pub stages: &'static [Stage],
}

/// The descriptor set every pipeline shares (set `bindings::DESCRIPTOR_SET`): every binding a
/// module may declare, and the stages allowed to use it.
pub const LAYOUT: [BindingSpec; 13] = {
    use DescriptorKind::*;
    use Stage::*;
    [
        BindingSpec {
            binding: b::BINDING_TLAS,
            kind: AccelerationStructure,
            stages: &[Raygen, Miss, ClosestHit, Compute],
        },
        BindingSpec { binding: b::BINDING_IMAGE, kind: StorageImage, stages: &[Raygen, Compute] },
        BindingSpec {
            binding: b::BINDING_FRAME,
            kind: UniformBuffer,
            stages: &[Raygen, Miss, ClosestHit, Callable, Compute],
        },
        BindingSpec {
            binding: b::BINDING_OBJECTS,
            kind: StorageBuffer,
            stages: &[Raygen, ClosestHit, AnyHit, Compute],
        },
        BindingSpec {
            binding: b::BINDING_PRIMITIVES,
            kind: StorageBuffer,
            stages: &[Raygen, Intersection, ClosestHit, Compute],
        },
        BindingSpec {
            binding: b::BINDING_MATERIALS,
            kind: StorageBuffer,
            stages: &[Raygen, ClosestHit, AnyHit, Compute],
        },
        BindingSpec {
            binding: b::BINDING_LIGHTS,
            kind: StorageBuffer,
            stages: &[Raygen, ClosestHit, Callable, Compute],
        },
        BindingSpec { binding: b::BINDING_HIT_IDS, kind: StorageBuffer, stages: &[Raygen, Compute] },
        BindingSpec {
            binding: b::BINDING_VERTICES,
            kind: StorageBuffer,
            stages: &[Raygen, ClosestHit, AnyHit, Compute],
        },
        BindingSpec {
            binding: b::BINDING_INDICES,
            kind: StorageBuffer,
            stages: &[Raygen, ClosestHit, AnyHit, Compute],
        },
        BindingSpec { binding: b::BINDING_PROBE_RAYS, kind: StorageBuffer, stages: &[Raygen, Compute] },
        BindingSpec { binding: b::BINDING_PROBE_RESULTS, kind: StorageBuffer, stages: &[Raygen, Compute] },
        BindingSpec {
            binding: b::BINDING_TEXTURES,
            kind: SampledImageArray,
            stages: &[Raygen, ClosestHit, AnyHit, Compute],
        },
    ]
};

impl ModuleSpec {
    /// The entry point a module built elsewhere offers for this spec: the only one with the
    /// stage's execution model, or among several the one named like the module (rust-gpu's
    /// way) or `main` (glslang's). `None` when there is no such choice;
    /// [`crate::module_check::check_module`] then says what the module has.
    pub fn find_entry(&self, info: &ModuleInfo) -> Option<String> {
        let model = self.stage.execution_model();
        let names: Vec<&str> = info.entry_points.iter().filter(|(m, _)| *m == model).map(|(_, n)| n.as_str()).collect();
        match names.as_slice() {
            [one] => Some(one.to_string()),
            several => several.iter().find(|n| **n == self.name || **n == "main").map(|n| n.to_string()),
        }
    }
}
