//! The clips of glTF models played where a scene file places them (`[shapes.NAME] kind =
//! "gltf"`): at each time each clip poses its model's own parts, and each part of the scene is
//! placed by its object's transform after its posed node, as a still places it after its
//! node at rest. The models' cameras and lights are not the scene's, so the clips move only
//! parts and meshes (skins and morph targets, named `NAME/...` as the models' meshes are).

use super::animation::{Clip, Moves};
use super::file::SceneFile;
use super::mesh::MeshData;
use glam::Mat4;
use std::collections::HashMap;
use std::sync::Arc;

/// Where one object of the scene comes from in a placed model: which model (among the
/// clip's), which placing object (a written object or a grid's), which of the model's parts,
/// and the placing transform.
#[derive(Clone, Copy, Debug)]
pub struct Part {
    pub model: usize,
    pub placement: usize,
    pub part: usize,
    pub placing: Mat4,
}

/// An animated model the scene places: its clip, `NAME/` (what the scene's names of its
/// meshes start with), and its own objects, for the clip to pose.
#[derive(Debug)]
pub struct Model {
    pub clip: Arc<dyn Clip>,
    pub prefix: String,
    pub objects: SceneFile,
}

/// The clips of the animated models a scene places, played together as the scene's: each at
/// the same time (`--time` plus frames at `--fps`), the scene as long as the longest; a model
/// past its last key loops its animations (`keyframes::pose`).
#[derive(Debug)]
pub struct PlacedClip {
    models: Vec<Model>,
    /// For each object of the scene, the part it is (`None`: not of an animated model).
    parts: Vec<Option<Part>>,
}

impl PlacedClip {
    /// The clip of `models` (at least one), their parts where `parts` says.
    pub fn new(models: Vec<Model>, parts: Vec<Option<Part>>) -> PlacedClip {
        assert!(!models.is_empty(), "a placed clip of no model");
        PlacedClip { models, parts }
    }
}

impl Clip for PlacedClip {
    fn start(&self) -> f32 {
        self.models.iter().map(|m| m.clip.start()).fold(f32::INFINITY, f32::min)
    }

    fn fps(&self) -> f32 {
        self.models[0].clip.fps()
    }

    fn frames(&self) -> u32 {
        self.models.iter().map(|m| m.clip.frames()).max().unwrap_or(1)
    }

    fn moves(&self) -> Moves {
        let any = |f: fn(&Moves) -> bool| self.models.iter().any(|m| f(&m.clip.moves()));
        Moves { objects: any(|m| m.objects), lights: false, camera: false, meshes: any(|m| m.meshes) }
    }

    fn pose(&self, time: f32, out: &mut SceneFile) {
        let posed: Vec<SceneFile> = self
            .models
            .iter()
            .map(|m| {
                let mut posed = m.objects.clone();
                m.clip.pose(time, &mut posed);
                posed
            })
            .collect();
        for (object, part) in out.objects.iter_mut().zip(&self.parts) {
            if let Some(p) = part {
                object.matrix = Some((p.placing * posed[p.model].objects[p.part].transform()).to_cols_array());
            }
        }
    }

    fn meshes(&self, time: f32) -> Result<Vec<(String, MeshData)>, String> {
        let mut all = Vec::new();
        for m in &self.models {
            all.extend(m.clip.meshes(time)?.into_iter().map(|(shape, mesh)| (format!("{}{shape}", m.prefix), mesh)));
        }
        Ok(all)
    }

    /// A body of a model under one placing object is a body of the scene; every other object
    /// is one of its own.
    fn bodies(&self) -> Vec<usize> {
        let inner: Vec<Vec<usize>> = self.models.iter().map(|m| m.clip.bodies()).collect();
        let mut ids: HashMap<(usize, usize), usize> = HashMap::new();
        let parts = self.parts.iter().enumerate();
        parts
            .map(|(i, part)| {
                let key = part.map_or((usize::MAX, i), |p| (p.placement, inner[p.model][p.part]));
                let next = ids.len();
                *ids.entry(key).or_insert(next)
            })
            .collect()
    }
}
