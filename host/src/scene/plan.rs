//! What the ray tracing pipeline of a scene contains: its hit groups, in the order of the
//! shader binding table, whether it traces shadow rays, and its specialisation.

use twinray_shared::shapes::{Shape, SHAPES};

/// A hit group: the built-in triangle test, or a registered shape's intersection stage.
/// Ordered as the SBT holds them: triangles, the robust shapes in registration order, then the
/// naive variants.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum HitGroup {
    /// Meshes: the built-in triangle test.
    Triangles,
    /// `SHAPES[shape]`, with its naive variant's intersection stage when `naive`.
    Procedural { naive: bool, shape: usize },
}

impl HitGroup {
    /// "triangles", or the shape's name, with " (naive)" for a naive variant.
    pub fn name(self) -> String {
        match (self, self.shape()) {
            (HitGroup::Procedural { naive: true, .. }, Some(s)) => format!("{} (naive)", s.name),
            (_, Some(s)) => s.name.to_string(),
            _ => "triangles".into(),
        }
    }

    /// The registered shape of a procedural group.
    pub fn shape(self) -> Option<&'static Shape> {
        match self {
            HitGroup::Triangles => None,
            HitGroup::Procedural { shape, .. } => SHAPES.get(shape),
        }
    }

    /// The intersection module, for procedural groups (triangles use the built-in test).
    pub fn intersection_module(self) -> Option<&'static str> {
        let naive = matches!(self, HitGroup::Procedural { naive: true, .. });
        self.shape().and_then(|s| if naive { s.naive_module } else { Some(s.module) })
    }

    /// The closest-hit module of the group.
    pub fn closest_hit_module(self) -> &'static str {
        match self {
            HitGroup::Triangles => "triangle_closest_hit",
            HitGroup::Procedural { .. } => "procedural_closest_hit",
        }
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
}
