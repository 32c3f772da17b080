//! Folders of stage sources taken as sets: a Rust shader crate or a folder of GLSL twins is
//! built (`twinray_build::folder`: rust-gpu or glslang, up to date when nothing changed) when a
//! set names it, and the set reads the modules it built. Each folder is built once a process.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Duration;
use twinray_build::folder::{self, Options};

/// Folders built by this process, by their canonical path, and the options of every build.
static BUILT: Mutex<BTreeMap<PathBuf, PathBuf>> = Mutex::new(BTreeMap::new());
static TIMEOUT: Mutex<Option<Duration>> = Mutex::new(None);

/// The deadline of every build this process starts [default: `folder::Options`'].
pub fn set_build_timeout(timeout: Duration) {
    *TIMEOUT.lock().unwrap_or_else(|e| e.into_inner()) = Some(timeout);
}

/// Whether `dir` holds stage sources rather than built modules.
pub fn holds_sources(dir: &Path) -> bool {
    folder::sources_in(dir).is_some()
}

/// The folder of modules built from the sources in `dir`: built now, found up to date, or
/// built earlier by this process. A build says so on standard error, with its time.
pub fn built(dir: &Path) -> Result<PathBuf, String> {
    let key = dir.canonicalize().map_err(|e| format!("{}: {e}", dir.display()))?;
    if let Some(set) = BUILT.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return Ok(set.clone());
    }
    let mut options = Options::default();
    if let Some(timeout) = *TIMEOUT.lock().unwrap_or_else(|e| e.into_inner()) {
        options.timeout = timeout;
    }
    let _doing = crate::util::activity::doing(format!("building the stages of {}", dir.display()));
    let built = folder::build(dir, options).map_err(|e| format!("{e:#}"))?;
    if built.rebuilt {
        eprintln!("build: {}", summary(dir, &built));
    }
    BUILT.lock().unwrap_or_else(|e| e.into_inner()).insert(key, built.set.clone());
    Ok(built.set)
}

/// A build in words: the folder, whether it was built, its modules, contract and time.
pub fn summary(dir: &Path, built: &folder::Built) -> String {
    let what = if built.rebuilt { "built" } else { "up to date" };
    let (modules, contract, seconds) = (built.modules, &built.contract, built.seconds);
    format!("{}: {what}, {modules} modules (twinray-shared {contract}), {seconds:.1} s", dir.display())
}
