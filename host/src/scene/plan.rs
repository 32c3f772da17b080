//! What the ray tracing pipeline of a scene contains: its hit groups, in the order of the
//! shader binding table, whether it traces shadow rays, and its specialisation.

use crate::sets::own::OwnShapeRef;
use twinray_shared::bindings::{
    CUTOUT_NONE, LIGHT_POINT, LIGHT_RECT, MATERIAL_CHECKER, MATERIAL_CUTOUT, MATERIAL_EMISSIVE, MATERIAL_KINDS,
};
use twinray_shared::features;
use twinray_shared::layout::{Light, Material};
use twinray_shared::shapes::{Shape, SHAPES, SHAPE_NAIVE};

/// What a hit group intersects: triangles with the built-in test, or a registered shape or a
/// crate's own with its intersection stage. Ordered as the SBT holds them: triangles, the
/// robust shapes in registration order, then the naive variants, then a crate's by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum HitGeometry {
    /// Meshes: the built-in triangle test.
    Triangles,
    /// `SHAPES[shape]`, with its naive variant's intersection stage when `naive`.
    Procedural { naive: bool, shape: usize },
    /// A crate's own shape.
    Own(OwnShapeRef),
}

/// A hit group: its geometry, and whether its objects are cutouts (an any-hit stage that
/// ignores hits in their holes; other objects' instances are forced opaque and run none).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct HitGroup {
    pub geometry: HitGeometry,
    pub cutout: bool,
    /// Where its closest-hit stage gets the material's colour.
    pub colour: Colour,
}

/// Where a hit group's closest-hit stage gets the material's colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Colour {
    /// Computed for any material kind (a branch on the kind).
    Inline,
    /// From the material callable its kind selects (`material_shading = "callable"`, and
    /// every material of a crate's own).
    Callable,
    /// The material's one colour, with no branch: the group serves only diffuse, emissive and
    /// cutout materials (`hit_groups = "per-material"`; checkers keep `Inline`).
    Flat,
}

/// The compute renderer's module (`renderer = "compute"`).
pub const RENDER_COMPUTE: &str = "render_compute";
/// The module that probes a compute scene: its rays traced as the compute renderer traces.
pub const PROBE_QUERY: &str = "probe_query";

/// `twinray explain`'s ray generation stage: its rays traced by `traceRay` as `raygen` traces.
pub const EXPLAIN: &str = "explain";
/// `twinray explain`'s compute stage: its rays traced inline, as the compute renderer traces
/// them and `raygen_query` traces shadow rays.
pub const EXPLAIN_QUERY: &str = "explain_query";

/// The any-hit module of procedural cutout hit groups.
pub const CUTOUT_ANY_HIT: &str = "cutout_any_hit";
/// The any-hit module of triangle cutout hit groups (which also reads the surface's alpha).
pub const TRIANGLE_CUTOUT_ANY_HIT: &str = "triangle_cutout_any_hit";

impl HitGroup {
    /// "triangles", or the shape's name, with " (naive)" for a naive variant, " (flat)" for a
    /// group of flat-coloured materials and " (cutout)" for cutouts.
    pub fn name(self) -> String {
        let base = match (self.geometry, self.shape()) {
            (HitGeometry::Own(own), _) => own.shape().name.to_string(),
            (HitGeometry::Procedural { naive: true, .. }, Some(s)) => format!("{} (naive)", s.name),
            (_, Some(s)) => s.name.to_string(),
            _ => "triangles".into(),
        };
        let base = if self.colour == Colour::Flat { format!("{base} (flat)") } else { base };
        if self.cutout {
            format!("{base} (cutout)")
        } else {
            base
        }
    }

    /// The registered shape of a procedural group.
    pub fn shape(self) -> Option<&'static Shape> {
        match self.geometry {
            HitGeometry::Triangles | HitGeometry::Own(_) => None,
            HitGeometry::Procedural { shape, .. } => SHAPES.get(shape),
        }
    }

    /// The intersection module, for procedural groups (triangles use the built-in test).
    pub fn intersection_module(self) -> Option<&'static str> {
        if let HitGeometry::Own(own) = self.geometry {
            return Some(own.shape().module);
        }
        let naive = matches!(self.geometry, HitGeometry::Procedural { naive: true, .. });
        self.shape().and_then(|s| if naive { s.naive_module } else { Some(s.module) })
    }

    /// The closest-hit module of the group.
    pub fn closest_hit_module(self) -> &'static str {
        let triangles = self.geometry == HitGeometry::Triangles;
        match (triangles, self.colour) {
            (true, Colour::Inline) => "triangle_closest_hit",
            (true, Colour::Callable) => "triangle_closest_hit_callable",
            (true, Colour::Flat) => "triangle_closest_hit_flat",
            (false, Colour::Inline) => "procedural_closest_hit",
            (false, Colour::Callable) => "procedural_closest_hit_callable",
            (false, Colour::Flat) => "procedural_closest_hit_flat",
        }
    }

    /// `ObjectData::shape` of its objects: the shape's hit kind, plus `SHAPE_NAIVE` for a
    /// naive variant; 0 for triangles.
    pub fn shape_routine(self) -> u32 {
        if let HitGeometry::Own(own) = self.geometry {
            return own.shape().hit_kind;
        }
        let naive = matches!(self.geometry, HitGeometry::Procedural { naive: true, .. });
        self.shape().map_or(0, |s| s.hit_kind + if naive { SHAPE_NAIVE } else { 0 })
    }

    /// The any-hit module, for cutout groups.
    pub fn any_hit_module(self) -> Option<&'static str> {
        let module = if self.geometry == HitGeometry::Triangles { TRIANGLE_CUTOUT_ANY_HIT } else { CUTOUT_ANY_HIT };
        self.cutout.then_some(module)
    }
}

/// What the ray tracing pipeline of a scene contains.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PipelinePlan {
    /// Distinct hit groups, in SBT order; an instance's SBT offset is its group's index here.
    pub hit_groups: Vec<HitGroup>,
    /// Whether any light casts shadows: the shadow miss shader and shadow rays.
    pub shadows: bool,
    /// M for M x M primary samples per pixel.
    pub samples_per_side: u32,
    /// `SHADOW_SAMPLER_STRATIFIED` or `SHADOW_SAMPLER_RANDOM`.
    pub shadow_sampler: u32,
    /// Shadow rays traced inline by ray queries (`shadow_method = "query"`).
    pub shadow_query: bool,
    /// Rendered by the compute stage `render_compute` with ray queries (`renderer =
    /// "compute"`): the hit groups are then what its queries decide as their stages would.
    pub compute: bool,
    /// Material kinds whose colours material callables compute: every kind the scene's
    /// materials use with `material_shading = "callable"`, else those of a crate's own alone
    /// (closest-hit stages compute the others').
    pub callable_kinds: Vec<u32>,
    /// The callable modules of the crate's own material kinds the scene uses, kind
    /// `MATERIAL_KINDS + i` being the `i`th.
    pub own_callables: Vec<&'static str>,
    /// The features the scene uses (`twinray_shared::features`), which every stage is
    /// specialised on (`SPEC_FEATURES`): the code of the others is dropped.
    pub features: u32,
}

/// The features that `materials` and `lights`, as uploaded, use: textures where a material
/// names a texture slot, area lights where a light is a rect, alpha masks where a material has
/// a cutout pattern, emission where a material is emissive or emits.
pub fn scene_features(materials: &[Material], lights: &[Light]) -> u32 {
    let any = |used: bool, bit: u32| if used { bit } else { 0 };
    let textured = materials.iter().any(|m| m.texture.x != 0 || m.texture.z != 0);
    let masked = materials.iter().any(|m| m.kind == MATERIAL_CUTOUT || m.cutout_pattern != CUTOUT_NONE);
    let emits = materials.iter().any(|m| m.kind == MATERIAL_EMISSIVE || m.emission.truncate() != glam::Vec3::ZERO);
    any(textured, features::TEXTURES)
        | any(lights.iter().any(|l| l.kind == LIGHT_RECT), features::AREA_LIGHTS)
        | any(masked, features::ALPHA_MASKS)
        | any(emits, features::EMISSION)
        | any(lights.iter().any(dimmed), features::LIGHT_CONES)
}

/// Whether a light is a point light with a range or a cone (`build::spot_cone` writes them).
fn dimmed(light: &Light) -> bool {
    light.kind == LIGHT_POINT && (light.position.w != 0.0 || light.u.truncate() != glam::Vec3::ZERO)
}

/// `names` without repeats, each where it first appears.
pub fn each_once(names: impl IntoIterator<Item = &'static str>) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for name in names {
        if !out.contains(&name) {
            out.push(name);
        }
    }
    out
}

/// The callable module that computes the colour of material kind `kind`: twinray's, or for a
/// kind from `MATERIAL_KINDS` on, the `own` module of a crate's material.
pub fn material_callable(kind: u32, own: &[&'static str]) -> &'static str {
    if kind == MATERIAL_CHECKER {
        "checker_material"
    } else if kind >= MATERIAL_KINDS {
        own.get((kind - MATERIAL_KINDS) as usize).copied().unwrap_or("flat_material")
    } else {
        "flat_material"
    }
}

impl PipelinePlan {
    /// The module that renders the scene: the ray generation stage `raygen`, or `raygen_query`
    /// when shadow rays are ray queries (then no shadow miss stage is needed); or the compute
    /// renderer `render_compute`, alone in its pipeline.
    pub fn render_raygen(&self) -> &'static str {
        if self.compute {
            RENDER_COMPUTE
        } else if self.shadow_query {
            "raygen_query"
        } else {
            "raygen"
        }
    }

    /// The callable modules of the scene's material kinds, each once, in kind order.
    pub fn callables(&self) -> Vec<&'static str> {
        each_once(self.callable_kinds.iter().map(|&k| material_callable(k, &self.own_callables)))
    }

    /// Whether the shadow miss stage is in the pipeline: shadow rays traced by `traceRay`.
    pub fn shadow_miss(&self) -> bool {
        self.shadows && !self.shadow_query && !self.compute
    }
}
