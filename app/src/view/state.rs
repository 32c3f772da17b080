//! What the page shows, in one JSON value pushed to it whenever it changes (server-sent
//! events), and the images of the last few renders, served from memory.

use super::jobs::{Compared, Shot};
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;
use std::sync::Mutex;
use tokio::sync::watch;
use twinray_host::scene::Scene;

/// Renders kept for the page: the one shown, the ones a click may still name, and a spare.
const KEPT_RENDERS: usize = 4;

/// The scene as the page needs it: what it may ask for (frames, camera).
#[derive(Clone, Debug, Serialize)]
pub struct SceneInfo {
    pub name: String,
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub up: [f32; 3],
}

impl SceneInfo {
    /// `scene` at the size `view` was given (`None`: the scene's).
    pub fn of(scene: &Scene, (width, height): (Option<u32>, Option<u32>)) -> SceneInfo {
        let (image, camera) = (scene.file.image, scene.file.camera);
        SceneInfo {
            name: scene.name().to_string(),
            frames: scene.frame_count(),
            width: width.unwrap_or(image.width),
            height: height.unwrap_or(image.height),
            eye: camera.eye,
            target: camera.target,
            up: camera.up,
        }
    }
}

/// A finished render: which image, and compare's report on it.
#[derive(Clone, Debug, Serialize)]
pub struct RenderInfo {
    /// Counts renders from 1; image URLs and explain requests name it.
    pub id: u64,
    pub shot: Shot,
    /// At the preview size, with a full-size render to follow.
    pub preview: bool,
    pub report: Value,
    /// The files whose save led to it, and milliseconds from the last save to the render
    /// being ready (building and rendering), when a save led to it.
    pub changed: Vec<String>,
    pub save_to_ready_ms: Option<f64>,
    pub build_ms: Option<f64>,
    pub render_ms: f64,
}

/// Something that went wrong, shown until a render succeeds.
#[derive(Clone, Debug, Serialize)]
pub struct Problem {
    /// "build", "render", "scene" or "explain".
    pub what: String,
    pub text: String,
}

/// The GPU-time ratio with its interval, and the null control's, when asked for.
#[derive(Clone, Debug, Default, Serialize)]
pub struct TimingInfo {
    pub running: bool,
    pub render: Option<u64>,
    pub ab: Option<Value>,
    pub null: Option<Value>,
    pub error: Option<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct PageState {
    pub scene: SceneInfo,
    /// Sets A and B as given.
    pub sets: [String; 2],
    /// What is watched, in words.
    pub live: Vec<String>,
    /// "idle", or what the server is doing ("building glsl", "rendering preview").
    pub status: String,
    pub render: Option<RenderInfo>,
    pub problem: Option<Problem>,
    pub timing: TimingInfo,
    /// The view the page asked for last (frame and camera).
    pub wanted: Shot,
}

/// The state, its watchers (each page's event stream), and the kept images.
pub struct Store {
    state: watch::Sender<PageState>,
    images: Mutex<BTreeMap<u64, (Shot, Compared)>>,
}

impl Store {
    pub fn new(state: PageState) -> Store {
        Store { state: watch::Sender::new(state), images: Mutex::new(BTreeMap::new()) }
    }

    pub fn get(&self) -> PageState {
        self.state.borrow().clone()
    }

    pub fn subscribe(&self) -> watch::Receiver<PageState> {
        self.state.subscribe()
    }

    /// Changes the state and tells every page.
    pub fn update(&self, change: impl FnOnce(&mut PageState)) {
        self.state.send_modify(change);
    }

    pub fn status(&self, status: impl Into<String>) {
        let status = status.into();
        self.update(|s| s.status = status);
    }

    /// Keeps render `id`'s images (dropping the oldest past `KEPT_RENDERS`).
    pub fn keep(&self, id: u64, shot: Shot, compared: Compared) {
        let mut images = self.images.lock().unwrap_or_else(|e| e.into_inner());
        images.insert(id, (shot, compared));
        while images.len() > KEPT_RENDERS {
            images.pop_first();
        }
    }

    /// Image `name` (a.png, b.png or diff.png) of render `id`, if kept.
    pub fn image(&self, id: u64, name: &str) -> Option<Vec<u8>> {
        let images = self.images.lock().unwrap_or_else(|e| e.into_inner());
        let (_, c) = images.get(&id)?;
        match name {
            "a.png" => Some(c.a.clone()),
            "b.png" => Some(c.b.clone()),
            "diff.png" => Some(c.diff.clone()),
            _ => None,
        }
    }

    /// Which image render `id` was, if kept.
    pub fn shot(&self, id: u64) -> Option<Shot> {
        let images = self.images.lock().unwrap_or_else(|e| e.into_inner());
        images.get(&id).map(|(shot, _)| shot.clone())
    }
}
