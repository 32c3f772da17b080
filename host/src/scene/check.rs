//! Rejects well-formed scene files with impossible values, naming the field or object.

use super::file::{
    CameraDesc, EmissionDesc, GridDesc, HitGroups, LightDesc, MaterialDesc, MaterialShading, ObjectDesc, Parity,
    Renderer, SceneFile,
};
use super::shape::ShapeDesc;
use super::texture::TextureDesc;
use glam::Vec3;
use twinray_shared::shapes::spec::{MAX_LENGTH, MIN_LENGTH};

/// Largest number of primitives one shape may have, and of objects in a scene.
pub use twinray_shared::shapes::spec::MAX_PRIMITIVES;
/// Largest number of objects in a scene, counting grids.
pub const MAX_OBJECTS: usize = 1 << 20;
/// Most lights in a scene: every hit shades every light (and traces its shadow rays), and
/// the lights buffer holds this many.
pub const MAX_LIGHTS: usize = twinray_shared::bindings::MAX_LIGHTS as usize;
/// Largest M (M x M primary samples) and N (N x N shadow samples per rect light).
pub const MAX_SAMPLES_PER_SIDE: u32 = 16;

/// Largest image side, and largest pixel count, twinray accepts before asking the device.
pub const MAX_SIDE: u32 = 16384;
/// Largest pixel count of an image.
pub const MAX_PIXELS: u64 = 8192 * 8192;

/// Checks an image size against twinray's own limits.
pub fn check_size(width: u32, height: u32) -> std::result::Result<(), String> {
    if width == 0 || height == 0 {
        return Err(format!("image size {width}x{height}: width and height must be at least 1"));
    }
    if width > MAX_SIDE || height > MAX_SIDE || u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(format!(
            "image size {width}x{height} is too large (at most {MAX_SIDE} per side and {MAX_PIXELS} pixels)"
        ));
    }
    Ok(())
}

type Checked = Result<(), String>;

/// Smallest and largest magnitude of an object's scale on any axis: beyond, its world-to-object
/// transform (the inverse) overflows or loses the object in f32 rounding.
pub const SCALE_RANGE: (f32, f32) = (1.0e-6, 1.0e6);

/// Finite numbers of magnitude at most `MAX_LENGTH` (coordinates, directions, colours, angles).
pub(super) fn finite(name: &str, values: &[f32]) -> Checked {
    if values.iter().all(|v| v.is_finite()) {
        if let Some(v) = values.iter().find(|v| v.abs() > MAX_LENGTH) {
            return Err(format!(
                "{name} must be at most {MAX_LENGTH:e} in magnitude (got {v:e}): beyond, its GPU data overflows f32"
            ));
        }
        Ok(())
    } else {
        Err(format!("{name} must be finite numbers (got {values:?})"))
    }
}

fn color(name: &str, c: [f32; 3]) -> Checked {
    finite(name, &c)?;
    if c.iter().any(|v| *v < 0.0) {
        return Err(format!("{name} must not be negative (got {c:?})"));
    }
    Ok(())
}

fn positive(name: &str, v: f32) -> Checked {
    if !(v > 0.0 && v.is_finite()) {
        return Err(format!("{name} must be > 0 (got {v})"));
    }
    if !(MIN_LENGTH..=MAX_LENGTH).contains(&v) {
        return Err(format!("{name} must be in [{MIN_LENGTH:e}, {MAX_LENGTH:e}] (got {v:e}): beyond, its GPU data overflows or degenerates in f32"));
    }
    Ok(())
}

fn samples(name: &str, n: u32) -> Checked {
    if (1..=MAX_SAMPLES_PER_SIDE).contains(&n) {
        Ok(())
    } else {
        Err(format!("{name} must be in 1..={MAX_SAMPLES_PER_SIDE} (got {n})"))
    }
}

pub fn check(scene: &SceneFile) -> Checked {
    check_size(scene.image.width, scene.image.height).map_err(|e| format!("image: {e}"))?;
    samples("image.samples", scene.image.samples)?;
    samples("shadow_samples", scene.shadow_samples)?;
    check_camera(&scene.camera)?;
    check_renderer(scene)?;
    for name in scene.features.iter().flatten() {
        if twinray_shared::features::by_name(name).is_none() {
            let known = twinray_shared::features::names(twinray_shared::features::ALL);
            return Err(format!("features: no feature {name:?} (the features are {known})"));
        }
    }
    color("background", scene.background)?;
    for (name, m) in &scene.materials {
        check_material(m).map_err(|e| format!("material {name:?}: {e}"))?;
    }
    if scene.lights.len() > MAX_LIGHTS {
        return Err(format!(
            "a scene has at most {MAX_LIGHTS} lights (got {}): every hit shades every light",
            scene.lights.len()
        ));
    }
    for (i, light) in scene.lights.iter().enumerate() {
        check_light(light).map_err(|e| format!("lights[{i}]: {e}"))?;
    }
    let mut primitives = 0u64;
    for (name, shape) in &scene.shapes {
        check_shape(shape).map_err(|e| format!("shape {name:?}: {e}"))?;
        primitives += shape.primitive_count();
    }
    // An object's first primitive travels in the 24-bit instance custom index.
    if primitives >= 1 << 24 {
        return Err(format!("the shapes hold {primitives} procedural primitives; at most {} fit", (1 << 24) - 1));
    }
    let mut total = scene.objects.len() as u64;
    for (i, grid) in scene.grids.iter().enumerate() {
        check_grid(scene, grid).map_err(|e| format!("grids[{i}] (shape {:?}): {e}", grid.shape))?;
        total += grid.count.iter().map(|&c| u64::from(c)).product::<u64>();
    }
    if total == 0 || total > MAX_OBJECTS as u64 {
        return Err(format!("a scene needs 1..={MAX_OBJECTS} objects, counting grids (got {total})"));
    }
    for (i, object) in scene.objects.iter().enumerate() {
        check_object(scene, object).map_err(|e| format!("objects[{i}] (shape {:?}): {e}", object.shape))?;
    }
    check_parity(&scene.parity)
}

/// The compute renderer has no SBT: no callables, and no hit groups to divide objects among.
fn check_renderer(scene: &SceneFile) -> Checked {
    if scene.renderer != Renderer::Compute {
        return Ok(());
    }
    if scene.material_shading == MaterialShading::Callable {
        return Err("renderer = \"compute\" computes material colours inline: it has no callables \
                    (material_shading = \"callable\" needs renderer = \"pipeline\")"
            .into());
    }
    if let Some(own) = scene.materials.values().find_map(|m| if let MaterialDesc::Own(o) = m { Some(o) } else { None })
    {
        return Err(format!(
            "renderer = \"compute\" has no callables, which colour a crate's own material kinds \
             ({:?} needs renderer = \"pipeline\")",
            own.kind
        ));
    }
    if scene.hit_groups == HitGroups::PerMaterial {
        return Err("renderer = \"compute\" has no hit groups (hit_groups = \"per-material\" needs \
                    renderer = \"pipeline\")"
            .into());
    }
    Ok(())
}

pub(super) fn check_camera(c: &CameraDesc) -> Checked {
    finite("camera.eye", &c.eye)?;
    finite("camera.target", &c.target)?;
    finite("camera.up", &c.up)?;
    let forward = Vec3::from(c.target) - Vec3::from(c.eye);
    if forward.length_squared() == 0.0 {
        return Err("camera.eye and camera.target must differ".into());
    }
    if forward.cross(Vec3::from(c.up)).length_squared() == 0.0 {
        return Err("camera.up must not be zero or parallel to the view direction".into());
    }
    if !(c.fov_y_degrees > 0.0 && c.fov_y_degrees < 180.0) {
        return Err(format!("camera.fov_y_degrees must be in (0, 180) (got {})", c.fov_y_degrees));
    }
    match c.orthographic_height {
        Some(h) if !(h.is_finite() && h > 0.0 && h <= MAX_LENGTH) => {
            Err(format!("camera.orthographic_height must be a height above 0, at most {MAX_LENGTH:e} (got {h})"))
        }
        _ => Ok(()),
    }
}

fn check_material(m: &MaterialDesc) -> Checked {
    match m {
        // Its keys were checked by their rules and the crate's `check` when resolved.
        MaterialDesc::Own(_) => Ok(()),
        MaterialDesc::Diffuse { color: c, texture, emission } => {
            color("color", *c)?;
            check_texture("texture", texture.as_deref())?;
            check_emission(emission.as_deref(), texture.as_deref())
        }
        MaterialDesc::Emissive { color: c, intensity } => {
            color("color", *c)?;
            positive("intensity", *intensity)
        }
        MaterialDesc::Checker { colors, scale } => {
            color("colors[0]", colors[0])?;
            color("colors[1]", colors[1])?;
            positive("scale", *scale)
        }
        MaterialDesc::Cutout { color: c, scale, threshold, opacity, texture, emission, .. } => {
            color("color", *c)?;
            positive("scale", *scale)?;
            if !(0.0..=1.0).contains(opacity) {
                return Err(format!("opacity must be in [0, 1] (got {opacity})"));
            }
            check_texture("texture", texture.as_deref())?;
            check_emission(emission.as_deref(), texture.as_deref())?;
            if !(*threshold > 0.0 && *threshold <= 1.0) {
                return Err(format!("threshold must be in (0, 1] (got {threshold})"));
            }
            Ok(())
        }
    }
}

fn check_texture(name: &str, texture: Option<&TextureDesc>) -> Checked {
    match texture {
        Some(t) if t.uv > 1 => Err(format!("{name}.uv must be 0 or 1 (got {})", t.uv)),
        Some(t) if t.file.is_empty() => Err(format!("{name}.file must name an image")),
        Some(t) => finite(&format!("{name}.transform"), &t.transform.concat()),
        None => Ok(()),
    }
}

/// A material's emission, beside its own `texture`: both textures go through one transform.
fn check_emission(emission: Option<&EmissionDesc>, texture: Option<&TextureDesc>) -> Checked {
    let Some(e) = emission else { return Ok(()) };
    color("emission.color", e.color)?;
    if !(e.intensity >= 0.0 && e.intensity.is_finite()) {
        return Err(format!("emission.intensity must be finite and not negative (got {})", e.intensity));
    }
    check_texture("emission.texture", e.texture.as_deref())?;
    if let (Some(own), Some(t)) = (texture, e.texture.as_deref()) {
        if own.transform != t.transform {
            return Err(format!(
                "emission.texture.transform {:?} differs from texture.transform {:?}: a material's textures share one transform",
                t.transform, own.transform
            ));
        }
    }
    Ok(())
}

pub(super) fn check_light(light: &LightDesc) -> Checked {
    match light {
        LightDesc::Directional { direction, color: c, intensity, .. } => {
            finite("direction", direction)?;
            if Vec3::from(*direction).length_squared() == 0.0 {
                return Err("direction must not be zero".into());
            }
            color("color", *c)?;
            positive("intensity", *intensity)
        }
        LightDesc::Point { position, color: c, intensity, range, spot, .. } => {
            finite("position", position)?;
            color("color", *c)?;
            positive("intensity", *intensity)?;
            range.map_or(Ok(()), |r| positive("range", r))?;
            spot.as_ref().map_or(Ok(()), check_spot)
        }
        LightDesc::Rect { center, u, v, color: c, intensity, samples: n, .. } => {
            finite("center", center)?;
            finite("u", u)?;
            finite("v", v)?;
            if Vec3::from(*u).cross(Vec3::from(*v)).length_squared() == 0.0 {
                return Err("u and v span no area (zero-area light)".into());
            }
            color("color", *c)?;
            positive("intensity", *intensity)?;
            n.map_or(Ok(()), |n| samples("samples", n))
        }
    }
}

/// A cone along a direction, its inner angle below its outer one, within a quarter turn.
fn check_spot(spot: &super::light::SpotDesc) -> Checked {
    finite("spot.direction", &spot.direction)?;
    if Vec3::from(spot.direction).length_squared() == 0.0 {
        return Err("spot.direction must not be zero".into());
    }
    let (inner, outer) = (spot.inner_cone_degrees, spot.outer_cone_degrees);
    if !((0.0..90.0).contains(&inner) && inner < outer && outer <= 90.0) {
        return Err(format!(
            "spot cone of inner_cone_degrees {inner} and outer_cone_degrees {outer}: 0 <= inner < outer <= 90"
        ));
    }
    Ok(())
}

/// Each key against its rule, then the kind's relations between keys.
fn check_shape(shape: &ShapeDesc) -> Checked {
    match shape {
        ShapeDesc::Procedural(p) => {
            for param in p.kind.params {
                if let Some(value) = p.values.value(param.name) {
                    param.check(value)?;
                }
            }
            (p.kind.check)(&p.values)
        }
        ShapeDesc::Own(own) => match &own.resolved {
            Some((shape, values)) => shape.primitives(values).map(|_| ()),
            None => Err(format!("kind {:?} is no kind of twinray's or of the sets'", own.kind)),
        },
        ShapeDesc::Mesh(m) => match (&m.builtin, &m.file) {
            (Some(_), None) | (None, Some(_)) => Ok(()),
            _ => Err("a mesh needs exactly one of builtin and file".into()),
        },
        ShapeDesc::Gltf(_) => Ok(()),
    }
}

fn check_object(scene: &SceneFile, object: &ObjectDesc) -> Checked {
    if !scene.shapes.contains_key(&object.shape) {
        return Err(format!("unknown shape {:?} (shapes: {})", object.shape, names(scene.shapes.keys())));
    }
    // An object of a glTF model takes the model's materials unless it names one for all.
    let model = matches!(scene.shapes.get(&object.shape), Some(ShapeDesc::Gltf(_)));
    let takes_the_models = model && object.material.is_empty();
    if !takes_the_models && !scene.materials.contains_key(&object.material) {
        return Err(format!("unknown material {:?} (materials: {})", object.material, names(scene.materials.keys())));
    }
    check_placement(object)
}

/// An object's translation, rotation and scale: what an animation may change.
pub(super) fn check_placement(object: &ObjectDesc) -> Checked {
    finite("translate", &object.translate)?;
    finite("rotate", &object.rotate)?;
    let scale = object.scale.axes();
    finite("scale", &scale)?;
    if scale.contains(&0.0) {
        return Err(format!("scale must not be zero on any axis (got {scale:?})"));
    }
    let (low, high) = SCALE_RANGE;
    if let Some(s) = scale.iter().find(|s| !(low..=high).contains(&s.abs())) {
        return Err(format!(
            "scale must be in [{low:e}, {high:e}] in magnitude on every axis (got {s:e}): beyond, the object's transform overflows or degenerates in f32"
        ));
    }
    object.matrix.as_ref().map_or(Ok(()), check_matrix)
}

/// An object's `matrix`: finite, affine (last row 0 0 0 1), and each axis it maps scaled
/// within `SCALE_RANGE`, with a volume that f32 resolves (not flattened to a plane).
fn check_matrix(m: &[f32; 16]) -> Checked {
    finite("matrix", m)?;
    let m = glam::Mat4::from_cols_array(m);
    if m.row(3) != glam::Vec4::W {
        return Err(format!("matrix must be affine: its last row must be 0 0 0 1 (got {})", m.row(3)));
    }
    let (low, high) = SCALE_RANGE;
    let axes = [m.x_axis, m.y_axis, m.z_axis].map(|a| a.truncate().length());
    if let Some(s) = axes.iter().find(|s| !(low..=high).contains(*s)) {
        return Err(format!("matrix scales an axis by {s:e}, outside [{low:e}, {high:e}]"));
    }
    let volume = m.determinant().abs() / axes.iter().product::<f32>();
    if volume < 1e-6 {
        return Err(format!("matrix flattens space (its axes span a volume {volume:e} of their lengths' product)"));
    }
    Ok(())
}

fn check_grid(scene: &SceneFile, grid: &GridDesc) -> Checked {
    if grid.count.contains(&0) {
        return Err(format!("count must be at least 1 on every axis (got {:?})", grid.count));
    }
    if grid.materials.is_empty() {
        return Err("materials must name at least one material".into());
    }
    finite("spacing", &grid.spacing)?;
    finite("origin", &grid.origin)?;
    finite("rotate_step", &grid.rotate_step)?;
    let last: Vec<f32> = (0..3).map(|i| grid.origin[i] + grid.spacing[i] * (grid.count[i] - 1) as f32).collect();
    finite("origin + spacing * (count - 1)", &last)?;
    // Each material and the shape, checked as one object of the grid would be.
    for material in &grid.materials {
        let object = ObjectDesc {
            name: None,
            shape: grid.shape.clone(),
            material: material.clone(),
            translate: grid.origin,
            rotate: [0.0; 3],
            scale: grid.scale,
            matrix: None,
            single_sided: false,
        };
        check_object(scene, &object)?;
    }
    Ok(())
}

fn names<'a>(keys: impl Iterator<Item = &'a String>) -> String {
    let list: Vec<&str> = keys.map(String::as_str).collect();
    if list.is_empty() {
        "none".into()
    } else {
        list.join(", ")
    }
}

fn check_parity(p: &Parity) -> Checked {
    if !(p.max_rmse.is_finite() && p.max_rmse >= 0.0) {
        return Err(format!("parity.max_rmse must be >= 0 (got {})", p.max_rmse));
    }
    for (name, v) in
        [("max_pixels_over_threshold", p.max_pixels_over_threshold), ("max_hit_mismatches", p.max_hit_mismatches)]
    {
        if !(0.0..=1.0).contains(&v) {
            return Err(format!("parity.{name} is a fraction of pixels, in [0, 1] (got {v})"));
        }
    }
    Ok(())
}
