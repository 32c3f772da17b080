//! Probe case files (TOML, documented in docs/probe-format.md): a scene, by name or path or
//! inline, and rays given explicitly or by generators. Seeded and reproducible.

use crate::error::{Error, Result};
use crate::probe::ProbeRay;
use crate::reference_scene::{SceneReference, SceneVerdict};
use crate::scene::{MeshFiles, Scene};
use glam::{DVec3, Vec3};
use serde::Deserialize;
use std::path::Path;
use twinray_shared::offset::offset_ray;
use twinray_shared::random::random;

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeFile {
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub scene: SceneRef,
    #[serde(default)]
    pub rays: Vec<RayDesc>,
    #[serde(default)]
    pub generators: Vec<Generator>,
    /// What the robust formulas must achieve on this case (the hard-case suite checks it).
    pub targets: Option<Targets>,
}

/// Targets of a case for the robust formulas: no false hit, false miss or wrong object among
/// decided rays, and a bound on the p99 relative t error.
#[derive(Clone, Copy, Debug, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Targets {
    pub max_relative_t_p99: f64,
}

/// A scene by built-in name or path (relative to the case file), or written inline.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum SceneRef {
    Named(String),
    Inline(toml::Table),
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RayDesc {
    pub origin: [f32; 3],
    pub direction: [f32; 3],
    #[serde(default)]
    pub t_min: f32,
    #[serde(default = "far")]
    pub t_max: f32,
}

fn far() -> f32 {
    1.0e30
}

fn band() -> f32 {
    1.2
}

#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Generator {
    /// `count` x `count` parallel rays from `from` towards the object's centre, across a
    /// square `band` times its bounding radius wide: through its silhouette.
    Silhouette {
        object: usize,
        from: [f32; 3],
        count: u32,
        #[serde(default = "band")]
        band: f32,
    },
    /// `count` secondary rays from points on the object's surface (found by the reference),
    /// offset as shadow rays are (Ray Tracing Gems ch. 6), in random directions of the outer
    /// hemisphere, with t_min 0.
    Surface {
        object: usize,
        count: u32,
        #[serde(default)]
        seed: u32,
    },
}

/// A loaded case: its scene, rays and the reference for them.
pub struct ProbeCase {
    pub file: ProbeFile,
    pub scene: Scene,
    /// The rays traced: `robust_rays` or `naive_rays`, by the formula in use.
    pub rays: Vec<ProbeRay>,
    pub reference: SceneReference,
    robust_rays: Vec<ProbeRay>,
    naive_rays: Vec<ProbeRay>,
}

/// t_min of the textbook shadow ray: a fixed epsilon, from an origin on the surface.
pub const NAIVE_SHADOW_EPSILON: f32 = 1.0e-3;

/// Defaults that an inline scene may leave out: a probe needs no camera, image or parity.
const INLINE_DEFAULTS: &str = r#"
name = "inline"
[image]
width = 1
height = 1
[camera]
eye = [0.0, 0.0, 1.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 45.0
[parity]
max_rmse = 0.0
pixel_threshold = 0
max_pixels_over_threshold = 0.0
max_hit_mismatches = 0.0
"#;

impl ProbeCase {
    pub fn load(path: &Path) -> Result<ProbeCase> {
        let source = path.display().to_string();
        let case_error = |message: String| Error::Scene { path: source.clone(), message };
        let text = std::fs::read_to_string(path).map_err(|e| case_error(format!("cannot read: {e}")))?;
        let file: ProbeFile =
            toml::from_str(&text).map_err(|e| case_error(e.to_string().trim_end().replace('\n', " ")))?;
        let folder = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let scene = match &file.scene {
            SceneRef::Named(name) => {
                let relative = folder.join(name);
                Scene::load(Some(if relative.exists() { relative.to_str().unwrap_or(name) } else { name }))?
            }
            SceneRef::Inline(table) => {
                let mut full: toml::Table = toml::from_str(INLINE_DEFAULTS).map_err(|e| case_error(e.to_string()))?;
                full.extend(table.clone());
                Scene::parse(&full.to_string(), &format!("{source} [scene]"), MeshFiles::Folder(folder))?
            }
        };
        let reference = SceneReference::new(&scene);
        let explicit: Vec<ProbeRay> =
            file.rays.iter().map(|r| ray(r.origin.into(), r.direction.into(), r.t_min, r.t_max)).collect();
        let (mut robust_rays, mut naive_rays) = (explicit.clone(), explicit);
        for (i, generator) in file.generators.iter().enumerate() {
            let generated = generate(generator, &reference).map_err(|e| case_error(format!("generators[{i}]: {e}")))?;
            robust_rays.extend(generated.iter().map(|pair| pair.0));
            naive_rays.extend(generated.iter().map(|pair| pair.1));
        }
        if robust_rays.is_empty() {
            return Err(case_error("no rays: give [[rays]] or [[generators]]".into()));
        }
        let rays = robust_rays.clone();
        Ok(ProbeCase { file, scene, rays, reference, robust_rays, naive_rays })
    }
}

impl ProbeCase {
    /// Uses `formula` for every shape that has both (the rays and the reference stay the same).
    /// The rays whose true answers the traced rays are judged by: the robust rays. A naive
    /// shadow ray starts on the surface, so its rounded origin may lie inside the shape; what
    /// it should report is whether the point it leaves sees past its own surface.
    pub fn reference_rays(&self) -> &[ProbeRay] {
        &self.robust_rays
    }

    /// Surface rays follow too: naive ones start on the surface with a fixed epsilon.
    pub fn set_formula(&mut self, formula: crate::scene::file::Formula) {
        for shape in self.scene.file.shapes.values_mut() {
            shape.set_formula(formula);
        }
        self.rays = match formula {
            crate::scene::file::Formula::Robust => self.robust_rays.clone(),
            crate::scene::file::Formula::Naive => self.naive_rays.clone(),
        };
    }
}

fn ray(origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> ProbeRay {
    ProbeRay { origin: origin.extend(t_min), direction: direction.extend(t_max) }
}

/// Centre and bounding radius of an object, in world space.
fn bounds(reference: &SceneReference, object: usize) -> std::result::Result<(DVec3, f64), String> {
    let o = reference
        .objects
        .get(object)
        .ok_or_else(|| format!("no object {object} (the scene has {})", reference.objects.len()))?;
    let center = o.object_to_world.transform_point3(DVec3::ZERO);
    let scale = o.object_to_world.transform_vector3(DVec3::ONE).length();
    let radius = o.shapes.iter().map(crate::reference::bounding_radius).fold(0.0, f64::max) * scale;
    Ok((center, radius.max(1e-6)))
}

/// The generated rays, each as (robust, naive): they differ only for surface rays.
fn generate(
    generator: &Generator,
    reference: &SceneReference,
) -> std::result::Result<Vec<(ProbeRay, ProbeRay)>, String> {
    match *generator {
        Generator::Silhouette { object, from, count, band } => {
            let (center, radius) = bounds(reference, object)?;
            let from = Vec3::from(from).as_dvec3();
            let forward = (center - from).normalize();
            let right = forward.any_orthonormal_vector();
            let up = forward.cross(right);
            let half = radius * f64::from(band);
            let n = count.max(1);
            Ok((0..n * n)
                .map(|k| {
                    let (i, j) = (k % n, k / n);
                    let u = -half + 2.0 * half * (f64::from(i) + 0.5) / f64::from(n);
                    let v = -half + 2.0 * half * (f64::from(j) + 0.5) / f64::from(n);
                    let origin = from + right * u + up * v;
                    let r = ray(origin.as_vec3(), forward.as_vec3(), 0.0, far());
                    (r, r)
                })
                .collect())
        }
        Generator::Surface { object, count, seed } => {
            let (center, radius) = bounds(reference, object)?;
            let mut rays = Vec::new();
            let mut k = 0;
            while rays.len() < count as usize && k < count * 20 {
                let index = k;
                let r = |d: u32| f64::from(random(seed, index, 0, d));
                k += 1;
                let toward = unit(r(0), r(1));
                let start = center + toward * radius * 4.0;
                if let SceneVerdict::Hit { object: hit, t, normal } = reference.trace(start, -toward, 0.0, f64::MAX) {
                    if hit != object {
                        continue;
                    }
                    let point = start - toward * t;
                    let n = normal.as_vec3();
                    let mut dir = unit(r(2), r(3)).as_vec3();
                    if dir.dot(n) < 0.0 {
                        dir = -dir;
                    }
                    let robust = ray(offset_ray(point.as_vec3(), n), dir, 0.0, far());
                    let naive = ray(point.as_vec3(), dir, NAIVE_SHADOW_EPSILON, far());
                    rays.push((robust, naive));
                }
            }
            Ok(rays)
        }
    }
}

/// A unit vector from two numbers in [0, 1), uniform on the sphere.
fn unit(a: f64, b: f64) -> DVec3 {
    let z = 2.0 * a - 1.0;
    let phi = std::f64::consts::TAU * b;
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}
