//! How a glTF model is seen and lit: its first camera, else one framing its bounds; its
//! KHR_lights_punctual lights, else one key light; and the rest of the scene file around them.

use super::super::file::{
    default_background, default_shadow_samples, CameraDesc, ImageDesc, LightDesc, MaterialDesc, ObjectDesc, SceneFile,
};
use super::super::mesh::MeshData;
use super::super::shape::ShapeDesc;
use glam::{Mat4, Vec3};
use std::collections::{BTreeMap, BTreeSet};

/// Height of the image of a model whose camera gives no aspect ratio; width from 4:3.
pub const IMAGE_HEIGHT: u32 = 480;
/// Vertical field of view of the framing camera, in degrees.
pub const FRAMING_FOV_DEGREES: f32 = 45.0;
/// Where the framing camera looks from, relative to the bounds' centre (glTF's +y is up, +z
/// its front): in front, a little right and above.
const FRAMING_DIRECTION: Vec3 = Vec3::new(0.5, 0.4, 1.0);

/// The camera, image size and lights of a model.
pub struct View {
    camera: CameraDesc,
    image: ImageDesc,
    lights: Vec<LightDesc>,
}

/// How `doc`'s model, its nodes `placed` and `objects` (the meshes' instances), is seen and lit.
pub fn view(
    doc: &gltf::Document,
    placed: &[(gltf::Node, Mat4)],
    objects: &[ObjectDesc],
    meshes: &BTreeMap<String, MeshData>,
    ignored: &mut BTreeSet<String>,
) -> Result<View, String> {
    let (lo, hi) = bounds(objects, meshes);
    let (center, radius) = ((lo + hi) / 2.0, ((hi - lo).length() / 2.0).max(1e-6));
    let first_camera = placed.iter().find_map(|(node, world)| node.camera().map(|c| (c, *world)));
    let (camera, aspect) = match first_camera {
        Some((c, world)) => match c.projection() {
            gltf::camera::Projection::Perspective(p) => (from_node(world, p.yfov(), center)?, p.aspect_ratio()),
            gltf::camera::Projection::Orthographic(_) => {
                ignored.insert("orthographic cameras (the view is framed instead)".into());
                (framing(center, radius), None)
            }
        },
        None => (framing(center, radius), None),
    };
    if doc.cameras().len() > 1 {
        ignored.insert("cameras after the first".into());
    }
    let aspect = aspect.filter(|a| a.is_finite() && (0.1..=10.0).contains(a)).unwrap_or(4.0 / 3.0);
    let width = ((IMAGE_HEIGHT as f32 * aspect).round() as u32).max(1);
    let image = ImageDesc { width, height: IMAGE_HEIGHT, samples: 1, seed: 0, texture_lod: Default::default() };
    let mut lights = punctual(placed, ignored);
    if lights.is_empty() {
        lights = default_lights(&camera);
    }
    Ok(View { camera, image, lights })
}

/// The world bounds of every object's mesh (their boxes' corners transformed).
fn bounds(objects: &[ObjectDesc], meshes: &BTreeMap<String, MeshData>) -> (Vec3, Vec3) {
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

/// A glTF camera node: it looks down its -z with +y up, from its origin.
fn from_node(world: Mat4, yfov: f32, center: Vec3) -> Result<CameraDesc, String> {
    let eye = world.transform_point3(Vec3::ZERO);
    let forward = world.transform_vector3(-Vec3::Z).normalize_or_zero();
    let up = world.transform_vector3(Vec3::Y);
    if forward == Vec3::ZERO || !eye.is_finite() {
        return Err("its camera node's transform is degenerate".into());
    }
    let distance = (center - eye).dot(forward).max(1e-3 * (center - eye).length()).max(1e-6);
    let target = eye + forward * distance;
    Ok(CameraDesc { eye: eye.into(), target: target.into(), up: up.into(), fov_y_degrees: yfov.to_degrees() })
}

/// A camera that sees the whole sphere of `radius` about `center`.
fn framing(center: Vec3, radius: f32) -> CameraDesc {
    let half = (FRAMING_FOV_DEGREES / 2.0).to_radians();
    let distance = radius / half.sin() * 1.05;
    let eye = center + FRAMING_DIRECTION.normalize() * distance;
    CameraDesc { eye: eye.into(), target: center.into(), up: [0.0, 1.0, 0.0], fov_y_degrees: FRAMING_FOV_DEGREES }
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

/// The model's KHR_lights_punctual lights at their nodes; spot lights become point lights.
fn punctual(placed: &[(gltf::Node, Mat4)], ignored: &mut BTreeSet<String>) -> Vec<LightDesc> {
    use gltf::khr_lights_punctual::Kind;
    let mut lights = Vec::new();
    for (node, world) in placed {
        let Some(light) = node.light() else { continue };
        let (color, intensity) = (light.color(), light.intensity());
        if !(intensity > 0.0 && intensity.is_finite()) {
            continue;
        }
        let position = world.transform_point3(Vec3::ZERO);
        lights.push(match light.kind() {
            Kind::Directional => {
                let direction = world.transform_vector3(Vec3::Z).normalize_or_zero();
                LightDesc::Directional { direction: direction.into(), color, intensity, shadows: true }
            }
            Kind::Point => LightDesc::Point { position: position.into(), color, intensity, shadows: true },
            Kind::Spot { .. } => {
                ignored.insert("spot light cones (spot lights shine as point lights)".into());
                LightDesc::Point { position: position.into(), color, intensity, shadows: true }
            }
        });
        if light.range().is_some() {
            ignored.insert("light ranges".into());
        }
    }
    lights
}

/// The scene file of a model: its view, shapes, materials and objects, and twinray's defaults.
pub fn scene_file(
    view: View,
    shapes: BTreeMap<String, ShapeDesc>,
    materials: BTreeMap<String, MaterialDesc>,
    objects: Vec<ObjectDesc>,
) -> SceneFile {
    SceneFile {
        name: String::new(),
        description: "a glTF 2.0 model".into(),
        image: view.image,
        camera: view.camera,
        background: default_background(),
        shadow_samples: default_shadow_samples(),
        shadow_sampler: Default::default(),
        shadow_method: Default::default(),
        material_shading: Default::default(),
        hit_groups: Default::default(),
        renderer: Default::default(),
        materials,
        lights: view.lights,
        shapes,
        objects,
        grids: Vec::new(),
        parity: Default::default(),
        animation: None,
    }
}
