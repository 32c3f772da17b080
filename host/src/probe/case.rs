//! Probe case files (TOML, documented in docs/probe-format.md): a scene, by name or path or
//! inline, and rays given explicitly or by generators. Seeded and reproducible.

use super::generate::{far, generate, ray, Generator};
use crate::error::{Error, Result};
use crate::reference::scene::SceneReference;
use crate::scene::shape::Formula;
use crate::scene::{MeshFiles, Scene};
use crate::sets::own::CrateKinds;
use crate::util::input::{read_text, MAX_TEXT_BYTES};
use serde::Deserialize;
use std::path::Path;
use twinray_shared::layout::ProbeRay;

/// A probe case file, as written (`docs/probe-format.md`).
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
/// decided rays, and a bound on the p99 relative t error, written as the error itself, in
/// units of its condition (error / (κ u), `reference::condition`), or both.
#[derive(Clone, Copy, Debug, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Targets {
    pub max_relative_t_p99: Option<f64>,
    pub max_condition_multiple_p99: Option<f64>,
}

/// A `[targets]` table names at least one bound, each positive and finite.
fn check_targets(t: &Targets) -> std::result::Result<(), String> {
    let bounds =
        [("max_relative_t_p99", t.max_relative_t_p99), ("max_condition_multiple_p99", t.max_condition_multiple_p99)];
    if bounds.iter().all(|(_, b)| b.is_none()) {
        return Err("name max_relative_t_p99, max_condition_multiple_p99 or both".into());
    }
    match bounds.iter().find(|(_, b)| b.is_some_and(|b| !(b > 0.0 && b.is_finite()))) {
        Some((name, b)) => Err(format!("{name} must be positive and finite (got {})", b.unwrap_or(0.0))),
        None => Ok(()),
    }
}

/// A scene by built-in name or path (relative to the case file), or written inline.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum SceneRef {
    /// A built-in scene's name, or a path relative to the case file.
    Named(String),
    /// A scene written in the case file (camera, image and parity may be left out).
    Inline(toml::Table),
}

/// One explicit ray.
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

/// What one generator of a case made: the rays it was asked for and made (always the same
/// number: a generator that cannot make them fails), and how many the set traced hit.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Generated {
    pub kind: String,
    pub made: usize,
    /// Filled in by `probe::report::evaluate`.
    pub hit: Option<usize>,
    /// Of those, how many went through the surface the reference hits first (see
    /// `ProbeReport::through`); filled in with `hit`.
    pub through: Option<usize>,
}

/// A loaded case: its scene, rays and the reference for them.
pub struct ProbeCase {
    pub file: ProbeFile,
    /// Per generator, in order: their rays follow the explicit ones in `rays`.
    pub generated: Vec<Generated>,
    pub scene: Scene,
    /// The rays traced: `robust_rays` or `naive_rays`, by the formula in use.
    pub rays: Vec<ProbeRay>,
    pub reference: SceneReference,
    robust_rays: Vec<ProbeRay>,
    naive_rays: Vec<ProbeRay>,
}

/// Tables an inline scene may leave out (a probe needs no camera or image), appended to the
/// case's text where missing, after every line of it, so that errors keep the file's lines.
const INLINE_DEFAULTS: [(&str, &str); 2] = [
    ("image", "[scene.image]\nwidth = 1\nheight = 1\n"),
    (
        "camera",
        "[scene.camera]\neye = [0.0, 0.0, 1.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_degrees = 45.0\n",
    ),
];

/// What Vulkan asks of a ray (finite origin and direction, 0 <= t_min <= t_max, no NaN) and
/// what a ray needs to go anywhere (a direction); the error starts with the field's name.
fn check_ray(r: &RayDesc) -> std::result::Result<(), String> {
    let finite = |v: &[f32]| v.iter().all(|x| x.is_finite());
    if !finite(&r.origin) {
        return Err(format!("origin must be finite (got {:?})", r.origin));
    }
    if !finite(&r.direction) || r.direction == [0.0; 3] {
        return Err(format!("direction must be finite and not zero (got {:?})", r.direction));
    }
    if !(r.t_min >= 0.0 && r.t_min.is_finite()) {
        return Err(format!("t_min must be finite and >= 0 (got {})", r.t_min));
    }
    if !(r.t_max >= r.t_min && r.t_max.is_finite()) {
        return Err(format!("t_max must be finite and >= t_min (got {} < {})", r.t_max, r.t_min));
    }
    Ok(())
}

/// The case's text with the tables its inline scene leaves out appended. A scene written as
/// one inline table (`scene = { ... }`) cannot be extended that way: it is written out again
/// as a table, with the defaults (errors in it then give that text's positions).
fn with_inline_defaults(text: &str, table: &toml::Table) -> std::result::Result<String, String> {
    let missing = INLINE_DEFAULTS.iter().filter(|(key, _)| !table.contains_key(*key));
    let inline_table =
        text.lines().any(|l| l.trim_start().strip_prefix("scene").is_some_and(|r| r.trim_start().starts_with('=')));
    if !inline_table {
        return Ok(
            missing.fold(text.to_string(), |doc, (key, defaults)| doc + &format!("\n# default {key}\n{defaults}"))
        );
    }
    let mut scene = table.clone();
    for (key, defaults) in missing {
        let defaults: toml::Table = toml::from_str(defaults).map_err(|e| e.to_string())?;
        scene.insert(key.to_string(), defaults["scene"][*key].clone());
    }
    let mut document = toml::Table::new();
    document.insert("scene".into(), toml::Value::Table(scene));
    Ok(document.to_string())
}

/// `e` as the case `source`'s error where it names the case's own text (its TOML or its inline
/// scene): a user reads of a probe case, not of a scene.
fn as_case(source: &str, e: Error) -> Error {
    match e {
        Error::Scene { path, message } if path == source => Error::Case { path, message },
        other => other,
    }
}

impl ProbeCase {
    /// Reads a case file: its scene, its rays (given and generated) and the reference.
    pub fn load(path: &Path) -> Result<ProbeCase> {
        ProbeCase::load_with(path, &[])
    }

    /// [`ProbeCase::load`] with the kinds of the crates' `own` shapes as well as twinray's.
    pub fn load_with(path: &Path, own: &[&'static CrateKinds]) -> Result<ProbeCase> {
        let source = path.display().to_string();
        let text = read_text(path, MAX_TEXT_BYTES)
            .map_err(|e| Error::Case { path: source.clone(), message: format!("cannot read: {e}") })?;
        ProbeCase::parse_with(&text, &source, path.parent().map(Path::to_path_buf).unwrap_or_default(), own)
    }

    /// Parses case text; `source` names it in errors, and named scenes and mesh files are
    /// looked up relative to `folder`.
    pub fn parse(text: &str, source: &str, folder: std::path::PathBuf) -> Result<ProbeCase> {
        ProbeCase::parse_with(text, source, folder, &[])
    }

    /// [`ProbeCase::parse`] with the kinds of the crates' `own` shapes as well as twinray's.
    pub fn parse_with(
        text: &str,
        source: &str,
        folder: std::path::PathBuf,
        own: &[&'static CrateKinds],
    ) -> Result<ProbeCase> {
        let case_error = |message: String| Error::Case { path: source.into(), message };
        let text = text.to_string();
        let source = source.to_string();
        let file: ProbeFile =
            toml::from_str(&text).map_err(|e| as_case(&source, crate::scene::toml_error(&source, &text, &e)))?;
        let scene = match &file.scene {
            SceneRef::Named(name) => {
                let relative = folder.join(name);
                let scene = Scene::load_with(
                    Some(if relative.exists() { relative.to_str().unwrap_or(name) } else { name }),
                    own,
                );
                scene.map_err(|e| case_error(format!("scene: {e}")))?
            }
            SceneRef::Inline(table) => {
                let document = with_inline_defaults(&text, table).map_err(case_error)?;
                let mut scene = Scene::parse_embedded(&document, &source, MeshFiles::Folder(folder), own)
                    .map_err(|e| as_case(&source, e))?;
                if !table.contains_key("name") {
                    scene.file.name = "inline".into();
                }
                scene
            }
        };
        let reference = SceneReference::new(&scene).map_err(case_error)?;
        if let Some(t) = file.targets {
            check_targets(&t).map_err(|e| case_error(format!("targets: {e}")))?;
        }
        for (i, r) in file.rays.iter().enumerate() {
            check_ray(r).map_err(|e| case_error(format!("rays[{i}].{e}")))?;
        }
        let explicit: Vec<ProbeRay> =
            file.rays.iter().map(|r| ray(r.origin.into(), r.direction.into(), r.t_min, r.t_max)).collect();
        let (mut robust_rays, mut naive_rays) = (explicit.clone(), explicit);
        let mut generated = Vec::new();
        for (i, generator) in file.generators.iter().enumerate() {
            let rays = generate(generator, &reference).map_err(|e| case_error(format!("generators[{i}]: {e}")))?;
            robust_rays.extend(rays.iter().map(|pair| pair.0));
            naive_rays.extend(rays.iter().map(|pair| pair.1));
            generated.push(Generated { kind: generator.kind().into(), made: rays.len(), hit: None, through: None });
        }
        if robust_rays.is_empty() {
            return Err(case_error("no rays: give [[rays]] or [[generators]]".into()));
        }
        let rays = robust_rays.clone();
        Ok(ProbeCase { file, generated, scene, rays, reference, robust_rays, naive_rays })
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

    /// Whether the naive formula changes anything here: a shape with a naive variant, or
    /// surface rays (whose naive form is the fixed-epsilon shadow ray).
    pub fn has_naive(&self) -> bool {
        self.scene.file.shapes.values().any(|s| s.has_naive())
            || self.file.generators.iter().any(|g| matches!(g, Generator::Surface { .. }))
    }

    /// Surface rays follow too: naive ones start on the surface with a fixed epsilon.
    pub fn set_formula(&mut self, formula: Formula) {
        for shape in self.scene.file.shapes.values_mut() {
            shape.set_formula(formula);
        }
        self.rays = match formula {
            Formula::Robust => self.robust_rays.clone(),
            Formula::Naive => self.naive_rays.clone(),
        };
    }
}
