//! A glTF model's animations (those a viewer plays together: `keyframes::playing`) played
//! over frames (`--frames`, `--fps`): frame k shows the model as a still picture at `--time`
//! plus k / fps seconds would (`load_at`): each object placed by its node's world matrix then,
//! the camera and the lights by theirs, and every mesh a node morphs or skins posed then, on
//! the host in f64 (`deform`). What moves is said in [`Moves`], so a renderer updates the
//! TLAS, or refits the posed meshes' BLASes, only where something did.
//!
//! Every frame's nodes are posed and checked when the model loads, as a scene file's
//! `[animation]` is: a node scaled to zero (glTF's way to hide one) in some frame, or a camera
//! that degenerates, is refused there with the time named, since an object of a moving scene
//! is drawn in every frame. A clip too long to check (`MAX_CLIP_WORK`) is played as a still,
//! said in the notice. Meshes are posed only for the frames drawn (a still picture of a large
//! skinned model would otherwise pose every frame of its clip to load): a posed vertex that is
//! not finite is refused when its frame is drawn, the frame and time named.

use super::super::animation::{Clip, Moves, MAX_FRAMES};
use super::super::check::{check_camera, check_light, check_placement};
use super::super::file::{CameraDesc, LightDesc, ObjectDesc, SceneFile};
use super::super::mesh::MeshData;
use super::nodes::{posed_shapes, walk};
use super::{deform, framing, instancing, keyframes, shared};
use glam::{Mat4, Vec3};
use std::collections::{BTreeMap, BTreeSet};

/// Frames per second of a clip unless `--fps` says otherwise (a scene file's default too).
pub const DEFAULT_FPS: f32 = 24.0;
/// Most work checking a clip's frames may take: frames times (objects and keys). Beyond it
/// the model is a still picture at its time.
pub const MAX_CLIP_WORK: u64 = 50_000_000;

/// The object of a model that a node places: the node, which of its copies
/// (`EXT_mesh_gpu_instancing`), and whether its mesh is skinned (placed by its joints alone).
#[derive(Clone, Copy, Debug)]
pub struct Part {
    pub node: usize,
    pub copy: Option<usize>,
    pub skinned: bool,
}

/// What a model loaded at its start time hands its clip.
pub struct Setup {
    pub scene: usize,
    /// The animations played (`keyframes::playing`).
    pub animations: Vec<keyframes::Played>,
    pub start: f32,
    pub fps: f32,
    /// The model's objects, in order.
    pub parts: Vec<Part>,
    /// The nodes that pose a mesh of their own (`posed_shapes`).
    pub posing: Vec<usize>,
    /// The camera's node, and the point its target is found from (the model's centre);
    /// `None` for a framing camera, which stays where it is.
    pub camera: Option<(usize, Vec3)>,
    /// Whether the lights are the model's own (they move with their nodes).
    pub own_lights: bool,
}

/// A glTF model's animations played together, its file kept to pose each frame from.
pub struct GltfClip {
    document: gltf::Document,
    buffers: Vec<Vec<u8>>,
    setup: Setup,
    moves: Moves,
    pub frames: u32,
}

impl std::fmt::Debug for GltfClip {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "GltfClip {{ start: {}, fps: {}, frames: {} }}", self.setup.start, self.setup.fps, self.frames)
    }
}

/// What a clip sets at a time.
pub struct At {
    pub objects: Vec<Mat4>,
    pub camera: Option<CameraDesc>,
    pub lights: Option<Vec<LightDesc>>,
}

impl GltfClip {
    /// The clip of `setup.animations` from `setup.start` to their last key, checked at
    /// every frame; `Ok(None)` where it has one frame or is too long to check (`why_still`
    /// then says which).
    pub fn new(
        document: gltf::Document,
        buffers: Vec<Vec<u8>>,
        setup: Setup,
        why_still: &mut BTreeSet<String>,
    ) -> Result<Option<GltfClip>, String> {
        let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
        // The animations' lengths, their channels left out included (`keyframes::Played`).
        let left_out = setup.animations.iter().map(|p| p.left_out_end);
        let (mut end, mut keys, mut trs, mut weights) = (left_out.fold(0.0f32, f32::max), 0u64, false, false);
        for channel in keyframes::channels(&document, &setup.animations) {
            let times: Vec<f32> = channel.reader(get).read_inputs().map(Iterator::collect).unwrap_or_default();
            end = end.max(times.last().copied().unwrap_or(0.0));
            keys += times.len() as u64;
            match channel.target().property() {
                gltf::animation::Property::MorphTargetWeights => weights = true,
                _ => trs = true,
            }
        }
        let span = f64::from((end - setup.start).max(0.0)) * f64::from(setup.fps);
        let frames = (span + 1e-3).floor().min(f64::from(MAX_FRAMES - 1)) as u32 + 1;
        if frames == 1 {
            return Ok(None);
        }
        let work = u64::from(frames) * (setup.parts.len() as u64 + keys + 1);
        if work > MAX_CLIP_WORK {
            why_still.insert(format!(
                "animation over time ({frames} frames of {} objects and {keys} keys are more than {MAX_CLIP_WORK} to check: a still at {} s; lower --fps to play it)",
                setup.parts.len(),
                setup.start
            ));
            return Ok(None);
        }
        let moves = Moves {
            objects: trs && setup.parts.iter().any(|p| !p.skinned),
            lights: trs && setup.own_lights,
            camera: trs && setup.camera.is_some(),
            meshes: !setup.posing.is_empty() && (weights || trs),
        };
        let clip = GltfClip { document, buffers, setup, moves, frames };
        clip.check()?;
        Ok(Some(clip))
    }

    /// Seconds at frame `frame`.
    fn time(&self, frame: u32) -> f32 {
        self.setup.start + frame as f32 / self.setup.fps
    }

    /// Poses every frame and checks it as a still picture's values are checked.
    fn check(&self) -> Result<(), String> {
        for frame in 0..self.frames {
            let time = self.time(frame);
            let at = |e: String| format!("its animation at {time} s (frame {frame} at {} fps): {e}", self.setup.fps);
            let posed = self.at(time).map_err(at)?;
            for (matrix, part) in posed.objects.iter().zip(&self.setup.parts) {
                let object = ObjectDesc::placed(String::new(), String::new(), Some(matrix.to_cols_array()));
                check_placement(&object).map_err(|e| at(format!("node {}: {e}", part.node)))?;
            }
            if let Some(camera) = &posed.camera {
                check_camera(camera).map_err(|e| at(format!("its camera: {e}")))?;
            }
            for light in posed.lights.iter().flatten() {
                check_light(light).map_err(|e| at(format!("a light: {e}")))?;
            }
        }
        Ok(())
    }

    /// The nodes of the model's scene at `time`, each with its world matrix.
    fn placed(&self, time: f32) -> Result<(Vec<(gltf::Node<'_>, Mat4)>, keyframes::Posed), String> {
        let posed = keyframes::pose(&self.document, &self.buffers, &self.setup.animations, time);
        let scene = self.document.scenes().nth(self.setup.scene).ok_or("its scene is gone")?;
        let mut placed = Vec::new();
        for node in scene.nodes() {
            walk(node, (Mat4::IDENTITY, 0), &posed.matrices, &mut placed)?;
        }
        Ok((placed, posed))
    }

    /// The objects' matrices, the camera and the lights at `time`.
    pub fn at(&self, time: f32) -> Result<At, String> {
        let (placed, _) = self.placed(time)?;
        let worlds: BTreeMap<usize, Mat4> = placed.iter().map(|(node, world)| (node.index(), *world)).collect();
        let world = |node: usize| worlds.get(&node).copied().ok_or(format!("node {node} is not placed"));
        let mut copies: BTreeMap<usize, Vec<Mat4>> = BTreeMap::new();
        let mut objects = Vec::with_capacity(self.setup.parts.len());
        for part in &self.setup.parts {
            objects.push(match (part.skinned, part.copy) {
                (true, _) => Mat4::IDENTITY,
                (false, None) => world(part.node)?,
                (false, Some(copy)) => {
                    if let std::collections::btree_map::Entry::Vacant(e) = copies.entry(part.node) {
                        let node = self.document.nodes().nth(part.node).ok_or("a node is gone")?;
                        let all = instancing::copies(&node, &self.document, &self.buffers, world(part.node)?)?;
                        e.insert(all.unwrap_or_default());
                    }
                    copies[&part.node].get(copy).copied().ok_or(format!("node {} lost copy {copy}", part.node))?
                }
            });
        }
        let camera = match self.setup.camera {
            Some((node, center)) => {
                let lens = self.document.nodes().nth(node).and_then(|n| n.camera()).ok_or("a camera is gone")?;
                Some(framing::from_node(world(node)?, &lens, center)?)
            }
            None => None,
        };
        let lights = self.setup.own_lights.then(|| framing::punctual(&placed));
        Ok(At { objects, camera, lights })
    }

    /// Every mesh a node poses, posed at `time`, by shape name.
    pub fn meshes_at(&self, time: f32) -> Result<Vec<(String, MeshData)>, String> {
        if !self.moves.meshes {
            return Ok(Vec::new());
        }
        let (placed, posed) = self.placed(time)?;
        let worlds: BTreeMap<usize, Mat4> = placed.iter().map(|(node, world)| (node.index(), *world)).collect();
        let mut meshes = BTreeMap::new();
        let mut decoded = shared::Decoded::of(&self.document);
        for &index in &self.setup.posing {
            let node = self.document.nodes().nth(index).ok_or("a node is gone")?;
            let pose = deform::Pose::of(&node, &posed.weights, &worlds, &self.buffers)?
                .ok_or(format!("node {index} no longer poses its mesh"))?;
            posed_shapes(&node, &pose, (&self.buffers, &mut decoded), &mut meshes)?;
        }
        if let Some((shape, _)) =
            meshes.iter().find(|(_, m)| m.vertices.iter().any(|v| !v.position.is_finite() || !v.normal.is_finite()))
        {
            return Err(format!("{shape}: a posed vertex is not finite"));
        }
        Ok(meshes.into_iter().collect())
    }
}

/// The camera a clip moves: the first camera's node, and the centre of `objects` (as
/// `framing::view` finds them).
pub fn camera(
    placed: &[(gltf::Node, Mat4)],
    objects: &[ObjectDesc],
    meshes: &BTreeMap<String, MeshData>,
) -> Option<(usize, Vec3)> {
    let node = placed.iter().find(|(node, _)| node.camera().is_some())?.0.index();
    let (lo, hi) = super::super::framing::bounds(objects, meshes);
    Some((node, (lo + hi) / 2.0))
}

impl Clip for GltfClip {
    fn start(&self) -> f32 {
        self.setup.start
    }

    fn fps(&self) -> f32 {
        self.setup.fps
    }

    fn frames(&self) -> u32 {
        self.frames
    }

    fn moves(&self) -> Moves {
        self.moves
    }

    fn pose(&self, time: f32, out: &mut SceneFile) {
        // Every frame was posed and checked when the model loaded (`check`).
        let Ok(at) = self.at(time) else { return };
        for (object, matrix) in out.objects.iter_mut().zip(at.objects) {
            object.matrix = Some(matrix.to_cols_array());
        }
        if let Some(camera) = at.camera {
            out.camera = camera;
        }
        if let Some(lights) = at.lights {
            out.lights = lights;
        }
    }

    fn meshes(&self, time: f32) -> Result<Vec<(String, MeshData)>, String> {
        self.meshes_at(time)
    }

    /// A part's node and copy (`EXT_mesh_gpu_instancing`) place it at every time.
    fn bodies(&self) -> Vec<usize> {
        let mut ids: std::collections::HashMap<(usize, Option<usize>), usize> = Default::default();
        let parts = self.setup.parts.iter();
        parts
            .map(|p| {
                let next = ids.len();
                *ids.entry((p.node, p.copy)).or_insert(next)
            })
            .collect()
    }
}
