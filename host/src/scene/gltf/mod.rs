//! glTF 2.0 models (`.gltf` with separate or embedded buffers, `.glb`) as twinray scenes: one
//! more way to fill the scene model TOML fills. Each triangle primitive of a mesh becomes a
//! mesh shape (one BLAS, shared by every node that uses the mesh; a node that morphs or skins
//! it poses one of its own, `deform`), each node that holds a mesh an object per primitive,
//! placed by the node's world matrix; each material a diffuse
//! material of its base colour factor. The model's first camera is the scene's camera (else
//! one framing its bounds) and its KHR_lights_punctual lights its lights (else one key light
//! over the camera's shoulder): see docs/gltf.md. What the model has that twinray does not
//! model is named in one notice per model; an extension the model requires and twinray lacks
//! refuses it.

mod accessors;
mod buffers;
mod clip;
pub use clip::{DEFAULT_FPS, MAX_CLIP_WORK};
mod deform;
mod textures;
pub use super::framing::{notice, Model};
pub use buffers::SUPPORTED_EXTENSIONS;
pub use graph::check as check_graph;
mod framing;
mod geometry;
mod graph;
mod instancing;
mod keyframes;
mod nodes;
use nodes::{posed_name, posed_shapes, shape_name, walk};
mod quantized;
mod rules;
mod shared;

use super::file::{CutoutPattern, EmissionDesc, MaterialDesc, ObjectDesc};
use super::framing::{ignore_found, listed};
use super::mesh::MeshData;
use super::shape::{MeshDesc, ShapeDesc};
use super::texture::TextureDesc;
use glam::Mat4;
use gltf::material::AlphaMode;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Material of primitives that name none: glTF's default (white, here a light grey).
pub const DEFAULT_MATERIAL: &str = "default";

/// Whether `path` names a glTF file, by its extension.
pub fn is_gltf(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// Where Debian's assimp-testmodels (installed by `cargo xtask setup`) keeps its glTF 2.0
/// models: the tests' models that no one here made.
pub const ASSIMP_TEST_MODELS: &str = "/usr/share/assimp/models/glTF2";

/// Every glTF file under `dir` (by extension), in folders below it too, sorted; none when it
/// cannot be read.
pub fn models_under(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for path in std::fs::read_dir(dir).into_iter().flatten().flatten().map(|e| e.path()) {
        if path.is_dir() {
            out.extend(models_under(&path));
        } else if is_gltf(&path) {
            out.push(path);
        }
    }
    out.sort();
    out
}

/// When a model is shown: the time of its animations at frame 0, in seconds, and the
/// frames per second it is played at over frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Playing {
    pub time: f32,
    pub fps: f32,
}

impl Default for Playing {
    fn default() -> Self {
        Playing { time: 0.0, fps: DEFAULT_FPS }
    }
}

static PLAYING: std::sync::OnceLock<Playing> = std::sync::OnceLock::new();

/// Sets when every model this process reads is shown (the global `--time` and `--fps`); the
/// first call wins.
pub fn set_playing(playing: Playing) {
    let _ = PLAYING.set(playing);
}

/// What [`set_playing`] set; 0 s at 24 frames a second if nothing did.
pub fn playing() -> Playing {
    PLAYING.get().copied().unwrap_or_default()
}

/// Reads the model at `path` (its scene `scene`, else its default one), its animations
/// (`keyframes::playing`) played as [`playing`] says; the error says what in it is wrong.
pub fn load(path: &Path, scene: Option<usize>) -> Result<Model, String> {
    load_at(path, scene, playing())
}

/// [`load`] with the animations played as `playing` says.
pub fn load_at(path: &Path, scene: Option<usize>, playing: Playing) -> Result<Model, String> {
    let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    model(buffers::load(path)?, (scene, playing), &name)
}

/// The model of a glTF file's `bytes`, its buffer files (if any) relative to `folder`: what
/// the fuzz target feeds.
pub fn parse(bytes: &[u8], folder: &Path) -> Result<Model, String> {
    model(buffers::parse(bytes, folder, super::mesh::max_mesh_bytes()?)?, (None, Playing::default()), "model")
}

fn model(loaded: buffers::Loaded, (scene, playing): (Option<usize>, Playing), name: &str) -> Result<Model, String> {
    let time = playing.time;
    let buffers::Loaded { gltf, buffers, left_out_ends, folder, mut budget } = loaded;
    let doc = &gltf.document;
    let mut ignored = BTreeSet::new();
    ignored
        .extend(doc.extensions_used().filter(|e| !SUPPORTED_EXTENSIONS.contains(e)).map(|e| format!("extension {e}")));
    let scene = match scene {
        Some(i) => doc.scenes().nth(i).ok_or_else(|| format!("it has no scene {i} ({} scenes)", doc.scenes().len()))?,
        None => doc.default_scene().or_else(|| doc.scenes().next()).ok_or("it has no scene")?,
    };
    graph::check(doc.as_json())?;
    rules::check(doc)?;
    rules::check_data(doc, &buffers)?;
    // A still picture shows the animations a viewer plays together at `time` (0 s unless
    // asked, as viewers open a file).
    let animations = keyframes::playing(doc, &left_out_ends);
    let posed = keyframes::pose(doc, &buffers, &animations, time);
    let mut placed = Vec::new();
    for node in scene.nodes() {
        walk(node, (Mat4::IDENTITY, 0), &posed.matrices, &mut placed)?;
    }

    let mut meshes = meshes(doc, &buffers, &mut ignored)?;
    let worlds: BTreeMap<usize, Mat4> = placed.iter().map(|(node, world)| (node.index(), *world)).collect();
    let mut poses = BTreeMap::new();
    let mut decoded = shared::Decoded::of(doc);
    for (node, _) in &placed {
        if let Some(pose) = deform::Pose::of(node, &posed.weights, &worlds, &buffers)? {
            posed_shapes(node, &pose, (&buffers, &mut decoded), &mut meshes)?;
            poses.insert(node.index(), pose.joints.is_some());
        }
    }
    let (mut objects, mut parts) = (Vec::new(), Vec::new());
    let mut materials = BTreeMap::new();
    let mut images = textures::Images::new();
    let files = textures::Files { buffers: &buffers, folder: &folder, budget: &mut budget };
    let mut read = Read { files, images: &mut images, source: name };
    for (node, world) in &placed {
        let copies = instancing::copies(node, doc, &buffers, *world)?;
        let posed = poses.get(&node.index()).copied();
        // A skinned mesh is placed by its joints alone (`deform`), once.
        let (world, copies) = match posed {
            Some(true) => {
                if copies.is_some() {
                    ignored.insert("EXT_mesh_gpu_instancing copies of a skinned node (drawn once)".into());
                }
                (Mat4::IDENTITY, None)
            }
            _ => (*world, copies),
        };
        let placing = Placing { node, world, copies: copies.as_deref(), meshes: &meshes, posed: posed.is_some() };
        for (copy, object) in placing.objects(&mut read, &mut materials, &mut ignored)? {
            parts.push(clip::Part { node: node.index(), copy, skinned: posed == Some(true) });
            objects.push(object);
        }
    }
    if objects.is_empty() {
        return Err(format!("its scene places no triangles (ignored: {})", listed(&ignored)));
    }
    // A mesh only its posing nodes use is not built at rest.
    let used: BTreeSet<&str> = objects.iter().map(|o| o.shape.as_str()).collect();
    meshes.retain(|name, _| used.contains(name.as_str()));
    let left: Vec<String> = doc
        .animations()
        .map(|a| a.index())
        .filter(|&i| animations.iter().all(|p| p.index != i))
        .map(|i| i.to_string())
        .collect();
    ignored.extend((!left.is_empty()).then(|| {
        let s = if left.len() > 1 { "s" } else { "" };
        format!("animation{s} {} (driving what an animation played drives)", left.join(", "))
    }));
    let shapes = meshes.keys().map(|name| (name.clone(), mesh_shape(name))).collect();
    let played = !animations.is_empty();
    let setup = clip::Setup {
        scene: scene.index(),
        animations,
        start: time,
        fps: playing.fps,
        parts,
        posing: poses.keys().copied().collect(),
        camera: clip::camera(&placed, &objects, &meshes),
        own_lights: !framing::punctual(&placed).is_empty(),
    };
    let view = framing::view(doc, &placed, &objects, &meshes, &mut ignored)?;
    let file = super::framing::scene_file("a glTF 2.0 model", view, shapes, materials, objects);
    let clip = if played { clip::GltfClip::new(gltf.document, buffers, setup, &mut ignored)? } else { None };
    let clip = clip.map(|c| std::sync::Arc::new(c) as std::sync::Arc<dyn super::animation::Clip>);
    Ok(Model { file, meshes, ignored, clip })
}

/// A node to place: its world matrix, its copies' (`EXT_mesh_gpu_instancing`) where it has
/// them, the model's meshes, and whether it poses its mesh (`posed_shapes`).
struct Placing<'a, 'd> {
    node: &'a gltf::Node<'d>,
    world: Mat4,
    copies: Option<&'a [Mat4]>,
    meshes: &'a BTreeMap<String, MeshData>,
    posed: bool,
}

impl Placing<'_, '_> {
    /// An object per triangle primitive of the node's mesh, per copy of the node (with the
    /// copy's index where the node has copies).
    fn objects(
        &self,
        read: &mut Read,
        materials: &mut BTreeMap<String, MaterialDesc>,
        ignored: &mut BTreeSet<String>,
    ) -> Result<Vec<(Option<usize>, ObjectDesc)>, String> {
        let mut objects = Vec::new();
        let Some(mesh) = self.node.mesh() else { return Ok(objects) };
        let node_name = match self.node.name() {
            Some(name) => format!("node {} {name:?}", self.node.index()),
            None => format!("node {}", self.node.index()),
        };
        for (copy, world) in self.copies.unwrap_or(std::slice::from_ref(&self.world)).iter().enumerate() {
            // A scale of zero on an axis is glTF's way to hide a node (and its children): its
            // world matrix has no inverse, so no instance can stand for it, and it is not drawn.
            if world.determinant() == 0.0 {
                ignored.insert("nodes scaled to zero on an axis (not drawn)".into());
                continue;
            }
            for primitive in mesh.primitives() {
                let mut shape = shape_name(&mesh, primitive.index());
                if self.posed {
                    shape = posed_name(&shape, self.node);
                }
                if !self.meshes.contains_key(&shape) {
                    continue; // not triangles
                }
                let material = material(&primitive.material(), materials, read, ignored)?;
                let mut object = ObjectDesc::placed(shape, material, Some(world.to_cols_array()));
                object.single_sided = !primitive.material().double_sided();
                object.name = Some(match self.copies {
                    Some(_) => format!("{node_name} copy {copy}"),
                    None => node_name.clone(),
                });
                objects.push((self.copies.map(|_| copy), object));
            }
        }
        Ok(objects)
    }
}

/// The triangle primitives of every mesh, by shape name.
fn meshes(
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    ignored: &mut BTreeSet<String>,
) -> Result<BTreeMap<String, MeshData>, String> {
    let mut out = BTreeMap::new();
    let mut bad_normals = false;
    let mut decoded = shared::Decoded::of(doc);
    for mesh in doc.meshes() {
        if mesh.primitives().len() == 0 {
            return Err(format!("mesh {} has no primitives (glTF asks for at least one)", mesh.index()));
        }
        for primitive in mesh.primitives() {
            let name = shape_name(&mesh, primitive.index());
            match geometry::primitive(&primitive, buffers, (&mut decoded, None), &name, &mut bad_normals)? {
                geometry::Outcome::Mesh(data) => drop(out.insert(name, data)),
                geometry::Outcome::NotTriangles(mode) => drop(ignored.insert(format!("{mode:?} primitives"))),
            }
            for (semantic, _) in primitive.attributes() {
                use gltf::Semantic as S;
                let modelled = matches!(
                    semantic,
                    S::Positions | S::Normals | S::TexCoords(0 | 1) | S::Colors(0) | S::Joints(_) | S::Weights(_)
                );
                if !modelled {
                    ignored.insert(format!("attribute {}", semantic.to_string()));
                }
            }
        }
    }
    if bad_normals {
        ignored.insert("NORMALs that are not finite or have no length (flat normals used)".into());
    }
    Ok(out)
}

/// A mesh shape whose triangles are given, under `name`, rather than read from a file.
pub(super) fn mesh_shape(name: &str) -> ShapeDesc {
    ShapeDesc::Mesh(MeshDesc { builtin: None, file: Some(name.to_string()), normals: Default::default() })
}

/// What reading a material's texture needs: the model's buffers and budget, its images decoded
/// so far, and its name for errors.
struct Read<'a> {
    files: textures::Files<'a>,
    images: &'a mut textures::Images,
    source: &'a str,
}

/// The name of `m`'s twinray material, added to `materials` the first time.
fn material(
    m: &gltf::Material,
    materials: &mut BTreeMap<String, MaterialDesc>,
    read: &mut Read,
    ignored: &mut BTreeSet<String>,
) -> Result<String, String> {
    let Some(index) = m.index() else {
        materials
            .insert(DEFAULT_MATERIAL.into(), MaterialDesc::Diffuse { color: [0.8; 3], texture: None, emission: None });
        return Ok(DEFAULT_MATERIAL.into());
    };
    let name = match m.name() {
        Some(n) => format!("material {index} {n:?}"),
        None => format!("material {index}"),
    };
    if materials.contains_key(&name) {
        return Ok(name);
    }
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, a] = pbr.base_color_factor();
    let mut texture = |info: Option<gltf::texture::Info>| {
        info.map(|i| textures::read(i, &mut read.files, read.images, read.source, ignored).map(Box::new)).transpose()
    };
    let base = texture(pbr.base_color_texture())?;
    let (color, emission) = if m.unlit() {
        // KHR_materials_unlit: the base colour whatever lights the surface, which is a black
        // surface emitting it (it still casts shadows and keeps its alpha).
        ([0.0; 3], Some(Box::new(EmissionDesc { color: [r, g, b], intensity: 1.0, texture: base.clone() })))
    } else {
        let emissive = texture(m.emissive_texture())?;
        ([r, g, b], emission(m, emissive, base.as_deref(), ignored))
    };
    let texture = base;
    // MASK: alpha-tested at the cutoff. BLEND is drawn the same way at 0.5 (a surface is
    // there where it is at least half opaque): twinray traces no transparency.
    let cutoff = match m.alpha_mode() {
        AlphaMode::Opaque => None,
        AlphaMode::Mask => Some(m.alpha_cutoff().unwrap_or(0.5)),
        AlphaMode::Blend => {
            ignored.insert("alpha mode BLEND (alpha-tested at 0.5)".into());
            Some(0.5)
        }
    };
    let material = match cutoff {
        // A cutoff of 0 or below keeps every hit: opaque.
        Some(c) if c > 0.0 => MaterialDesc::Cutout {
            color,
            pattern: CutoutPattern::Alpha,
            scale: 1.0,
            // A cutoff above 1 (a surface all hole) acts as 1: only full opacity passes.
            threshold: c.min(1.0),
            opacity: a.clamp(0.0, 1.0),
            texture,
            emission,
        },
        _ => MaterialDesc::Diffuse { color, texture, emission },
    };
    materials.insert(name.clone(), material);
    let found = [
        (!m.unlit(), "metallic-roughness (shaded as diffuse)"),
        (m.normal_texture().is_some(), "normal maps"),
        (m.occlusion_texture().is_some(), "occlusion maps"),
    ];
    ignore_found(ignored, &found);
    Ok(name)
}

/// The emission of `m`: its emissive factor (times KHR_materials_emissive_strength) and
/// `texture`, none where the factor is black. Its texture is read through the base colour
/// texture's transform where both have one (a twinray material has one transform).
fn emission(
    m: &gltf::Material,
    texture: Option<Box<TextureDesc>>,
    base: Option<&TextureDesc>,
    ignored: &mut BTreeSet<String>,
) -> Option<Box<EmissionDesc>> {
    let color = m.emissive_factor();
    if color == [0.0; 3] {
        return None;
    }
    let intensity = m.emissive_strength().unwrap_or(1.0);
    let texture = texture.map(|mut t| {
        if let Some(base) = base.filter(|b| b.transform != t.transform) {
            ignored.insert("the emissive texture's own KHR_texture_transform (the base colour's used)".into());
            t.transform = base.transform;
        }
        t
    });
    Some(Box::new(EmissionDesc { color, intensity, texture }))
}

#[cfg(test)]
pub(crate) mod tests;
