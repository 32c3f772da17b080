//! A twinray scene as Mitsuba 3 scene dictionaries (docs/shading-model.md): one pass per
//! light, and the `emitters` pass that finds the pixels the two renderers cannot agree on.

use super::textures;
use glam::{Mat4, Vec2, Vec3};
use serde_json::{json, Value};
use std::f32::consts::PI;
use twinray_host::error::{Error, Result};
use twinray_host::scene::file::{LightDesc, MaterialDesc};
use twinray_host::scene::shape::ShapeDesc;
use twinray_host::scene::Scene;
use twinray_shared::shapes::mitsuba::{unit_cylinder, unit_sphere, MitsubaKind, MitsubaPart, TriangleMesh};

/// The Mitsuba side of one scene: its passes and the meshes they name.
pub struct MitsubaScene {
    pub passes: Vec<Pass>,
    /// `meshes/NAME.ply` files the passes read, by name, with each vertex's texture
    /// coordinates where the mesh is textured (else none).
    pub meshes: Vec<(String, TriangleMesh, Vec<Vec2>)>,
    /// `textures/N.png` files the passes read.
    pub images: Vec<std::sync::Arc<twinray_host::scene::texture::TextureImage>>,
    /// The scene's background, added where Mitsuba's coverage is not full.
    pub background: [f32; 3],
    /// What was drawn with another shape than twinray's (meshes for cones, tori, ...).
    pub notes: Vec<String>,
}

/// One Mitsuba render.
pub struct Pass {
    /// `light-N` (twinray's light N alone) or `emitters`.
    pub name: String,
    pub scene: Value,
}

/// Name of the pass that renders every emitter at radiance 1 (the mask).
pub const EMITTERS: &str = "emitters";

/// One placed Mitsuba shape of the scene's objects.
struct Placed {
    shape: Value,
    /// Its diffuse reflectance: a colour, or a textured mesh's `bitmap`.
    reflectance: Value,
    emissive: bool,
}

/// `scene` at `width` x `height` with `spp` samples per pixel per pass, or an input error
/// naming what has no Mitsuba equivalent.
pub fn convert(scene: &Scene, (width, height): (u32, u32), spp: u32) -> Result<MitsubaScene> {
    let file = &scene.file;
    let mut meshes = Vec::new();
    let mut notes = Vec::new();
    let mut placed = Vec::new();
    let mut images = textures::Images::default();
    for (i, object) in file.objects.iter().enumerate() {
        let albedo = albedo(scene, &object.material)?;
        let emissive = matches!(file.materials.get(&object.material), Some(MaterialDesc::Emissive { .. }));
        let world = object.transform();
        let texture = textures::texture(scene, &object.material)?;
        if texture.is_some() && !scene.meshes.contains_key(&object.shape) {
            // Mitsuba's own shapes parametrise their surfaces otherwise than twinray's.
            return Err(Error::Input(format!(
                "{}: object {i} (shape {:?}): a texture on a procedural shape has no Mitsuba equivalent (its shapes read other coordinates); use a mesh",
                scene.source, object.shape
            )));
        }
        for (k, part) in parts(scene, &object.shape, &mut notes)?.into_iter().enumerate() {
            let to_world = world * part.to_object;
            let id = format!("o{i}-{k}");
            let shape = shape(part.kind, to_world, &id, &mut meshes, &mut notes);
            let reflectance = match texture {
                Some(t) => {
                    let what = format!("{}: object {i} (shape {:?})", scene.source, object.shape);
                    let uvs = textures::uvs(&scene.meshes[&object.shape], t, &what)?;
                    if let Some(mesh) = meshes.iter_mut().find(|(name, ..)| *name == id) {
                        mesh.2 = uvs;
                    }
                    images.bitmap(t, scene, &object.material)?
                }
                None => rgb(albedo * part.tint),
            };
            placed.push(Placed { shape, reflectance, emissive });
        }
    }
    if scene.file.camera.orthographic_height.is_some() {
        return Err(Error::Input(format!(
            "{}: an orthographic camera, which the cross-check does not hand to Mitsuba yet",
            scene.name()
        )));
    }
    let sensor = sensor(scene, (width, height), spp);
    let mut passes = Vec::new();
    for (l, light) in file.lights.iter().enumerate() {
        let mut dict =
            base(&sensor, json!({"type": "direct", "emitter_samples": 1, "bsdf_samples": 0, "hide_emitters": true}));
        for (j, p) in placed.iter().filter(|p| !p.emissive).enumerate() {
            dict[format!("shape-{j}")] = with_bsdf(&p.shape, diffuse(p.reflectance.clone()));
        }
        for (j, emitter) in light_parts(light, l)?.into_iter().enumerate() {
            dict[format!("light-{j}")] = emitter;
        }
        passes.push(Pass { name: format!("light-{l}"), scene: dict });
    }
    passes.push(Pass { name: EMITTERS.into(), scene: emitters_pass(&sensor, &placed, file) });
    Ok(MitsubaScene { passes, meshes, images: images.images, background: file.background, notes })
}

/// The `emitters` pass: emissive surfaces and rect lights' rectangles at radiance 1, every
/// other surface black, no lights.
fn emitters_pass(sensor: &Value, placed: &[Placed], file: &twinray_host::scene::SceneFile) -> Value {
    let mut dict =
        base(sensor, json!({"type": "direct", "emitter_samples": 1, "bsdf_samples": 0, "hide_emitters": false}));
    for (j, p) in placed.iter().enumerate() {
        let mut shape = with_bsdf(&p.shape, diffuse(rgb(Vec3::ZERO)));
        if p.emissive {
            shape["emitter"] = area(Vec3::ONE);
        }
        dict[format!("shape-{j}")] = shape;
    }
    for (l, light) in file.lights.iter().enumerate() {
        if let LightDesc::Rect { center, u, v, .. } = *light {
            for (k, m) in rect_sides(center.into(), u.into(), v.into()).into_iter().enumerate() {
                dict[format!("rect-{l}-{k}")] = rectangle(m, Vec3::ONE);
            }
        }
    }
    dict
}

/// A scene dictionary with the sensor and `integrator`.
fn base(sensor: &Value, integrator: Value) -> Value {
    json!({"type": "scene", "integrator": integrator, "sensor": sensor})
}

fn sensor(scene: &Scene, (width, height): (u32, u32), spp: u32) -> Value {
    let c = &scene.file.camera;
    let reach = scene.frame_uniform(width, height).reach;
    json!({
        "type": "perspective",
        "fov_axis": "y",
        "fov": c.fov_y_degrees,
        "near_clip": reach.z,
        "far_clip": reach.x,
        "to_world": {"look_at": {"origin": c.eye, "target": c.target, "up": c.up}},
        "film": {"type": "hdrfilm", "width": width, "height": height, "pixel_format": "rgba",
                 "rfilter": {"type": "box"}},
        "sampler": {"type": "stratified", "sample_count": spp},
    })
}

/// The albedo of `material`: emissive ones are black (they light nothing); materials with no
/// Mitsuba equivalent are refused.
fn albedo(scene: &Scene, material: &str) -> Result<Vec3> {
    match scene.file.materials.get(material) {
        Some(MaterialDesc::Diffuse { color, emission: None, .. }) => Ok(Vec3::from(*color)),
        Some(MaterialDesc::Diffuse { .. }) => Err(Error::Input(format!(
            "{}: material {material:?} emits, which the cross-check does not hand to Mitsuba yet",
            scene.source
        ))),
        Some(MaterialDesc::Emissive { .. }) => Ok(Vec3::ZERO),
        Some(MaterialDesc::Checker { .. } | MaterialDesc::Cutout { .. }) => Err(Error::Input(format!(
            "{}: material {material:?} is a checker or cutout, which has no Mitsuba equivalent here (docs/shading-model.md)",
            scene.source
        ))),
        Some(MaterialDesc::Own(own)) => Err(Error::Input(format!(
            "{}: material {material:?} is of a crate's own kind {:?}, which has no Mitsuba equivalent",
            scene.source, own.kind
        ))),
        None => Err(Error::Input(format!("{}: no material {material:?}", scene.source))),
    }
}

/// The Mitsuba parts of shape `name`.
fn parts(scene: &Scene, name: &str, notes: &mut Vec<String>) -> Result<Vec<MitsubaPart>> {
    match scene.file.shapes.get(name) {
        Some(ShapeDesc::Procedural(p)) => {
            let parts = (p.kind.mitsuba)(&p.values);
            if parts.is_empty() {
                return Err(Error::Input(format!(
                    "{}: shape {name:?} of kind {:?} has no Mitsuba equivalent",
                    scene.source, p.kind.name
                )));
            }
            if parts.iter().any(|part| matches!(part.kind, MitsubaKind::Mesh(_))) {
                note(notes, format!("{} shapes are drawn in Mitsuba as fine meshes", p.kind.name));
            }
            Ok(parts)
        }
        Some(ShapeDesc::Own(own)) => Err(Error::Input(format!(
            "{}: shape {name:?} is of a crate's own kind {:?}, which has no Mitsuba equivalent",
            scene.source, own.kind
        ))),
        Some(ShapeDesc::Mesh(_) | ShapeDesc::Gltf(_)) => {
            let data =
                scene.meshes.get(name).ok_or_else(|| Error::Input(format!("no mesh data for shape {name:?}")))?;
            let positions = data.vertices.iter().map(|v| v.position.truncate()).collect();
            let normals = data.vertices.iter().map(|v| v.normal.truncate()).collect();
            let triangles = data.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
            let mesh = TriangleMesh { positions, normals, triangles };
            Ok(vec![MitsubaPart::new(MitsubaKind::Mesh(mesh), Mat4::IDENTITY)])
        }
        None => Err(Error::Input(format!("{}: no shape {name:?}", scene.source))),
    }
}

fn note(notes: &mut Vec<String>, text: String) {
    if !notes.contains(&text) {
        notes.push(text);
    }
}

/// One Mitsuba shape at `to_world`; a sphere or cylinder under a scale Mitsuba's own cannot
/// take becomes a mesh (its file named after `id`).
fn shape(
    kind: MitsubaKind,
    to_world: Mat4,
    id: &str,
    meshes: &mut Vec<(String, TriangleMesh, Vec<Vec2>)>,
    notes: &mut Vec<String>,
) -> Value {
    let kind = match kind {
        MitsubaKind::Sphere if !round(to_world, true) => {
            note(notes, "spheres under a non-uniform scale are drawn in Mitsuba as fine meshes".into());
            MitsubaKind::Mesh(unit_sphere())
        }
        MitsubaKind::Cylinder if !round(to_world, false) => {
            note(notes, "cylinders under a non-uniform scale are drawn in Mitsuba as fine meshes".into());
            MitsubaKind::Mesh(unit_cylinder())
        }
        other => other,
    };
    let matrix = matrix(to_world);
    match kind {
        MitsubaKind::Sphere => json!({"type": "sphere", "to_world": matrix}),
        MitsubaKind::Rectangle => json!({"type": "rectangle", "to_world": matrix}),
        MitsubaKind::Disk => json!({"type": "disk", "to_world": matrix}),
        MitsubaKind::Cube => json!({"type": "cube", "to_world": matrix}),
        MitsubaKind::Cylinder => json!({"type": "cylinder", "to_world": matrix}),
        MitsubaKind::Mesh(mesh) => {
            meshes.push((id.to_string(), mesh, Vec::new()));
            json!({"type": "ply", "filename": format!("meshes/{id}.ply"), "to_world": matrix, "face_normals": false})
        }
    }
}

/// Whether `m`'s x and y axes (and z too, for a `sphere`) have one length and are at right
/// angles: what Mitsuba's sphere (all three) and cylinder (its cross-section) take.
fn round(m: Mat4, sphere: bool) -> bool {
    let [x, y, z] = [m.x_axis.truncate(), m.y_axis.truncate(), m.z_axis.truncate()];
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-5 * a.abs().max(b.abs());
    let right = |a: Vec3, b: Vec3| a.dot(b).abs() <= 1e-5 * a.length() * b.length();
    close(x.length(), y.length())
        && right(x, y)
        && right(x, z)
        && right(y, z)
        && (!sphere || close(x.length(), z.length()))
}

/// Row-major, as Mitsuba's `ScalarTransform4f` takes a nested list.
fn matrix(m: Mat4) -> Value {
    json!(m.transpose().to_cols_array_2d())
}

fn with_bsdf(shape: &Value, bsdf: Value) -> Value {
    let mut s = shape.clone();
    s["bsdf"] = bsdf;
    s
}

fn rgb(c: Vec3) -> Value {
    json!({"type": "rgb", "value": c.to_array()})
}

/// Two-sided Lambert of `reflectance` (Mitsuba's diffuse BSDF is one-sided).
fn diffuse(reflectance: Value) -> Value {
    json!({"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": reflectance}})
}

fn area(radiance: Vec3) -> Value {
    json!({"type": "area", "radiance": rgb(radiance)})
}

/// A black rectangle at `m` emitting `radiance` from its front.
fn rectangle(m: Mat4, radiance: Vec3) -> Value {
    json!({"type": "rectangle", "to_world": matrix(m), "bsdf": diffuse(rgb(Vec3::ZERO)), "emitter": area(radiance)})
}

/// Mitsuba's [-1, 1]^2 rectangle placed as twinray's rect light, facing +(u x v) and -(u x v).
fn rect_sides(center: Vec3, u: Vec3, v: Vec3) -> [Mat4; 2] {
    let n = u.cross(v).normalize();
    let place = |a: Vec3, b: Vec3, n: Vec3| {
        Mat4::from_cols((a / 2.0).extend(0.0), (b / 2.0).extend(0.0), n.extend(0.0), center.extend(1.0))
    };
    [place(u, v, n), place(v, u, -n)]
}

/// Light `l` as Mitsuba emitters (radiance times pi: Mitsuba's Lambert has the 1/pi that
/// twinray's shading leaves out).
fn light_parts(light: &LightDesc, l: usize) -> Result<Vec<Value>> {
    let scaled = |color: [f32; 3], intensity: f32| Vec3::from(color) * intensity * PI;
    let shadows = match *light {
        LightDesc::Directional { shadows, .. } | LightDesc::Point { shadows, .. } | LightDesc::Rect { shadows, .. } => {
            shadows
        }
    };
    if !shadows {
        return Err(Error::Input(format!("light {l} has shadows = false, which Mitsuba cannot render")));
    }
    if let LightDesc::Point { range, spot, .. } = light {
        if range.is_some() || spot.is_some() {
            return Err(Error::Input(format!(
                "light {l} has a range or a spot cone, whose glTF falloff Mitsuba's point and spot lights do not have"
            )));
        }
    }
    Ok(match *light {
        LightDesc::Directional { direction, color, intensity, .. } => vec![json!({
            "type": "directional",
            "direction": (-Vec3::from(direction).normalize()).to_array(),
            "irradiance": rgb(scaled(color, intensity)),
        })],
        LightDesc::Point { position, color, intensity, .. } => {
            vec![json!({"type": "point", "position": position, "intensity": rgb(scaled(color, intensity))})]
        }
        LightDesc::Rect { center, u, v, color, intensity, .. } => rect_sides(center.into(), u.into(), v.into())
            .into_iter()
            .map(|m| rectangle(m, scaled(color, intensity)))
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use twinray_host::scene::MeshFiles;

    fn scene(body: &str) -> Scene {
        let text = format!(
            "[image]\nwidth = 8\nheight = 6\n[camera]\neye = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n\
             fov_y_degrees = 40.0\n[materials.m]\nkind = \"diffuse\"\ncolor = [0.5, 0.5, 0.5]\n{body}"
        );
        Scene::parse(&text, "test.toml", MeshFiles::Builtin).unwrap_or_else(|e| panic!("{e}"))
    }

    const SPHERE: &str = "[shapes.s]\nkind = \"sphere\"\nradius = 1.0\n[[objects]]\nshape = \"s\"\nmaterial = \"m\"\n";

    /// A rect light is two back-to-back emitting rectangles of pi times its radiance; a point
    /// light's intensity and a directional light's irradiance are pi times twinray's, and the
    /// directional one points the other way.
    #[test]
    fn lights_are_scaled_by_pi_and_rect_lights_face_both_ways() {
        let lights = "[[lights]]\nkind = \"rect\"\ncenter = [0.0, 3.0, 0.0]\nu = [2.0, 0.0, 0.0]\nv = [0.0, 0.0, 1.0]\n\
                      color = [1.0, 1.0, 1.0]\nintensity = 2.0\n[[lights]]\nkind = \"directional\"\ndirection = [0.0, 2.0, 0.0]\n\
                      color = [1.0, 0.5, 0.25]\nintensity = 1.0\n";
        let m = convert(&scene(&format!("{SPHERE}{lights}")), (8, 6), 4).unwrap();
        let names: Vec<&str> = m.passes.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["light-0", "light-1", EMITTERS]);
        let rect = &m.passes[0].scene;
        let normal = |v: &Value| {
            let row = |i: usize| {
                Vec3::new(
                    v[i][0].as_f64().unwrap() as f32,
                    v[i][1].as_f64().unwrap() as f32,
                    v[i][2].as_f64().unwrap() as f32,
                )
            };
            // Columns 0 and 1 of the row-major matrix: where Mitsuba's x and y go.
            let (x, y) = (Vec3::new(row(0).x, row(1).x, row(2).x), Vec3::new(row(0).y, row(1).y, row(2).y));
            x.cross(y).normalize()
        };
        let (front, back) = (normal(&rect["light-0"]["to_world"]), normal(&rect["light-1"]["to_world"]));
        // u x v = (2, 0, 0) x (0, 0, 1) points down.
        assert!((front - Vec3::NEG_Y).length() < 1e-6, "{front}");
        assert!((front + back).length() < 1e-6, "{front} {back}");
        let radiance = rect["light-0"]["emitter"]["radiance"]["value"][0].as_f64().unwrap();
        assert!((radiance - 2.0 * std::f64::consts::PI).abs() < 1e-5);
        let sun = &m.passes[1].scene["light-0"];
        assert_eq!(sun["direction"][1].as_f64(), Some(-1.0));
        assert!((sun["irradiance"]["value"][1].as_f64().unwrap() - 0.5 * std::f64::consts::PI).abs() < 1e-5);
        // The emitters pass holds the rect light's two rectangles at radiance 1.
        assert_eq!(m.passes[2].scene["rect-0-1"]["emitter"]["radiance"]["value"][0].as_f64(), Some(1.0));
    }

    /// A sphere under a non-uniform scale is a mesh, a uniform one Mitsuba's own sphere;
    /// cones are meshes, and said so.
    #[test]
    fn shapes_mitsuba_cannot_take_become_meshes() {
        let light =
            "[[lights]]\nkind = \"point\"\nposition = [0.0, 3.0, 0.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n";
        let m = convert(&scene(&format!("{SPHERE}scale = 2.0\n{light}")), (8, 6), 4).unwrap();
        assert_eq!(m.passes[0].scene["shape-0"]["type"], "sphere");
        assert!(m.meshes.is_empty() && m.notes.is_empty());
        let m = convert(&scene(&format!("{SPHERE}scale = [2.0, 1.0, 1.0]\n{light}")), (8, 6), 4).unwrap();
        assert_eq!(m.passes[0].scene["shape-0"]["type"], "ply");
        assert_eq!(m.meshes.len(), 1);
        let cone =
            "[shapes.c]\nkind = \"cone\"\nradius = 1.0\nheight = 2.0\n[[objects]]\nshape = \"c\"\nmaterial = \"m\"\n";
        let m = convert(&scene(&format!("{cone}{light}")), (8, 6), 4).unwrap();
        assert!(m.notes.iter().any(|n| n.contains("cone")), "{:?}", m.notes);
    }

    /// What Mitsuba cannot render is refused by name, before anything is written.
    #[test]
    fn checkers_and_unshadowed_lights_are_refused_by_name() {
        let checker = "[materials.c]\nkind = \"checker\"\ncolors = [[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]\nscale = 1.0\n\
                       [shapes.s]\nkind = \"sphere\"\nradius = 1.0\n[[objects]]\nshape = \"s\"\nmaterial = \"c\"\n";
        let e = convert(&scene(checker), (8, 6), 4).err().expect("refused").to_string();
        assert!(e.contains("\"c\"") && e.contains("checker"), "{e}");
        let light = "[[lights]]\nkind = \"point\"\nposition = [0.0, 3.0, 0.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\nshadows = false\n";
        let e = convert(&scene(&format!("{SPHERE}{light}")), (8, 6), 4).err().expect("refused").to_string();
        assert!(e.contains("light 0") && e.contains("shadows = false"), "{e}");
    }
}
