//! How a model read from a file (glTF, OBJ) is seen and lit when it brings no camera or
//! lights of its own: a camera framing its bounds, a key and a fill light set by the camera,
//! and the rest of the scene file around them.

use super::file::{
    default_background, default_shadow_samples, CameraDesc, ImageDesc, LightDesc, MaterialDesc, ObjectDesc, SceneFile,
};
use super::mesh::MeshData;
use super::shape::ShapeDesc;
use glam::Vec3;
use std::collections::{BTreeMap, BTreeSet};

/// A model read from a file as a scene file and its meshes by shape name, and what it has that
/// twinray ignored (for the notice).
pub struct Model {
    pub file: SceneFile,
    pub meshes: BTreeMap<String, MeshData>,
    pub ignored: BTreeSet<String>,
    /// Its own animation, played over frames (a glTF clip); `None` for a still model.
    pub clip: Option<std::sync::Arc<dyn super::animation::Clip>>,
}

/// Height of the image of a model whose camera gives no aspect ratio; width from 4:3.
pub const IMAGE_HEIGHT: u32 = 480;
/// Vertical field of view of the framing camera, in degrees.
pub const FRAMING_FOV_DEGREES: f32 = 45.0;
/// Where the framing camera looks from, relative to the bounds' centre (glTF's +y is up, +z
/// its front): in front, a little right and above.
const FRAMING_DIRECTION: Vec3 = Vec3::new(0.5, 0.4, 1.0);

/// One notice line of what a model read from `source` has that twinray ignored, if anything.
pub fn notice(source: &str, ignored: &BTreeSet<String>) {
    if !ignored.is_empty() {
        let line = format!("{source}: not modelled, ignored: {}", listed(ignored));
        if first_time(&line) {
            log::warn!("{line}");
        }
    }
}

/// Whether this process has not said `line` yet (and now has): a command that loads a model
/// again (`bench` on every fresh device, a moving scene's frames) says its notice once per run.
pub fn first_time(line: &str) -> bool {
    static SAID: std::sync::Mutex<BTreeSet<String>> = std::sync::Mutex::new(BTreeSet::new());
    // A poisoned lock (a panic elsewhere while it was held) still holds a set: use it.
    SAID.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).insert(line.to_string())
}

/// Adds to `ignored` the name of each feature of `found` that a model has: (has it, name).
pub fn ignore_found(ignored: &mut BTreeSet<String>, found: &[(bool, &str)]) {
    ignored.extend(found.iter().filter(|(has, _)| *has).map(|(_, what)| what.to_string()));
}

/// What was ignored, in one comma-separated list.
pub fn listed(ignored: &BTreeSet<String>) -> String {
    ignored.iter().map(String::as_str).collect::<Vec<_>>().join(", ")
}

/// The camera, image size and lights of a model.
pub struct View {
    camera: CameraDesc,
    image: ImageDesc,
    lights: Vec<LightDesc>,
}

impl View {
    /// `camera`, an image 480 high at `aspect` (4:3 where it is absent or unreasonable), and
    /// `lights`, or the key and fill lights where there are none.
    pub fn new(camera: CameraDesc, aspect: Option<f32>, mut lights: Vec<LightDesc>) -> View {
        let aspect = aspect.filter(|a| a.is_finite() && (0.1..=10.0).contains(a)).unwrap_or(4.0 / 3.0);
        let width = ((IMAGE_HEIGHT as f32 * aspect).round() as u32).max(1);
        let image = ImageDesc { width, height: IMAGE_HEIGHT, samples: 1, seed: 0, texture_lod: Default::default() };
        if lights.is_empty() {
            lights = default_lights(&camera);
        }
        View { camera, image, lights }
    }

    /// `objects` (instances of `meshes`) framed by a camera and lit by the key and fill lights.
    pub fn framed(objects: &[ObjectDesc], meshes: &BTreeMap<String, MeshData>) -> View {
        let (lo, hi) = bounds(objects, meshes);
        let (center, radius) = ((lo + hi) / 2.0, ((hi - lo).length() / 2.0).max(1e-6));
        View::new(framing(center, radius), None, Vec::new())
    }
}

/// The world bounds of every object's mesh (their boxes' corners transformed).
pub fn bounds(objects: &[ObjectDesc], meshes: &BTreeMap<String, MeshData>) -> (Vec3, Vec3) {
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for object in objects {
        let Some(mesh) = meshes.get(&object.shape) else { continue };
        let (mlo, mhi) = mesh.vertices.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), v| {
            (a.min(v.position.truncate()), b.max(v.position.truncate()))
        });
        let m = object.transform();
        for k in 0..8 {
            let corner = Vec3::new(
                if k & 1 == 0 { mlo.x } else { mhi.x },
                if k & 2 == 0 { mlo.y } else { mhi.y },
                if k & 4 == 0 { mlo.z } else { mhi.z },
            );
            let p = m.transform_point3(corner);
            (lo, hi) = (lo.min(p), hi.max(p));
        }
    }
    (lo, hi)
}

/// A camera that sees the whole sphere of `radius` about `center`.
pub fn framing(center: Vec3, radius: f32) -> CameraDesc {
    let half = (FRAMING_FOV_DEGREES / 2.0).to_radians();
    let distance = radius / half.sin() * 1.05;
    let eye = center + FRAMING_DIRECTION.normalize() * distance;
    CameraDesc::perspective(eye.into(), center.into(), [0.0, 1.0, 0.0], FRAMING_FOV_DEGREES)
}

/// Two directional lights, white, set by the camera: a key light from above it and to its
/// left (intensity 1, with shadows) and a fill light from its right and a little below
/// (intensity 0.35, without), so that no face the camera sees is black.
fn default_lights(camera: &CameraDesc) -> Vec<LightDesc> {
    let back = (Vec3::from(camera.eye) - Vec3::from(camera.target)).normalize();
    let right = Vec3::from(camera.up).cross(back).normalize_or_zero();
    let up = back.cross(right);
    let light = |direction: Vec3, intensity, shadows| LightDesc::Directional {
        direction: direction.normalize().into(),
        color: [1.0; 3],
        intensity,
        shadows,
    };
    vec![light(back + up * 1.2 - right * 0.6, 1.0, true), light(back - up * 0.3 + right * 1.0, 0.35, false)]
}

/// The scene file of a model: its view, shapes, materials and objects, and twinray's defaults.
pub fn scene_file(
    description: &str,
    view: View,
    shapes: BTreeMap<String, ShapeDesc>,
    materials: BTreeMap<String, MaterialDesc>,
    objects: Vec<ObjectDesc>,
) -> SceneFile {
    SceneFile {
        name: String::new(),
        description: description.into(),
        image: view.image,
        camera: view.camera,
        background: default_background(),
        shadow_samples: default_shadow_samples(),
        shadow_sampler: Default::default(),
        shadow_method: Default::default(),
        material_shading: Default::default(),
        hit_groups: Default::default(),
        renderer: Default::default(),
        gpu_origin: Default::default(),
        features: None,
        materials,
        lights: view.lights,
        shapes,
        objects,
        grids: Vec::new(),
        parity: Default::default(),
        animation: None,
    }
}
