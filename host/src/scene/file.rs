//! The scene file format (TOML), as serde reads it. `docs/scene-format.md` documents every
//! field; `check.rs` rejects impossible values; `build.rs` turns a scene into GPU data.

use super::animation::format::AnimationDesc;
pub use super::camera::CameraDesc;
pub use super::light::{LightDesc, SpotDesc};
use super::material::OwnMaterialDesc;
use super::shape::ShapeDesc;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer};
use std::collections::BTreeMap;
use twinray_shared::custom::BUILTIN_MATERIALS;

/// Every `kind` a scene file can name, by section (shapes from the registry); a test checks each
/// parses and is documented.
pub fn kinds() -> [(&'static str, Vec<&'static str>); 4] {
    [
        ("shapes", super::shape::kind_names()),
        ("meshes", vec!["box", "pyramid", "prism", "icosahedron", "(file = OBJ)", "(kind = gltf)"]),
        ("materials", BUILTIN_MATERIALS.to_vec()),
        ("lights", vec!["directional", "point", "rect"]),
    ]
}

/// A scene file, as written (`docs/scene-format.md`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Empty when the file leaves it out: `Scene::parse` fills in the file's stem.
    #[serde(default)]
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub image: ImageDesc,
    pub camera: CameraDesc,
    /// Colour of rays that hit nothing.
    #[serde(default = "default_background")]
    pub background: [f32; 3],
    /// Shadow samples per side of rect lights that do not set their own.
    #[serde(default = "default_shadow_samples")]
    pub shadow_samples: u32,
    /// How rect lights' N x N shadow samples are placed.
    #[serde(default)]
    pub shadow_sampler: ShadowSampler,
    /// How shadow rays are traced: `traceRay`, or inline ray queries.
    #[serde(default)]
    pub shadow_method: ShadowMethod,
    /// Where materials' colours are computed: in the closest-hit stages, or by callables.
    #[serde(default)]
    pub material_shading: MaterialShading,
    /// One hit group per shape kind, or per shape kind and material kind.
    #[serde(default)]
    pub hit_groups: HitGroups,
    /// What renders the image: the ray tracing pipeline, or a compute shader with ray queries.
    #[serde(default)]
    pub renderer: Renderer,
    /// Where the GPU's coordinates are centred (`"local"`, the default, or `"world"`).
    #[serde(default)]
    pub gpu_origin: GpuOrigin,
    /// The features every stage is specialised on (`twinray_shared::features`, by name); left
    /// out, those the scene uses. A list drops the code of features it leaves out even where
    /// the scene uses them, and keeps that of features it names though unused: what a feature's
    /// code costs, measured.
    #[serde(default)]
    pub features: Option<Vec<String>>,
    #[serde(default, deserialize_with = "materials")]
    pub materials: BTreeMap<String, MaterialDesc>,
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    pub shapes: BTreeMap<String, ShapeDesc>,
    #[serde(default)]
    pub objects: Vec<ObjectDesc>,
    /// Regular arrays of objects, expanded into `objects` when the scene is loaded.
    #[serde(default)]
    pub grids: Vec<GridDesc>,
    /// Only comparisons read it; a scene without `[parity]` gets `Parity::default()`.
    #[serde(default)]
    pub parity: Parity,
    /// What moves, frame by frame; a scene without it is still.
    #[serde(default)]
    pub animation: Option<AnimationDesc>,
}

pub(super) fn default_background() -> [f32; 3] {
    [0.3; 3]
}

pub(super) fn default_shadow_samples() -> u32 {
    4
}

fn one() -> u32 {
    1
}

fn unit() -> f32 {
    1.0
}

/// `[image]`: size, samples and seed.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageDesc {
    pub width: u32,
    pub height: u32,
    /// M: M x M stratified, jittered primary rays per pixel.
    #[serde(default = "one")]
    pub samples: u32,
    /// Seed of every random sequence (jitter, light samples).
    #[serde(default)]
    pub seed: u32,
    /// How textures pick their level of detail.
    #[serde(default)]
    pub texture_lod: TextureLod,
}

/// `[image] texture_lod`: by the ray cone's footprint (`"cones"`), or level 0 everywhere
/// (`"zero"`, to compare against renderers that do not filter, or to see what filtering does).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TextureLod {
    #[default]
    Cones,
    Zero,
}

/// A material, by `kind`.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum MaterialDesc {
    /// Lambert reflection with albedo `color`, times its `texture` (on meshes) where it has one,
    /// plus its `emission`.
    Diffuse {
        color: [f32; 3],
        #[serde(default)]
        texture: Option<Box<super::texture::TextureDesc>>,
        #[serde(default)]
        emission: Option<Box<EmissionDesc>>,
    },
    /// Shows `color` x `intensity`; lights nothing.
    Emissive { color: [f32; 3], intensity: f32 },
    /// Alternating cubes of side `1 / scale` in object space.
    Checker { colors: [[f32; 3]; 2], scale: f32 },
    /// Diffuse `color` with holes: where `pattern`'s alpha, over object-space x and z in cells
    /// of side `1 / scale`, is below `threshold`, rays pass through (the any-hit stage).
    /// With `pattern = "alpha"`, the holes are where the surface's own alpha (`opacity` times
    /// its `texture`'s alpha times its vertex colours' alpha; meshes only) is below `threshold`.
    Cutout {
        color: [f32; 3],
        pattern: CutoutPattern,
        scale: f32,
        threshold: f32,
        #[serde(default = "unit")]
        opacity: f32,
        #[serde(default)]
        texture: Option<Box<super::texture::TextureDesc>>,
        #[serde(default)]
        emission: Option<Box<EmissionDesc>>,
    },
    /// A kind of a shader crate's own, coloured by its callable stage.
    #[serde(skip)]
    Own(OwnMaterialDesc),
}

/// A scene's `[materials]`: each table of a kind of twinray's read as serde reads it, one of
/// another well-formed kind kept for the crate that may know it.
fn materials<'de, D: Deserializer<'de>>(deserializer: D) -> Result<BTreeMap<String, MaterialDesc>, D::Error> {
    let entries = BTreeMap::<String, Entry>::deserialize(deserializer)?;
    Ok(entries.into_iter().map(|(name, Entry(m))| (name, m)).collect())
}

struct Entry(MaterialDesc);

impl<'de> Deserialize<'de> for Entry {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let mut table = toml::Table::deserialize(deserializer)?;
        let own = match table.get("kind") {
            Some(toml::Value::String(kind)) => {
                let well_formed = kind.starts_with(|c: char| c.is_ascii_lowercase())
                    && kind.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
                (well_formed && !BUILTIN_MATERIALS.contains(&kind.as_str())).then(|| kind.clone())
            }
            _ => None,
        };
        if let Some(kind) = own {
            table.remove("kind");
            return Ok(Entry(MaterialDesc::Own(OwnMaterialDesc::written(kind, table))));
        }
        toml::Value::Table(table).try_into().map(Entry).map_err(D::Error::custom)
    }
}

/// Radiance a diffuse or cutout surface emits on top of the light it reflects (glTF's emissive
/// factor and texture): `color` x `intensity`, times its `texture` (on meshes) where it has
/// one. Like emissive materials, it lights nothing else.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EmissionDesc {
    pub color: [f32; 3],
    #[serde(default = "unit")]
    pub intensity: f32,
    /// Read through the same transform as the material's own texture, if it has one: a
    /// material has one transform.
    #[serde(default)]
    pub texture: Option<Box<super::texture::TextureDesc>>,
}

impl MaterialDesc {
    /// The material's textures: its own and its emission's.
    pub fn textures_mut(&mut self) -> [Option<&mut super::texture::TextureDesc>; 2] {
        match self {
            MaterialDesc::Diffuse { texture, emission, .. } | MaterialDesc::Cutout { texture, emission, .. } => {
                [texture.as_deref_mut(), emission.as_deref_mut().and_then(|e| e.texture.as_deref_mut())]
            }
            MaterialDesc::Emissive { .. } | MaterialDesc::Checker { .. } | MaterialDesc::Own(_) => [None, None],
        }
    }
}

/// A cutout's alpha pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CutoutPattern {
    /// Alpha 1 in even cells and 0 in odd ones: square holes.
    Checker,
    /// Alpha from 0 at each cell's centre to 1 half a cell away: round holes of radius
    /// `threshold` half-cells.
    Discs,
    /// The surface's own alpha (meshes, through their texture coordinates and colours).
    Alpha,
}

/// One placed shape: a TLAS instance.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDesc {
    /// What reports (`twinray explain`) call it; a glTF model's object is named after its
    /// node.
    #[serde(default)]
    pub name: Option<String>,
    pub shape: String,
    /// Required, but for an object of a glTF model, which takes the model's materials when
    /// this is empty.
    #[serde(default)]
    pub material: String,
    #[serde(default)]
    pub translate: [f32; 3],
    /// Degrees about x, then y, then z.
    #[serde(default)]
    pub rotate: [f32; 3],
    #[serde(default)]
    pub scale: Scale,
    /// A 4x4 matrix, column by column as glTF writes it, applied before `scale`, `rotate`
    /// and `translate`: a glTF node's world transform (which may shear) lands here.
    #[serde(default)]
    pub matrix: Option<[f32; 16]>,
    /// A mesh whose triangles are seen from the front only, as a glTF material that is not
    /// `doubleSided`: primary rays pass through a face seen from behind, shadow rays do not.
    /// The front is where the triangle's corners run counterclockwise in world space (a
    /// mirroring transform flips it). Procedural shapes have no back faces to cull.
    #[serde(default)]
    pub single_sided: bool,
}

impl ObjectDesc {
    /// Shape `shape` of `material`, placed by `matrix` alone (a model's node) or not at all.
    pub fn placed(shape: String, material: String, matrix: Option<[f32; 16]>) -> ObjectDesc {
        let (translate, rotate, scale) = ([0.0; 3], [0.0; 3], Default::default());
        ObjectDesc { name: None, shape, material, translate, rotate, scale, matrix, single_sided: false }
    }

    /// Object space to world space: `matrix`, then scale, rotation and translation.
    pub fn transform(&self) -> glam::Mat4 {
        let placed = object_transform(self.translate, self.rotate, self.scale.axes());
        self.matrix.map_or(placed, |m| placed * glam::Mat4::from_cols_array(&m))
    }
}

/// Scale, then rotation about x, y and z (degrees), then translation.
pub fn object_transform(translate: [f32; 3], rotate_degrees: [f32; 3], scale: [f32; 3]) -> glam::Mat4 {
    let [x, y, z] = rotate_degrees.map(f32::to_radians);
    let rotation = glam::Quat::from_euler(glam::EulerRot::ZYX, z, y, x);
    glam::Mat4::from_scale_rotation_translation(scale.into(), rotation, translate.into())
}

/// `count[0] x count[1] x count[2]` objects of one shape, `spacing` apart from `origin`, each
/// turned `rotate_step` degrees more than the last and using `materials` in turn.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridDesc {
    pub shape: String,
    pub materials: Vec<String>,
    pub count: [u32; 3],
    pub spacing: [f32; 3],
    #[serde(default)]
    pub origin: [f32; 3],
    #[serde(default)]
    pub rotate_step: [f32; 3],
    #[serde(default)]
    pub scale: Scale,
}

impl GridDesc {
    /// The objects of this grid, in x, then y, then z order.
    pub fn objects(&self) -> Vec<ObjectDesc> {
        let [nx, ny, nz] = self.count;
        let mut objects = Vec::with_capacity((nx * ny * nz) as usize);
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    let i = objects.len();
                    let step = i as f32;
                    let at = [x as f32, y as f32, z as f32];
                    objects.push(ObjectDesc {
                        name: None,
                        shape: self.shape.clone(),
                        material: self.materials[i % self.materials.len().max(1)].clone(),
                        translate: std::array::from_fn(|k| self.origin[k] + self.spacing[k] * at[k]),
                        rotate: self.rotate_step.map(|r| (r * step) % 360.0),
                        scale: self.scale,
                        matrix: None,
                        single_sided: false,
                    });
                }
            }
        }
        objects
    }
}

/// A uniform scale factor, or one per axis.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(untagged)]
pub enum Scale {
    /// The same factor on every axis.
    Uniform(f32),
    /// One factor per axis.
    PerAxis([f32; 3]),
}

impl Default for Scale {
    fn default() -> Self {
        Scale::Uniform(1.0)
    }
}

impl Scale {
    /// The factor of each axis.
    pub fn axes(self) -> [f32; 3] {
        match self {
            Scale::Uniform(s) => [s; 3],
            Scale::PerAxis(v) => v,
        }
    }
}

/// How close two shader sets' renders of this scene must be. A key left out takes its
/// default: what eleven of the twelve built-in scenes ask for.
#[derive(Clone, Copy, Debug, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Parity {
    pub max_rmse: f64,
    pub pixel_threshold: u8,
    pub max_pixels_over_threshold: f64,
    pub max_hit_mismatches: f64,
}

impl Default for Parity {
    fn default() -> Self {
        Parity { max_rmse: 0.01, pixel_threshold: 2, max_pixels_over_threshold: 0.002, max_hit_mismatches: 0.002 }
    }
}

/// Placement of a rect light's N x N shadow samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ShadowSampler {
    /// One jittered sample in each cell of an N x N grid over the light.
    #[default]
    Stratified,
    /// N x N independent samples, each anywhere on the light.
    Random,
}

/// How ray generation traces shadow rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ShadowMethod {
    /// `traceRay` with the shadow miss stage.
    #[default]
    Trace,
    /// Inline ray queries (`VK_KHR_ray_query`) from the `raygen_query` stage.
    Query,
}

/// Where the closest-hit stages get a material's colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MaterialShading {
    /// Computed in the closest-hit stage.
    #[default]
    Inline,
    /// Computed by the callable shader that the material's kind selects in the SBT.
    Callable,
}

/// How objects are divided among hit groups (and so among closest-hit shaders).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum HitGroups {
    /// One per shape kind: its closest-hit stage branches on the material's kind.
    #[default]
    PerShape,
    /// One per shape kind and material kind, each instance's SBT offset choosing it: diffuse,
    /// emissive and cutout materials get a closest-hit stage without the branch.
    PerMaterial,
}

/// `gpu_origin`: where the GPU's world coordinates are centred. `Local`: where an object lies
/// far from the world origin for its size (`reach::far_instances`), at the camera's eye for a
/// render, and for a probe each ray where it meets what it can hit (`launches`), so that the driver's f32 transforms and the stages work at the
/// magnitude of what a ray sees, not of the world's coordinates (`scene::origin`). `Eye`: at
/// the camera's eye, always, probes too: what a render's rays get, secondary ones included,
/// shown by a probe. `World`: at the world origin, always: what the driver alone makes of a far
/// scene, shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GpuOrigin {
    #[default]
    Local,
    Eye,
    World,
}

/// What renders the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Renderer {
    /// The ray tracing pipeline: ray generation, miss and hit stages through the SBT.
    #[default]
    Pipeline,
    /// One compute stage (`render_compute`) that traces primary and shadow rays with ray
    /// queries (`VK_KHR_ray_query`), deciding candidates with the same shared code.
    Compute,
}

impl ShadowSampler {
    /// As the scene file writes it.
    pub fn name(self) -> &'static str {
        match self {
            ShadowSampler::Stratified => "stratified",
            ShadowSampler::Random => "random",
        }
    }
}
