//! How a glTF model is seen and lit: its first camera, else one framing its bounds; its
//! KHR_lights_punctual lights, else the key and fill lights (`scene::framing`).

use super::super::file::{CameraDesc, LightDesc, ObjectDesc, SpotDesc};
use super::super::framing::{bounds, framing, View, FRAMING_FOV_DEGREES};
use super::super::mesh::MeshData;
use glam::{Mat4, Vec3};
use std::collections::{BTreeMap, BTreeSet};

/// How `doc`'s model, its nodes `placed` and `objects` (the meshes' instances), is seen and lit:
/// its first camera and its lights where it has them, else framed and lit as any model.
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
        Some((c, world)) => (from_node(world, &c, center)?, aspect_of(&c)),
        None => (framing(center, radius), None),
    };
    if doc.cameras().len() > 1 {
        ignored.insert("cameras after the first".into());
    }
    Ok(View::new(camera, aspect, punctual(placed)))
}

/// The width over the height of what `camera` sees, where it says.
fn aspect_of(camera: &gltf::Camera) -> Option<f32> {
    match camera.projection() {
        gltf::camera::Projection::Perspective(p) => p.aspect_ratio(),
        gltf::camera::Projection::Orthographic(o) => Some(o.xmag() / o.ymag()),
    }
}

/// A glTF camera node: it looks down its -z with +y up, from its origin; a perspective camera
/// by its vertical field of view, an orthographic one seeing `2 ymag` high (`ymag` is half the
/// height, as glTF has it).
pub(super) fn from_node(world: Mat4, camera: &gltf::Camera, center: Vec3) -> Result<CameraDesc, String> {
    let (yfov, height) = match camera.projection() {
        gltf::camera::Projection::Perspective(p) => (p.yfov(), None),
        gltf::camera::Projection::Orthographic(o) => (FRAMING_FOV_DEGREES.to_radians(), Some(2.0 * o.ymag())),
    };
    let eye = world.transform_point3(Vec3::ZERO);
    let forward = world.transform_vector3(-Vec3::Z).normalize_or_zero();
    let up = world.transform_vector3(Vec3::Y);
    if forward == Vec3::ZERO || !eye.is_finite() {
        return Err("its camera node's transform is degenerate".into());
    }
    let distance = (center - eye).dot(forward).max(1e-3 * (center - eye).length()).max(1e-6);
    let target = eye + forward * distance;
    let perspective = CameraDesc::perspective(eye.into(), target.into(), up.into(), yfov.to_degrees());
    Ok(CameraDesc { orthographic_height: height, ..perspective })
}

/// The model's KHR_lights_punctual lights at their nodes, with their ranges; a spot light is a
/// point light with a cone about its node's -z.
pub(super) fn punctual(placed: &[(gltf::Node, Mat4)]) -> Vec<LightDesc> {
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
            Kind::Point | Kind::Spot { .. } => {
                let spot = match light.kind() {
                    Kind::Spot { inner_cone_angle, outer_cone_angle } => Some(SpotDesc {
                        direction: world.transform_vector3(-Vec3::Z).normalize_or_zero().into(),
                        inner_cone_degrees: inner_cone_angle.to_degrees(),
                        outer_cone_degrees: outer_cone_angle.to_degrees().min(90.0),
                    }),
                    _ => None,
                };
                let (position, range) = (position.into(), light.range());
                LightDesc::Point { position, color, intensity, shadows: true, range, spot }
            }
        });
    }
    lights
}
