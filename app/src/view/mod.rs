//! `twinray view`: a page in the browser that shows two sets' renders of a scene side by side,
//! as a wipe, flipped, and as their difference, live: a save to a shader source, a set's
//! folder or the scene file rebuilds what changed and renders again, and a click on a pixel
//! explains it. Layers, from the bottom: `sets` (what a set's spec builds and reads), `jobs`
//! (GPU work in child processes), `state` (what the page shows), `live` (the loop), `watch`
//! (saves), `server` (HTTP).

pub mod jobs;
pub mod live;
pub mod server;
pub mod sets;
pub mod state;
pub mod watch;

use jobs::{Jobs, Shot};
use live::Live;
use state::{PageState, SceneInfo, Store, TimingInfo};
use std::net::{IpAddr, SocketAddr};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use twinray_compile::sources;
use twinray_host::error::{Error, Result};
use twinray_host::scene::Scene;
use twinray_host::sets::own::CrateKinds;

/// What `twinray view` was asked for.
pub struct ViewConfig {
    pub scene: Option<String>,
    /// The kinds of the sets' crates, which the scene may name beside twinray's.
    pub own: Vec<&'static CrateKinds>,
    pub sets: [String; 2],
    /// A checkout whose sources rebuild the built-in sets (`None`: their embedded modules).
    pub sources: Option<PathBuf>,
    pub bind: IpAddr,
    /// 0: any free port.
    pub port: u16,
    /// Image size [default: the scene's].
    pub size: (Option<u32>, Option<u32>),
    pub preview_width: u32,
    /// The `twinray` binary that does the GPU work, and the global flags it gets.
    pub twinray: PathBuf,
    pub global: Vec<String>,
    /// Where fresh sets are built, and compare's images land before they are read.
    pub work_dir: PathBuf,
}

/// Serves the page until Ctrl-C; `ready` gets the address once it listens.
pub fn serve(config: ViewConfig, ready: impl FnOnce(SocketAddr)) -> Result<()> {
    let scene = Scene::load_with(config.scene.as_deref(), &config.own)?;
    let info = SceneInfo::of(&scene, config.size);
    twinray_host::scene::check_size(info.width, info.height).map_err(Error::Input)?;
    let runtime = tokio::runtime::Runtime::new().map_err(|e| Error::Input(format!("starting the server: {e}")))?;
    runtime.block_on(run(config, info, ready))
}

async fn run(config: ViewConfig, info: SceneInfo, ready: impl FnOnce(SocketAddr)) -> Result<()> {
    let scene_file =
        config.scene.as_ref().map(PathBuf::from).filter(|p| p.is_file()).and_then(|p| p.canonicalize().ok());
    let live = Arc::new(Live {
        scene: config.scene.clone(),
        own: config.own.clone(),
        scene_file: scene_file.clone(),
        sets: config.sets.clone(),
        sources: config.sources.clone(),
        built_dir: config.work_dir.join("sets"),
        scratch: config.work_dir.join("renders"),
        size: config.size,
        preview_width: config.preview_width,
        jobs: Jobs {
            twinray: config.twinray.clone(),
            global: config.global.clone(),
            backstop: Duration::from_secs(600),
            gpu: tokio::sync::Mutex::new(()),
        },
        store: Store::new(PageState {
            wanted: Shot { width: info.width, height: info.height, frame: 0, eye: None, look_at: None },
            scene: info,
            sets: config.sets.clone(),
            live: Vec::new(),
            status: "starting".into(),
            render: None,
            problem: None,
            timing: TimingInfo::default(),
        }),
        built: Mutex::new(Default::default()),
    });
    let (dirs, files, words) = watched(&live, scene_file);
    live.store.update(|s| s.live = words);
    let (triggers, received) = tokio::sync::mpsc::unbounded_channel();
    let _watcher = watch::watch(dirs, files, triggers.clone())
        .map_err(|e| Error::Input(format!("watching the view's files: {e}")))?;
    let app = Arc::new(server::App { live: live.clone(), triggers, loopback_only: config.bind.is_loopback() });
    let listener = tokio::net::TcpListener::bind(SocketAddr::new(config.bind, config.port))
        .await
        .map_err(|e| Error::Input(format!("listening on {}:{}: {e}", config.bind, config.port)))?;
    let address = listener.local_addr().map_err(|e| Error::Input(format!("the server's address: {e}")))?;
    ready(address);
    let looping = live.clone();
    tokio::spawn(async move { looping.run(received).await });
    // Ctrl-C ends the server (open event streams and all) so `twinray view` can remove its
    // built sets; the render in flight, a child process, is killed with it.
    tokio::select! {
        served = axum::serve(listener, server::router(app)) => {
            served.map_err(|e| Error::Input(format!("serving: {e}")))
        }
        _ = tokio::signal::ctrl_c() => Ok(()),
    }
}

/// The folders and files a save to which re-renders, and what that is in words.
fn watched(live: &Live, scene_file: Option<PathBuf>) -> (Vec<PathBuf>, Vec<PathBuf>, Vec<String>) {
    let (mut dirs, mut files, mut words) = (Vec::new(), Vec::new(), Vec::new());
    let buildable = live.buildable();
    for language in buildable.iter().copied() {
        let root = live.sources.clone().unwrap_or_default();
        dirs.extend(sources(language).iter().map(|d| root.join(d)));
        words.push(format!("{}: rebuilt from {} on save", language.name(), root.display()));
    }
    for spec in &live.sets {
        for language in sets::languages(spec).into_iter().filter(|l| !buildable.contains(l)) {
            let word = format!("{}: the built-in modules (no sources given or found: not rebuilt)", language.name());
            if !words.contains(&word) {
                words.push(word);
            }
        }
        for path in sets::watched(spec) {
            let Ok(path) = path.canonicalize() else { continue };
            words.push(format!("{} (modules from disk)", path.display()));
            if path.is_dir() {
                dirs.push(path);
            } else {
                files.push(path);
            }
        }
    }
    if let Some(file) = scene_file {
        words.push(format!("{} (the scene)", file.display()));
        files.push(file);
    }
    (dirs, files, words)
}
