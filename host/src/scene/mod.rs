//! Scenes: loaded from a TOML file or by built-in name, checked before any GPU work, and
//! turned into GPU data and a pipeline plan.

pub mod animation;
mod build;
mod builtin;
pub mod camera;
mod check;
pub mod file;
mod framing;
pub mod gltf;
pub mod launches;
pub mod light;
pub mod material;
pub mod merge;
pub mod mesh;
mod models;
pub mod obj;
pub mod origin;
mod placed_clip;
pub mod plan;
pub mod pool;
pub mod reach;
pub mod shape;
pub mod texture;

use crate::error::{Error, Result};
use crate::sets::own::CrateKinds;
use crate::util::input::{confined, read_text, MAX_TEXT_BYTES};
pub use animation::Animation;
pub use build::{frame_data, frame_uniform, Aabb, BlasDesc, FrameData, InstanceDesc, SceneData};
pub use builtin::{BUILTIN, BUILTIN_MESH_FILES, DEFAULT_SCENE};
pub use check::{check_size, MAX_OBJECTS, MAX_PIXELS, MAX_PRIMITIVES, MAX_SAMPLES_PER_SIDE, MAX_SIDE};
pub use file::{object_transform, GpuOrigin, HitGroups, MaterialShading, Parity, Renderer, SceneFile, ShadowMethod};
use glam::Vec3;
pub use mesh::MeshData;
pub use plan::{
    each_once, material_callable, Colour, HitGeometry, HitGroup, PipelinePlan, CUTOUT_ANY_HIT, EXPLAIN, EXPLAIN_QUERY,
    PROBE_QUERY, RENDER_COMPUTE,
};
pub use shape::{Formula, ShapeDesc};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use twinray_shared::layout::FrameUniform;

/// A checked scene, ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    pub file: SceneFile,
    /// Where it came from: a path, or `builtin:NAME`.
    pub source: String,
    /// The triangles of every mesh shape, by shape name.
    pub meshes: BTreeMap<String, Arc<MeshData>>,
    /// What moves, checked; `None` for a still scene. `file` holds frame 0's values.
    pub animation: Option<Animation>,
    /// Where the GPU's world coordinates are centred (see `origin`); `None`, at the world origin.
    pub origin: Option<Vec3>,
    /// A box around where a probe's rays start, in the scene's coordinates
    /// ([`Scene::starting_in`]); the far-instances feature then judges objects from it too
    /// (`reach::far_from`). `None` for a render, which judges by the objects' places alone: its
    /// rays from the eye lose to a far start no more than f32's rounding of the eye allows, and
    /// the feature costs every ray (docs/numerics.md, "A ray brought near its primitive").
    pub ray_starts: Option<Aabb>,
}

impl Scene {
    /// Loads `arg` as a file path, or else as a built-in scene name; `None` is the default scene.
    /// A panic while loading (a bug, here or in a crate, that a file reached) is an error that
    /// names the file, not a crash.
    pub fn load(arg: Option<&str>) -> Result<Scene> {
        Scene::load_with(arg, &[])
    }

    /// [`Scene::load`] with the kinds of the crates' `own` shapes (the sets' of a command) as
    /// well as twinray's.
    pub fn load_with(arg: Option<&str>, own: &[&'static CrateKinds]) -> Result<Scene> {
        crate::util::crash::catching(|| Scene::load_unguarded(arg, own)).unwrap_or_else(|panic| {
            let path = arg.unwrap_or(DEFAULT_SCENE).to_string();
            let message = format!("twinray's loader failed on it (a bug; please report it with the file): {panic}");
            Err(Error::Scene { path, message })
        })
    }

    fn load_unguarded(arg: Option<&str>, own: &[&'static CrateKinds]) -> Result<Scene> {
        if let Some(path) = arg.map(Path::new).filter(|p| gltf::is_gltf(p) && p.exists()) {
            return Scene::load_gltf(path);
        }
        if let Some(path) = arg.map(Path::new).filter(|p| obj::is_obj(p) && p.exists()) {
            return Scene::load_obj(path);
        }
        let (text, source, mesh_files) = Scene::read(arg)?;
        Scene::parse_with(&text, &source, mesh_files, own)
    }

    /// A glTF 2.0 model (`.gltf` or `.glb`) as a scene (see `gltf`); what twinray ignored
    /// in it is said in one notice.
    pub fn load_gltf(path: &Path) -> Result<Scene> {
        let source = path.display().to_string();
        let model = gltf::load(path, None).map_err(|message| Error::Scene { path: source.clone(), message })?;
        gltf::notice(&source, &model.ignored);
        Scene::from_model(model, &source)
    }

    /// An OBJ file and its material library as a scene (see `obj`); what twinray ignored in
    /// it is said in one notice.
    pub fn load_obj(path: &Path) -> Result<Scene> {
        let source = path.display().to_string();
        let model = obj::load(path).map_err(|message| Error::Scene { path: source.clone(), message })?;
        gltf::notice(&source, &model.ignored);
        Scene::from_model(model, &source)
    }

    /// The scene of a glTF model read from `source`, checked as a scene file is.
    pub fn from_model(model: gltf::Model, source: &str) -> Result<Scene> {
        let mut scene = Scene::from_file(model.file, source, MeshFiles::Given(model.meshes), &[])?;
        scene.animation = model.clip.map(|clip| Animation::playing(clip, &scene.file));
        Ok(scene)
    }

    /// The text of the scene `load` would load, the name it goes by in errors, and where its
    /// mesh files are.
    pub fn read(arg: Option<&str>) -> Result<(String, String, MeshFiles)> {
        let arg = arg.unwrap_or(DEFAULT_SCENE);
        let path = Path::new(arg);
        if path.exists() {
            let text = read_text(path, MAX_TEXT_BYTES)
                .map_err(|e| Error::Scene { path: arg.into(), message: format!("cannot read: {e}") })?;
            let folder = path.parent().map(Path::to_path_buf).unwrap_or_default();
            return Ok((text, arg.to_string(), MeshFiles::Folder(folder)));
        }
        if let Some((name, text)) = BUILTIN.iter().find(|(name, _)| *name == arg) {
            return Ok((text.to_string(), format!("builtin:{name}"), MeshFiles::Builtin));
        }
        // The default first, then the rest in order.
        let others = BUILTIN.iter().map(|(n, _)| *n).filter(|n| *n != DEFAULT_SCENE);
        let names: Vec<_> = std::iter::once(DEFAULT_SCENE).chain(others).collect();
        Err(Error::Scene {
            path: arg.into(),
            message: format!("no such file, and no built-in scene of that name (built-ins: {})", names.join(", ")),
        })
    }

    /// Parses and checks scene text and loads its meshes; `source` names it in errors.
    pub fn parse(text: &str, source: &str, mesh_files: MeshFiles) -> Result<Scene> {
        Scene::parse_with(text, source, mesh_files, &[])
    }

    /// [`Scene::parse`] with the kinds of the crates' `own` shapes as well as twinray's.
    pub fn parse_with(text: &str, source: &str, mesh_files: MeshFiles, own: &[&'static CrateKinds]) -> Result<Scene> {
        let file: SceneFile = toml::from_str(text).map_err(|e| toml_error(source, text, &e))?;
        Scene::from_file(file, source, mesh_files, own)
    }

    /// Parses the scene written as the `[scene]` table of a larger TOML document (a probe
    /// case's inline scene): errors give the document's own lines and table names.
    pub fn parse_embedded(
        document: &str,
        source: &str,
        mesh_files: MeshFiles,
        own: &[&'static CrateKinds],
    ) -> Result<Scene> {
        #[derive(serde::Deserialize)]
        struct Document {
            scene: SceneFile,
        }
        let doc: Document = toml::from_str(document).map_err(|e| toml_error(source, document, &e))?;
        Scene::from_file(doc.scene, source, mesh_files, own)
    }

    /// Checks a parsed scene, expands its grids and loads its meshes.
    fn from_file(
        mut file: SceneFile,
        source: &str,
        mut mesh_files: MeshFiles,
        own: &[&'static CrateKinds],
    ) -> Result<Scene> {
        let scene_error = |message: String| Error::Scene { path: source.into(), message };
        shape::resolve_own(file.shapes.iter_mut(), own).map_err(scene_error)?;
        let own_materials = file.materials.iter_mut().filter_map(|(name, m)| match m {
            file::MaterialDesc::Own(desc) => Some((name, desc)),
            _ => None,
        });
        material::resolve_own(own_materials, own).map_err(scene_error)?;
        if file.name.is_empty() {
            let stem = Path::new(source).file_stem().map(|s| s.to_string_lossy().into_owned());
            file.name = stem.unwrap_or_else(|| "scene".into());
        }
        check::check(&file).map_err(scene_error)?;
        let mut grids = Vec::with_capacity(file.grids.len());
        let grid_objects: Vec<_> = file.grids.iter().flat_map(|g| g.objects()).collect();
        for grid in &file.grids {
            let start = grids.last().map_or(file.objects.len(), |r: &std::ops::Range<usize>| r.end);
            grids.push(start..start + grid.count.iter().map(|&c| c as usize).product::<usize>());
        }
        file.objects.extend(grid_objects);
        // Animations move objects as written: a placed glTF model's parts follow their object.
        let written = file.animation.is_some().then(|| file.clone());
        let models::Placed { meshes: mut placed, owners, clip } =
            models::place(&mut file, mesh_files.folder()).map_err(scene_error)?;
        load_textures(&mut file, mesh_files.folder()).map_err(scene_error)?;
        let clip = clip.map(|c| Arc::new(c) as Arc<dyn animation::Clip>);
        let animation = match (&file.animation, &written) {
            (Some(a), Some(written)) => {
                Some(Animation { owners, clip, ..animation::resolve(a, written, &grids).map_err(scene_error)? })
            }
            _ => clip.map(|c| Animation::playing(c, &file)),
        };
        // Whatever reads `file` (a still render, the reference, a probe) sees frame 0.
        if let Some(a) = &animation {
            a.pose(0, &mut file);
        }
        let mut meshes = BTreeMap::new();
        for (name, shape) in &file.shapes {
            if let Some(mesh) = placed.remove(name) {
                meshes.insert(name.clone(), Arc::new(mesh));
            } else if let ShapeDesc::Mesh(m) = shape {
                let mesh = match (m.builtin, &m.file) {
                    (Some(kind), _) => Ok(mesh::builtin(kind, m.normals)),
                    (None, Some(f)) => mesh_files.load(f, m.normals),
                    (None, None) => Err("a mesh needs exactly one of builtin and file".into()),
                };
                let mesh = mesh.map_err(|e| scene_error(format!("shape {name:?}: {e}")))?;
                meshes.insert(name.clone(), Arc::new(mesh));
            }
        }
        let mut scene = Scene { file, source: source.into(), meshes, animation, origin: None, ray_starts: None };
        let data = scene.build();
        scene.check_resolution(&data).map_err(scene_error)?;
        scene.origin = scene.local_origin(&data);
        Ok(scene)
    }

    /// An error when f32 cannot resolve an object where it stands (at frame 0), a warning
    /// on the log when it resolves it only coarsely, or comes nearer the eye than primary rays'
    /// near reach (see `reach`).
    fn check_resolution(&self, data: &SceneData) -> std::result::Result<(), String> {
        let boxes = data.world_boxes();
        let eye = Vec3::from(self.file.camera.eye);
        let near = reach::reach(&boxes, eye).z;
        if let Some((i, d)) = reach::within_near(&boxes, eye, near) {
            log::warn!(
                "scene {}: object {i} comes within {d:e} units of the camera, nearer than primary rays start                  ({near:e}, 2^-20 of their reach): that part of it is not seen",
                self.source
            );
        }
        let Some((i, steps)) = reach::coarsest(&boxes, eye) else { return Ok(()) };
        let b = &boxes[i];
        let size = (b.max - b.min).max_element();
        let magnitude =
            b.min.abs().max(b.max.abs()).max_element().max(Vec3::from(self.file.camera.eye).abs().max_element());
        let what = format!(
            "object {i} (shape {:?}) is {size:e} units wide at {magnitude:e} units from the origin (or the camera's \
             distance), where f32 steps by {:e}: {steps:.1} steps across it",
            self.file.objects.get(i).map_or("of a grid", |o| o.shape.as_str()),
            reach::step(magnitude)
        );
        if steps < reach::UNRESOLVED_STEPS {
            return Err(format!("{what}, so f32 cannot resolve it on the GPU; bring the scene nearer the origin"));
        }
        if steps < reach::COARSE_STEPS {
            log::warn!("scene {}: {what}, so f32 resolves it only coarsely", self.source);
        }
        Ok(())
    }

    /// Where the GPU's coordinates should be centred: at the camera's eye where an object lies
    /// far from the world origin for its size (or always, where the file asks for the eye),
    /// unless the file asks for the world origin.
    fn local_origin(&self, data: &SceneData) -> Option<Vec3> {
        let transforms: Vec<glam::Mat4> = data.instances.iter().map(|i| i.object_to_world).collect();
        let far = reach::far_instances(&data.object_bounds(), &transforms);
        let eye = Vec3::from(self.file.camera.eye);
        match self.file.gpu_origin {
            file::GpuOrigin::Local => far.then_some(eye),
            file::GpuOrigin::Eye => Some(eye),
            file::GpuOrigin::World => None,
        }
    }

    /// The scene as the GPU gets it: moved to its local origin, which the copy no longer has
    /// (its coordinates are local). Borrowed where the origin is the world's.
    pub fn on_gpu(&self) -> std::borrow::Cow<'_, Scene> {
        let Some(o) = self.origin else { return std::borrow::Cow::Borrowed(self) };
        let mut local = self.clone();
        origin::rebase(&mut local.file, o);
        local.origin = None;
        std::borrow::Cow::Owned(local)
    }

    /// `file` (this scene posed at some frame) as the GPU gets it (see [`Scene::on_gpu`]).
    pub fn file_on_gpu<'f>(&self, file: &'f SceneFile) -> std::borrow::Cow<'f, SceneFile> {
        let Some(o) = self.origin else { return std::borrow::Cow::Borrowed(file) };
        let mut local = file.clone();
        origin::rebase(&mut local, o);
        std::borrow::Cow::Owned(local)
    }

    /// The scene centred on `at` where it is centred at all: a probe centres it for each of its
    /// launches (`launches`).
    pub fn centred_on(&self, at: Option<Vec3>) -> std::borrow::Cow<'_, Scene> {
        match (self.origin, at) {
            (Some(o), Some(at)) if o != at => std::borrow::Cow::Owned(Scene { origin: Some(at), ..self.clone() }),
            _ => std::borrow::Cow::Borrowed(self),
        }
    }

    /// The scene with the GPU's coordinates at the world origin: borrowed where they are
    /// there already.
    pub fn at_world_origin(&self) -> std::borrow::Cow<'_, Scene> {
        match self.origin {
            Some(_) => std::borrow::Cow::Owned(Scene { origin: None, ..self.clone() }),
            None => std::borrow::Cow::Borrowed(self),
        }
    }

    /// Gives every rect light `n` x `n` shadow samples.
    pub fn set_shadow_samples(&mut self, n: u32) {
        self.file.shadow_samples = n;
        for light in &mut self.file.lights {
            if let file::LightDesc::Rect { samples, .. } = light {
                *samples = Some(n);
            }
        }
    }

    /// Whether a rect light casts shadows: soft shadows, whose sampler matters.
    pub fn has_soft_shadows(&self) -> bool {
        self.file.lights.iter().any(|l| matches!(l, file::LightDesc::Rect { shadows: true, .. }))
    }

    /// Frames of the animation; a still scene has one.
    pub fn frame_count(&self) -> u32 {
        self.animation.as_ref().map_or(1, |a| a.frames)
    }

    /// Seconds into the animation at frame `frame`; a still scene's, the time its glTF models
    /// were posed at (`gltf::playing`, `--time`).
    pub fn time(&self, frame: u32) -> f32 {
        self.animation.as_ref().map_or_else(|| gltf::playing().time, |a| a.time(frame))
    }

    /// Writes frame `frame`'s values of what moves into `out`, a copy of `self.file`.
    pub fn pose(&self, frame: u32, out: &mut SceneFile) {
        if let Some(animation) = &self.animation {
            animation.pose(frame, out);
        }
    }

    /// The still scene with everything placed as at frame `frame`, its posed meshes (a glTF
    /// clip's skins and morph targets) posed then; an error says what could not be posed.
    pub fn at_frame(&self, frame: u32) -> Result<Scene> {
        let mut still = self.clone();
        self.pose(frame, &mut still.file);
        let posed = self.animation.as_ref().map(|a| a.meshes(frame)).transpose();
        let posed = posed.map_err(|message| Error::Scene { path: self.source.clone(), message })?;
        for (shape, mesh) in posed.into_iter().flatten() {
            still.meshes.insert(shape, Arc::new(mesh));
        }
        still.file.animation = None;
        still.animation = None;
        Ok(still)
    }

    /// The scene seen from `eye` towards `target` (either left as the scene has it when
    /// `None`), with the scene's up and field of view; an impossible camera is refused.
    pub fn with_camera(mut self, eye: Option<[f32; 3]>, target: Option<[f32; 3]>) -> Result<Scene> {
        let camera = &mut self.file.camera;
        camera.eye = eye.unwrap_or(camera.eye);
        camera.target = target.unwrap_or(camera.target);
        check::check_camera(camera).map_err(|e| Error::Input(format!("--eye/--look-at: {e}")))?;
        // A far scene stays centred on the camera, where it now stands.
        self.origin = self.origin.map(|_| Vec3::from(self.file.camera.eye));
        Ok(self)
    }

    /// The scene's `name`.
    pub fn name(&self) -> &str {
        &self.file.name
    }

    /// Buffers, acceleration structure contents and pipeline plan of this scene.
    pub fn build(&self) -> SceneData {
        build::build(&self.file, &self.meshes, self.origin.unwrap_or(Vec3::ZERO), self.ray_starts.as_ref())
    }

    /// The scene traced by a probe's rays, which start in `starts` (scene coordinates).
    pub fn starting_in(&self, starts: Aabb) -> Scene {
        Scene { ray_starts: Some(starts), ..self.clone() }
    }

    /// Camera and frame constants for an image of `width` x `height`.
    pub fn frame_uniform(&self, width: u32, height: u32) -> FrameUniform {
        build::frame_uniform(&self.file, width, height, &self.build().world_boxes())
    }
}

/// Decodes the image of every material texture a scene file names (PNG or JPEG, relative to
/// `folder`; read bounded as mesh files are), each file once. Textures of placed glTF models
/// come decoded.
fn load_textures(file: &mut SceneFile, folder: Option<&Path>) -> std::result::Result<(), String> {
    let mut decoded: BTreeMap<String, std::sync::Arc<texture::TextureImage>> = BTreeMap::new();
    // Every texture file together, encoded and decoded, within the mesh file limit (asked for
    // when the first file is read).
    let mut budget = None;
    let textures =
        file.materials.iter_mut().flat_map(|(name, m)| m.textures_mut().into_iter().flatten().map(move |t| (name, t)));
    for (name, t) in textures {
        if t.image.is_some() {
            continue;
        }
        let image = match decoded.get(&t.file) {
            Some(image) => image.clone(),
            None => {
                let folder =
                    folder.ok_or_else(|| format!("material {name:?}: a built-in scene has no texture files"))?;
                let path =
                    confined(folder, &t.file).map_err(|e| format!("material {name:?}: cannot read texture {e}"))?;
                let mut left = budget.map_or_else(mesh::max_mesh_bytes, Ok)?;
                let bytes = crate::util::input::read_bounded(&path, left)
                    .map_err(|e| format!("material {name:?}: cannot read texture {:?}: {e}", t.file))?;
                left = left.saturating_sub(bytes.len() as u64);
                let image =
                    texture::decode(&t.file, &bytes, true, &mut left).map_err(|e| format!("material {name:?}: {e}"))?;
                budget = Some(left);
                let image = std::sync::Arc::new(image);
                decoded.insert(t.file.clone(), image.clone());
                image
            }
        };
        t.image = Some(image);
    }
    Ok(())
}

/// A TOML error as one line: where (line, column and that line's text) and what.
pub fn toml_error(source: &str, text: &str, e: &toml::de::Error) -> Error {
    let message = e.message().trim().replace('\n', " ");
    let message = match e.span() {
        Some(span) if span.start <= text.len() => {
            let before = &text[..span.start];
            let line = before.matches('\n').count() + 1;
            let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            let quoted = text[span.start - (column - 1)..].lines().next().unwrap_or("").trim();
            // A line of a hostile file may be megabytes long: quote its start only.
            let short: String = quoted.chars().take(60).collect();
            let more = if short.len() < quoted.len() { "..." } else { "" };
            format!("line {line}, column {column} (`{short}{more}`): {message}")
        }
        _ => message,
    };
    Error::Scene { path: source.into(), message }
}

/// Where a scene's mesh files are.
#[derive(Clone, Debug)]
pub enum MeshFiles {
    /// Relative to this folder (the scene file's).
    Folder(PathBuf),
    /// Inside the binary ([`BUILTIN_MESH_FILES`]), for built-in scenes.
    Builtin,
    /// Made already (a glTF model's primitives), by name; each is taken once.
    Given(BTreeMap<String, MeshData>),
}

impl MeshFiles {
    /// The folder files are read from, if they are read from one.
    fn folder(&self) -> Option<&Path> {
        match self {
            MeshFiles::Folder(folder) => Some(folder),
            MeshFiles::Builtin | MeshFiles::Given(_) => None,
        }
    }

    fn load(&mut self, name: &str, normals: shape::Normals) -> std::result::Result<MeshData, String> {
        match self {
            MeshFiles::Given(meshes) => meshes.remove(name).ok_or_else(|| format!("no mesh {name:?} in the model")),
            MeshFiles::Folder(folder) => {
                let path = confined(folder, name).map_err(|e| format!("cannot read mesh file {e}"))?;
                mesh::load_obj(&path, normals)
            }
            MeshFiles::Builtin => match BUILTIN_MESH_FILES.iter().find(|(n, _)| *n == name) {
                Some((_, text)) => mesh::parse_obj(text.as_bytes(), name, normals),
                None => Err(format!("no built-in mesh file {name:?}")),
            },
        }
    }
}

#[cfg(test)]
mod tests;
