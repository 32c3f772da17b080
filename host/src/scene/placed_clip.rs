//! A glTF model's clip played where a scene file places the model (`[shapes.NAME] kind =
//! "gltf"`): at each time the clip poses the model's own parts, and each part of the scene is
//! placed by its object's transform after its posed node, as a still places it after its
//! node at rest. The model's cameras and lights are not the scene's, so the clip moves only
//! parts and meshes (its skins and morph targets, named `NAME/...` as the model's meshes are).

use super::animation::{Clip, Moves};
use super::file::SceneFile;
use super::mesh::MeshData;
use glam::Mat4;
use std::collections::HashMap;
use std::sync::Arc;

/// Where one object of the scene comes from in a placed model: which placing object (a
/// written object or a grid's), which of the model's parts, and the placing transform.
#[derive(Clone, Copy, Debug)]
pub struct Part {
    pub placement: usize,
    pub part: usize,
    pub placing: Mat4,
}

/// A model's clip, as the scene's.
#[derive(Debug)]
pub struct PlacedClip {
    clip: Arc<dyn Clip>,
    /// `NAME/`, what the scene's names of the model's meshes start with.
    prefix: String,
    /// The model's own objects, for the clip to pose.
    model: SceneFile,
    /// For each object of the scene, the part it is (`None`: not of the model).
    parts: Vec<Option<Part>>,
}

impl PlacedClip {
    pub fn new(clip: Arc<dyn Clip>, name: &str, model: SceneFile, parts: Vec<Option<Part>>) -> PlacedClip {
        PlacedClip { clip, prefix: format!("{name}/"), model, parts }
    }
}

impl Clip for PlacedClip {
    fn start(&self) -> f32 {
        self.clip.start()
    }

    fn fps(&self) -> f32 {
        self.clip.fps()
    }

    fn frames(&self) -> u32 {
        self.clip.frames()
    }

    fn moves(&self) -> Moves {
        let inner = self.clip.moves();
        Moves { objects: inner.objects, lights: false, camera: false, meshes: inner.meshes }
    }

    fn pose(&self, time: f32, out: &mut SceneFile) {
        let mut posed = self.model.clone();
        self.clip.pose(time, &mut posed);
        for (object, part) in out.objects.iter_mut().zip(&self.parts) {
            if let Some(p) = part {
                object.matrix = Some((p.placing * posed.objects[p.part].transform()).to_cols_array());
            }
        }
    }

    fn meshes(&self, time: f32) -> Result<Vec<(String, MeshData)>, String> {
        let meshes = self.clip.meshes(time)?;
        Ok(meshes.into_iter().map(|(shape, mesh)| (format!("{}{shape}", self.prefix), mesh)).collect())
    }

    /// A body of the model under one placing object is a body of the scene; every other
    /// object is one of its own.
    fn bodies(&self) -> Vec<usize> {
        let inner = self.clip.bodies();
        let mut ids: HashMap<(usize, usize), usize> = HashMap::new();
        let parts = self.parts.iter().enumerate();
        parts
            .map(|(i, part)| {
                let key = part.map_or((usize::MAX, i), |p| (p.placement, inner[p.part]));
                let next = ids.len();
                *ids.entry(key).or_insert(next)
            })
            .collect()
    }
}
