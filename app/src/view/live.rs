//! The live loop: waits for a save (sources, set folders, the scene file), a new view from the
//! page (frame, camera) or a request for timings; rebuilds only the sets whose sources
//! changed, renders both sets at the preview size and then at full size, and tells the page.
//! A build error, a refused module or a failed render is shown and the last good images stay;
//! the next good save recovers.

use super::jobs::{Compared, Failed, Jobs, Shot, Timing};
use super::sets;
use super::state::{Problem, RenderInfo, SceneInfo, Store, TimingInfo};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Instant, SystemTime};
use tokio::sync::mpsc::UnboundedReceiver;
use twinray_compile::{build_set, has_sources, sets_for, Output, GENERATORS};
use twinray_host::scene::Scene;
use twinray_host::sets::own::CrateKinds;
use twinray_shared::catalog::Language;

/// How long a save's events settle before the turn they start.
const SETTLE: std::time::Duration = std::time::Duration::from_millis(100);

/// What the loop is asked to do.
#[derive(Debug)]
pub enum Trigger {
    /// These files (absolute paths) were saved, added or removed.
    Saved(Vec<PathBuf>),
    /// The page wants this frame and camera.
    View(Shot),
    /// The page wants the GPU-time ratio with its interval, and the null control's.
    Timing,
}

/// Everything a turn of the loop has to do, gathered from the triggers waiting.
#[derive(Default)]
struct Work {
    saved: Vec<PathBuf>,
    rebuild: Vec<Language>,
    view: bool,
    timing: bool,
}

impl Work {
    fn add(&mut self, trigger: Trigger, store: &Store) {
        match trigger {
            Trigger::Saved(paths) => self.saved.extend(paths),
            Trigger::View(shot) => {
                store.update(|s| s.wanted = shot);
                self.view = true;
            }
            Trigger::Timing => self.timing = true,
        }
    }

    fn is_empty(&self) -> bool {
        self.saved.is_empty() && self.rebuild.is_empty() && !self.view && !self.timing
    }
}

pub struct Live {
    /// The scene as given (a file or a built-in name; `None`: the default scene).
    pub scene: Option<String>,
    /// The kinds of the sets' crates, as first built.
    pub own: Vec<&'static CrateKinds>,
    /// The scene's file, when it is one: a save to it re-renders.
    pub scene_file: Option<PathBuf>,
    pub sets: [String; 2],
    /// A checkout whose shader sources rebuild the built-in sets the specs name.
    pub sources: Option<PathBuf>,
    /// Where fresh sets are built (one folder per language).
    pub built_dir: PathBuf,
    /// Where compare writes its images before they are read into memory.
    pub scratch: PathBuf,
    /// The image size `view` was given (`None`: the scene's).
    pub size: (Option<u32>, Option<u32>),
    pub preview_width: u32,
    pub jobs: Jobs,
    pub store: Store,
    /// The built-in sets rebuilt from sources so far, by language.
    pub built: Mutex<sets::Built>,
}

impl Live {
    /// The built-in sets of the specs that `sources` can rebuild.
    pub fn buildable(&self) -> Vec<Language> {
        let Some(root) = &self.sources else { return Vec::new() };
        let named: Vec<Language> = self.sets.iter().flat_map(|s| sets::languages(s)).collect();
        Language::ALL.into_iter().filter(|l| named.contains(l) && has_sources(root, *l)).collect()
    }

    /// Specs A and B with the built-in sets rebuilt so far replaced by their folders.
    pub fn specs(&self) -> (String, String) {
        let built = self.built.lock().unwrap_or_else(|e| e.into_inner()).clone();
        (sets::rewrite(&self.sets[0], &built), sets::rewrite(&self.sets[1], &built))
    }

    /// Runs until the server ends: builds what has sources, renders, then follows triggers.
    pub async fn run(&self, mut triggers: UnboundedReceiver<Trigger>) {
        let mut work = Work { rebuild: self.buildable(), view: true, ..Work::default() };
        loop {
            if work.is_empty() {
                match triggers.recv().await {
                    Some(t) => work.add(t, &self.store),
                    None => return,
                }
            }
            if !work.saved.is_empty() {
                // An editor's save is several events (write, rename, close): one turn for all.
                tokio::time::sleep(SETTLE).await;
            }
            while let Ok(t) = triggers.try_recv() {
                work.add(t, &self.store);
            }
            let turn = std::mem::take(&mut work);
            self.turn(turn, &mut triggers, &mut work).await;
            self.store.status("idle");
        }
    }

    /// One turn: rebuild, render the preview, then (if nothing newer waits) the full size.
    async fn turn(&self, mut turn: Work, triggers: &mut UnboundedReceiver<Trigger>, next: &mut Work) {
        let saved_at = last_save(&turn.saved);
        let changed: Vec<String> = turn.saved.iter().map(|p| p.display().to_string()).collect();
        if !turn.saved.is_empty() {
            println!("view: changed {}", changed.join(", "));
        }
        if self.scene_file.as_ref().is_some_and(|f| turn.saved.contains(f)) {
            if let Err(text) = self.reload_scene() {
                return self.problem("scene", text);
            }
        }
        turn.rebuild.extend(self.rebuilt_by(&turn.saved));
        let build_start = Instant::now();
        for language in Language::ALL.into_iter().filter(|l| turn.rebuild.contains(l)) {
            if let Err(text) = self.build(language).await {
                return self.problem("build", text);
            }
        }
        let build_ms = (!turn.rebuild.is_empty()).then(|| build_start.elapsed().as_secs_f64() * 1e3);
        if turn.saved.is_empty() && turn.rebuild.is_empty() && !turn.view {
            return self.timing().await;
        }
        let full = self.store.get().wanted;
        let preview = self.preview_of(&full);
        let mut shots = vec![(preview.clone(), preview != full)];
        if preview != full {
            shots.push((full, false));
        }
        for (shot, is_preview) in shots {
            let save = saved_at.map(|t| (t, changed.clone(), build_ms));
            if !self.render(shot, is_preview, save).await {
                return;
            }
            while let Ok(t) = triggers.try_recv() {
                next.add(t, &self.store);
            }
            if !next.saved.is_empty() || next.view {
                // Something newer waits: its render comes before this one's refinement.
                next.timing |= turn.timing;
                return;
            }
        }
        if turn.timing || std::mem::take(&mut next.timing) {
            self.timing().await;
        }
    }

    /// The built-in sets the saved files rebuild.
    fn rebuilt_by(&self, saved: &[PathBuf]) -> Vec<Language> {
        let Some(root) = &self.sources else { return Vec::new() };
        let relative: Vec<&Path> = saved.iter().filter_map(|p| p.strip_prefix(root).ok()).collect();
        if relative.iter().any(|p| GENERATORS.iter().any(|g| p.ends_with(g))) {
            println!(
                "view: a layout, binding, catalog or registry file changed: run `cargo xtask shaders` and restart"
            );
        }
        let buildable = self.buildable();
        sets_for(relative.iter().copied()).into_iter().filter(|l| buildable.contains(l)).collect()
    }

    /// Builds `language`'s set beside its folder and swaps it in only when it built, so a
    /// broken save never leaves a half-built set for a click to explain.
    async fn build(&self, language: Language) -> Result<(), String> {
        let Some(root) = self.sources.clone() else { return Ok(()) };
        self.store.status(format!("building {}", language.name()));
        let dir = self.built_dir.join(language.name());
        let fresh = self.built_dir.join(format!("{}.building", language.name()));
        let start = Instant::now();
        let (to, done) = (fresh.clone(), dir.clone());
        let built = tokio::task::spawn_blocking(move || {
            build_set(&root, language, &to, Output::OnFailure)?;
            if done.exists() {
                std::fs::remove_dir_all(&done)?;
            }
            std::fs::rename(&to, &done)?;
            anyhow::Ok(())
        })
        .await;
        match built {
            Ok(Ok(())) => {
                println!("view: built the {} set in {:.1} s", language.name(), start.elapsed().as_secs_f64());
                self.built.lock().unwrap_or_else(|e| e.into_inner()).insert(language.name(), dir);
                Ok(())
            }
            Ok(Err(e)) => Err(format!("the {} set does not build: {e:#}", language.name())),
            Err(e) => Err(format!("building the {} set: {e}", language.name())),
        }
    }

    /// Renders `shot` with both sets; false when it failed (the problem is shown).
    async fn render(&self, shot: Shot, preview: bool, save: Option<(SystemTime, Vec<String>, Option<f64>)>) -> bool {
        let id = self.store.get().render.map_or(1, |r| r.id + 1);
        self.store.status(if preview { "rendering preview" } else { "rendering" });
        let start = Instant::now();
        let (a, b) = self.specs();
        let scratch = self.scratch.join(format!("render-{id}"));
        let scene = self.scene.as_deref();
        match self.jobs.compare(scene, (&a, &b), &shot, Timing::Once, &scratch).await {
            Err(Failed(text)) => {
                self.problem("render", text);
                false
            }
            Ok(compared) => {
                self.show(id, shot, preview, compared, start, save);
                true
            }
        }
    }

    fn show(
        &self,
        id: u64,
        shot: Shot,
        preview: bool,
        compared: Compared,
        start: Instant,
        save: Option<(SystemTime, Vec<String>, Option<f64>)>,
    ) {
        let report = compared.report.clone();
        self.store.keep(id, shot.clone(), compared);
        let (saved, changed, build_ms) = save.unwrap_or((SystemTime::now(), Vec::new(), None));
        let since_save = SystemTime::now().duration_since(saved).unwrap_or_default().as_secs_f64() * 1e3;
        let render_ms = start.elapsed().as_secs_f64() * 1e3;
        let info = RenderInfo {
            id,
            shot,
            preview,
            report,
            save_to_ready_ms: (!changed.is_empty()).then_some(since_save),
            changed,
            build_ms,
            render_ms,
        };
        self.store.update(|s| {
            s.render = Some(info);
            s.problem = None;
        });
    }

    /// Times A against B, and A against itself (the null control), at the shown image.
    async fn timing(&self) {
        let Some(render) = self.store.get().render else { return };
        let shot = Shot { width: render.shot.width, height: render.shot.height, ..render.shot.clone() };
        self.store.update(|s| s.timing = TimingInfo { running: true, ..Default::default() });
        self.store.status("timing A against B, then A against itself");
        let (a, b) = self.specs();
        let scene = self.scene.as_deref();
        let scratch = self.scratch.join("timing");
        let ab = self.jobs.compare(scene, (&a, &b), &shot, Timing::Interval, &scratch).await;
        let null = self.jobs.compare(scene, (&a, &a), &shot, Timing::Interval, &scratch).await;
        self.store.update(|s| {
            s.timing.running = false;
            s.timing.render = Some(render.id);
            match (ab, null) {
                (Ok(ab), Ok(null)) => {
                    s.timing.ab = Some(ab.report);
                    s.timing.null = Some(null.report);
                }
                (Err(Failed(e)), _) | (_, Err(Failed(e))) => s.timing.error = Some(e),
            }
        });
    }

    fn problem(&self, what: &str, text: String) {
        println!("view: {what} failed: {}", text.lines().next().unwrap_or_default());
        self.store.update(|s| s.problem = Some(Problem { what: what.into(), text }));
    }

    /// Reads the scene file again; the page's frame and camera start afresh from it.
    fn reload_scene(&self) -> Result<(), String> {
        let scene = Scene::load_with(self.scene.as_deref(), &self.own).map_err(|e| e.to_string())?;
        let info = SceneInfo::of(&scene, self.size);
        self.store.update(|s| {
            s.wanted = Shot { width: info.width, height: info.height, frame: 0, eye: None, look_at: None };
            s.scene = info;
        });
        Ok(())
    }

    /// `full` at the preview width (same aspect), or `full` when it is no larger.
    pub fn preview_of(&self, full: &Shot) -> Shot {
        if full.width <= self.preview_width {
            return full.clone();
        }
        let height = (u64::from(full.height) * u64::from(self.preview_width) / u64::from(full.width)).max(1);
        Shot { width: self.preview_width, height: height as u32, ..full.clone() }
    }
}

/// When the last of `saved` was saved (now for one removed); `None` for no saves.
fn last_save(saved: &[PathBuf]) -> Option<SystemTime> {
    let when = |p: &PathBuf| std::fs::metadata(p).and_then(|m| m.modified()).unwrap_or_else(|_| SystemTime::now());
    saved.iter().map(when).max()
}
