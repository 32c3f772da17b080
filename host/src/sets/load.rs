//! Loading a set: what each path of a `SetSpec` names is found, a folder of stage sources (a
//! Rust shader crate, GLSL twins) is built (`twinray_compile::folder`: rust-gpu or glslang, up
//! to date when nothing changed), and every module read is checked (`super::module::load`).
//! A loader is made once per command, after its options and log are set: it carries the
//! build deadline and remembers the folders it built, so a folder named by several sets is
//! built once.

use super::module::{load, Origin};
use super::own::{CrateKinds, OwnKinds};
use super::set::ShaderSet;
use super::spec::{Key, SetSpec, Source};
use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use twinray_compile::folder::{self, Options};
use twinray_shared::catalog::{Language, ModuleSpec, MODULES};
use twinray_shared::interface::MAX_RECURSION_DEPTH;

/// Builds and reads the sets of one command. Its clones share what it built.
#[derive(Clone, Debug, Default)]
pub struct Loader {
    /// The deadline of every build [default: `folder::Options`'].
    build_timeout: Option<Duration>,
    /// Folders built by this loader, by their canonical path, and the modules' folder of each.
    built: Arc<Mutex<BTreeMap<PathBuf, PathBuf>>>,
}

/// What a path of a set turned out to be.
enum Found {
    Language(Language),
    /// A folder of modules, and whether this loader built it from sources.
    Folder(PathBuf, bool),
    File(PathBuf),
}

impl Loader {
    /// A loader whose builds stop at `build_timeout` (the default deadline when `None`).
    pub fn new(build_timeout: Option<Duration>) -> Loader {
        Loader { build_timeout, built: Arc::default() }
    }

    /// The set `spec` names, every module it reads checked and every folder of sources built.
    pub fn load(&self, spec: &SetSpec) -> Result<ShaderSet> {
        let fail = |message: String| Error::Input(format!("shader set {:?}: {message}", spec.to_string()));
        let mut set = match self.find(&spec.base).map_err(fail)? {
            Found::Language(language) => ShaderSet::uniform(language),
            Found::Folder(dir, built) => {
                // Native code is loaded only from a crate's build: a folder of modules from
                // elsewhere is data, whatever library lies in it. Read first: the depth it
                // declares is the one the folder's modules are checked for.
                let library = dir.join(twinray_compile::cpu::LIBRARY);
                let ours = built && library.is_file();
                let kinds = ours.then(|| CrateKinds::load(&library)).transpose().map_err(fail)?;
                let depth = kinds.as_ref().map_or(MAX_RECURSION_DEPTH, |k| k.recursion_depth);
                let mut set = ShaderSet::uniform(Language::Rust);
                set.set_where(|_| true, |m| from_folder(m, &dir, depth)).map_err(fail)?;
                let names = own_modules(&dir);
                if kinds.is_some() || !names.is_empty() {
                    set.set_own(OwnKinds::new(kinds, &names, |m| from_folder(m, &dir, depth)).map_err(fail)?);
                }
                set
            }
            Found::File(file) => {
                return Err(fail(format!(
                    "{}: a base set is rust, glsl or a folder; name the module of a file (MODULE=FILE.spv)",
                    file.display()
                )))
            }
        };
        for (key, source) in &spec.overrides {
            let found = self.find(source).map_err(fail)?;
            apply(&mut set, *key, &found).map_err(fail)?;
        }
        set.named(spec);
        Ok(set)
    }

    /// Each of `specs`, loaded.
    pub fn load_all(&self, specs: &[SetSpec]) -> Result<Vec<ShaderSet>> {
        specs.iter().map(|s| self.load(s)).collect()
    }

    /// The folder of modules built from the sources in `dir`: built now, found up to date, or
    /// built earlier by this loader. A build says so on standard error, with its time.
    pub fn build(&self, dir: &Path) -> Result<PathBuf, String> {
        let key = dir.canonicalize().map_err(|e| format!("{}: {e}", dir.display()))?;
        if let Some(set) = self.built.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
            return Ok(set.clone());
        }
        let built = self.build_now(dir, false).map_err(|e| format!("{e:#}"))?;
        if built.rebuilt {
            eprintln!("build: {}", summary(dir, &built));
        }
        self.built.lock().unwrap_or_else(|e| e.into_inner()).insert(key, built.set.clone());
        Ok(built.set)
    }

    /// Builds the sources in `dir` whatever this loader built before (`force`: even when
    /// they are up to date), with this loader's deadline.
    pub fn build_now(&self, dir: &Path, force: bool) -> anyhow::Result<folder::Built> {
        let mut options = Options { force, ..Options::default() };
        if let Some(timeout) = self.build_timeout {
            options.timeout = timeout;
        }
        let _doing = crate::util::activity::doing(format!("building the stages of {}", dir.display()));
        folder::build(dir, options)
    }

    fn find(&self, source: &Source) -> Result<Found, String> {
        let path = match source {
            Source::Language(language) => return Ok(Found::Language(*language)),
            Source::Path(path) => path,
        };
        let word = path.display().to_string();
        if path.is_dir() && folder::sources_in(path).is_some() {
            Ok(Found::Folder(self.build(path)?, true))
        } else if path.is_dir() && MODULES.iter().any(|m| path.join(format!("{}.spv", m.name)).exists()) {
            Ok(Found::Folder(path.clone(), false))
        } else if path.is_dir() {
            Err(format!(
                "{word}: neither a set nor a shader crate (no NAME.spv of the catalog, no Cargo.toml, no raygen.rgen)"
            ))
        } else if path.is_file() {
            Ok(Found::File(path.clone()))
        } else if word.ends_with(".spv") || word.contains('/') {
            Err(format!("{word}: no such file or folder"))
        } else {
            Err(format!(
                "unknown language {word:?} (expected rust, glsl, a shader crate, a folder of modules or a .spv file)"
            ))
        }
    }
}

/// A build in words: the folder, whether it was built, its modules, contract and time.
pub fn summary(dir: &Path, built: &folder::Built) -> String {
    let what = if built.rebuilt { "built" } else { "up to date" };
    let (modules, contract, seconds) = (built.modules, &built.contract, built.seconds);
    format!("{}: {what}, {modules} modules (twinray-shared {contract}), {seconds:.1} s", dir.display())
}

/// The intersection and callable modules of `dir` that are no module of twinray's: those of a
/// crate's own shapes (`SHAPE_intersection.spv`) and materials (`MATERIAL_material.spv`).
fn own_modules(dir: &Path) -> Vec<String> {
    let files = std::fs::read_dir(dir).into_iter().flatten().flatten();
    let mut names: Vec<String> = files
        .filter_map(|e| e.file_name().to_str().and_then(|n| n.strip_suffix(".spv")).map(str::to_string))
        .filter(|n| (n.ends_with("_intersection") || n.ends_with("_material")) && !MODULES.iter().any(|m| m.name == n))
        .collect();
    names.sort();
    names
}

/// Module `spec` of a folder set: `DIR/NAME.spv`, checked for pipelines of recursion `depth`,
/// or missing.
fn from_folder(spec: &ModuleSpec, dir: &Path, depth: u32) -> Result<Origin, String> {
    let path = dir.join(format!("{}.spv", spec.name));
    if path.exists() {
        Ok(Origin::Disk(Arc::new(load(spec, &path, depth)?)))
    } else {
        Ok(Origin::Missing(path))
    }
}

/// The modules `key` names in `set`, taken from what `found` is, checked for the recursion
/// depth of `set`'s pipelines.
fn apply(set: &mut ShaderSet, key: Key, found: &Found) -> Result<(), String> {
    let depth = set.recursion_depth();
    let origin = |m: &ModuleSpec| match found {
        Found::Language(language) => Ok(Origin::Builtin(*language)),
        Found::Folder(dir, _) => from_folder(m, dir, depth),
        Found::File(file) => Ok(Origin::Disk(Arc::new(load(m, file, depth)?))),
    };
    match (key, found) {
        // A file is one module: a stage key names the module called as the stage.
        (Key::Stage(stage), Found::File(_)) => match MODULES.iter().find(|m| m.name == stage.name()) {
            Some(m) => set.set_where(|s| s.name == m.name, origin),
            None => {
                let names: Vec<_> = MODULES.iter().filter(|m| m.stage == stage).map(|m| m.name).collect();
                let stage = stage.name();
                Err(format!("{stage}=FILE: the {stage} stage has several modules; name one ({})", names.join(", ")))
            }
        },
        (Key::Stage(stage), _) => set.set_where(|s| s.stage == stage, origin),
        (Key::Module(name), _) => set.set_where(|s| s.name == name, origin),
    }
}
