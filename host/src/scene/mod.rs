//! Scenes: loaded from a TOML file or by built-in name, checked before any GPU work, and
//! turned into GPU data and a pipeline plan.

mod build;
mod check;
pub mod file;

use crate::error::{Error, Result};
pub use build::{object_transform, Aabb, HitGroup, InstanceDesc, PipelinePlan, SceneData};
pub use check::{MAX_OBJECTS, MAX_PRIMITIVES, MAX_SAMPLES_PER_SIDE};
pub use file::{Parity, SceneFile};
use std::path::Path;
use twinray_shared::layout::FrameUniform;

/// Scenes shipped inside the binary, by name.
pub const BUILTIN: [(&str, &str); 1] = [("spheres", include_str!("../../../scenes/spheres.toml"))];
pub const DEFAULT_SCENE: &str = "spheres";

/// A checked scene, ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    pub file: SceneFile,
    /// Where it came from: a path, or `builtin:NAME`.
    pub source: String,
}

impl Scene {
    /// Loads `arg` as a file path, or else as a built-in scene name; `None` is the default scene.
    pub fn load(arg: Option<&str>) -> Result<Scene> {
        let arg = arg.unwrap_or(DEFAULT_SCENE);
        let path = Path::new(arg);
        if path.exists() {
            let text = std::fs::read_to_string(path)
                .map_err(|e| Error::Scene { path: arg.into(), message: format!("cannot read: {e}") })?;
            return Scene::parse(&text, arg);
        }
        if let Some((name, text)) = BUILTIN.iter().find(|(name, _)| *name == arg) {
            return Scene::parse(text, &format!("builtin:{name}"));
        }
        let names: Vec<_> = BUILTIN.iter().map(|(n, _)| *n).collect();
        Err(Error::Scene {
            path: arg.into(),
            message: format!("no such file, and no built-in scene of that name (built-ins: {})", names.join(", ")),
        })
    }

    /// Parses and checks scene text; `source` names it in errors.
    pub fn parse(text: &str, source: &str) -> Result<Scene> {
        let file: SceneFile = toml::from_str(text)
            .map_err(|e| Error::Scene { path: source.into(), message: e.to_string().trim_end().replace('\n', " ") })?;
        check::check(&file).map_err(|message| Error::Scene { path: source.into(), message })?;
        Ok(Scene { file, source: source.into() })
    }

    pub fn name(&self) -> &str {
        &self.file.name
    }

    /// Buffers, acceleration structure contents and pipeline plan of this scene.
    pub fn build(&self) -> SceneData {
        build::build(&self.file)
    }

    /// Camera and frame constants for an image of `width` x `height`.
    pub fn frame_uniform(&self, width: u32, height: u32) -> FrameUniform {
        build::frame_uniform(&self.file, width, height)
    }
}
