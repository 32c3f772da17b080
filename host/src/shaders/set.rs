//! A shader set, written as a base followed by overrides, each `KEY=VALUE`:
//!
//! - the base: `rust`, `glsl` (the built-in sets), a folder of compiled modules (`NAME.spv`
//!   for each module of the catalog, as `cargo xtask shaders` writes them), or a folder of
//!   stage sources, built first (`sources`: a Rust shader crate, GLSL twins);
//! - `STAGE=LANGUAGE` or `STAGE=FOLDER`: every module of a stage (`raygen`, `miss`,
//!   `intersection`, `closest_hit`) from that set;
//! - `MODULE=LANGUAGE`, `MODULE=FOLDER` or `MODULE=FILE.spv`: one module of the catalog
//!   (`sphere_intersection`, `raygen`, ...) from there; `raygen=FILE.spv` and `miss=FILE.spv`
//!   name the module of that name.
//!
//! Every file is read and checked when the set is parsed, so a bad module is an input error
//! before any GPU work.

use super::module::{load, Origin, StageModule};
use crate::error::{Error, Result};
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::Arc;
use twinray_shared::catalog::{Language, ModuleSpec, Stage, MODULES};

/// Which module each stage uses.
#[derive(Clone, Debug)]
pub struct ShaderSet {
    /// One origin per module of the catalog, in catalog order.
    origins: Vec<Origin>,
    /// As written, for sets with modules from disk (built-in sets print canonically).
    text: Option<String>,
    /// 0 for the set itself; N for its Nth salted copy (see `copy`).
    copy: u32,
}

impl PartialEq for ShaderSet {
    fn eq(&self, other: &Self) -> bool {
        self.origins == other.origins && self.copy == other.copy
    }
}

impl Eq for ShaderSet {}

/// What the value of an item names.
enum Target {
    Language(Language),
    Folder(PathBuf),
    File(PathBuf),
}

impl ShaderSet {
    /// Every module from the built-in set of `language`.
    pub fn uniform(language: Language) -> Self {
        ShaderSet { origins: vec![Origin::Builtin(language); MODULES.len()], text: None, copy: 0 }
    }

    /// Copy `n` of this set (n > 0): every module salted (`salt::salted`) so that the driver
    /// compiles and places it apart from the set's own and any other copy's, its code
    /// unchanged. Printed as the set with "(copy N)" after it. Copy 0 is the set itself.
    pub fn copy(&self, n: u32) -> ShaderSet {
        ShaderSet { copy: n, ..self.clone() }
    }

    /// The set this is a copy of (itself when it is no copy).
    pub fn original(&self) -> ShaderSet {
        self.copy(0)
    }

    /// Each of `sets` with every repeat of an earlier set made its next copy: "glsl,glsl,rust,
    /// glsl" is glsl, glsl (copy 1), rust and glsl (copy 2). Timing the same code twice then
    /// times two placements of it, never one pipeline shared by a driver's cache.
    pub fn distinct(sets: &[ShaderSet]) -> Vec<ShaderSet> {
        let mut out: Vec<ShaderSet> = Vec::with_capacity(sets.len());
        for set in sets {
            let repeats = out.iter().filter(|s| s.original() == set.original()).count() as u32;
            out.push(if repeats == 0 { set.clone() } else { set.copy(set.copy + repeats) });
        }
        out
    }

    /// The built-in language of `stage`, when every module of the stage comes from one.
    pub fn language(&self, stage: Stage) -> Option<Language> {
        let mut languages = self.stage_origins(stage).map(|o| match o {
            Origin::Builtin(language) => Some(*language),
            _ => None,
        });
        let first = languages.next().flatten()?;
        languages.all(|l| l == Some(first)).then_some(first)
    }

    fn stage_origins(&self, stage: Stage) -> impl Iterator<Item = &Origin> {
        MODULES.iter().zip(&self.origins).filter(move |(m, _)| m.stage == stage).map(|(_, o)| o)
    }

    /// Whether this set takes the module called `name` from a folder that has no file for it.
    pub fn lacks(&self, name: &str) -> bool {
        MODULES.iter().zip(&self.origins).any(|(m, o)| m.name == name && matches!(o, Origin::Missing(_)))
    }

    /// The module called `name` in this set.
    pub fn module(&self, name: &str) -> Result<StageModule> {
        let spec = twinray_shared::catalog::module(name)
            .ok_or_else(|| Error::Unsupported(format!("no module {name} in the catalog")))?;
        self.resolve(&spec)
    }

    /// The module for `spec` in this set.
    pub fn resolve(&self, spec: &ModuleSpec) -> Result<StageModule> {
        let index = MODULES.iter().position(|m| m.name == spec.name);
        let origin = index.and_then(|i| self.origins.get(i)).ok_or_else(|| {
            Error::Unsupported(format!("module {} is not in the catalog this build knows", spec.name))
        })?;
        let module = origin.resolve(spec).map_err(|e| Error::Input(format!("shader set {self}: {e}")))?;
        if self.copy == 0 {
            return Ok(module);
        }
        let spirv = super::salt::salted(&module.spirv, self.copy)
            .ok_or_else(|| Error::Input(format!("shader set {self}: module {} is not SPIR-V to salt", spec.name)))?;
        Ok(StageModule { spirv: spirv.into(), ..module })
    }

    /// This set with the modules called `names` taken from `other` (what `twinray bisect`
    /// renders). Printed as this set followed by one `MODULE=ORIGIN` per module taken, so a
    /// set from disk stays a set that parses back.
    pub fn with_modules_from(&self, other: &ShaderSet, names: &[&str]) -> ShaderSet {
        let mut out = self.clone();
        let mut taken = Vec::new();
        for (i, spec) in MODULES.iter().enumerate().filter(|(_, m)| names.contains(&m.name)) {
            out.origins[i] = other.origins[i].clone();
            taken.push(match &other.origins[i] {
                Origin::Builtin(language) => format!("{}={}", spec.name, language.name()),
                Origin::Disk(m) => format!("{}={}", spec.name, m.path.display()),
                Origin::Missing(path) => format!("{}={}", spec.name, path.display()),
            });
        }
        out.text =
            out.from_disk().then(|| std::iter::once(self.to_string()).chain(taken).collect::<Vec<_>>().join(","));
        out
    }

    /// Whether the module called `name` is the same code in both sets (same SPIR-V and entry
    /// point), wherever each comes from.
    pub fn same_module(&self, other: &ShaderSet, name: &str) -> bool {
        match (self.module(name), other.module(name)) {
            (Ok(a), Ok(b)) => a.spirv == b.spirv && a.entry == b.entry,
            _ => false,
        }
    }

    /// Whether any module comes from disk.
    pub fn from_disk(&self) -> bool {
        self.origins.iter().any(|o| !matches!(o, Origin::Builtin(_)))
    }

    fn set_where(&mut self, target: &Target, mut which: impl FnMut(&ModuleSpec) -> bool) -> Result<(), String> {
        for (spec, origin) in MODULES.iter().zip(self.origins.iter_mut()) {
            if which(spec) {
                *origin = match target {
                    Target::Language(language) => Origin::Builtin(*language),
                    Target::Folder(dir) => from_folder(spec, dir)?,
                    Target::File(file) => Origin::Disk(Arc::new(load(spec, file)?)),
                };
            }
        }
        Ok(())
    }
}

/// Module `spec` of a folder set: `DIR/NAME.spv`, checked, or missing.
fn from_folder(spec: &ModuleSpec, dir: &Path) -> Result<Origin, String> {
    let path = dir.join(format!("{}.spv", spec.name));
    if path.exists() {
        Ok(Origin::Disk(Arc::new(load(spec, &path)?)))
    } else {
        Ok(Origin::Missing(path))
    }
}

fn target(word: &str) -> Result<Target, String> {
    match word.to_ascii_lowercase().as_str() {
        "rust" => return Ok(Target::Language(Language::Rust)),
        "glsl" => return Ok(Target::Language(Language::Glsl)),
        _ => {}
    }
    let path = PathBuf::from(word);
    if path.is_dir() && super::sources::holds_sources(&path) {
        Ok(Target::Folder(super::sources::built(&path)?))
    } else if path.is_dir() && MODULES.iter().any(|m| path.join(format!("{}.spv", m.name)).exists()) {
        Ok(Target::Folder(path))
    } else if path.is_dir() {
        Err(format!(
            "{word}: neither a set nor a shader crate (no NAME.spv of the catalog, no Cargo.toml, no raygen.rgen)"
        ))
    } else if path.is_file() {
        Ok(Target::File(path))
    } else if word.ends_with(".spv") || word.contains('/') {
        Err(format!("{word}: no such file or folder"))
    } else {
        Err(format!(
            "unknown language {word:?} (expected rust, glsl, a shader crate, a folder of modules or a .spv file)"
        ))
    }
}

fn parse_stage(word: &str) -> Option<Stage> {
    let normalized = word.to_ascii_lowercase().replace('-', "_");
    Stage::ALL.into_iter().find(|s| s.name() == normalized)
}

impl ShaderSet {
    fn apply(&mut self, key: &str, value: &str) -> Result<(), String> {
        let target = target(value)?;
        let module = MODULES.iter().find(|m| m.name == key);
        match (parse_stage(key), &target, module) {
            (Some(stage), Target::File(_), None) => {
                let names: Vec<_> = MODULES.iter().filter(|m| m.stage == stage).map(|m| m.name).collect();
                Err(format!("{key}={value}: the {key} stage has several modules; name one ({})", names.join(", ")))
            }
            (_, Target::File(_), Some(m)) => self.set_where(&target, |s| s.name == m.name),
            (Some(stage), _, _) => self.set_where(&target, |s| s.stage == stage),
            (None, _, Some(m)) => self.set_where(&target, |s| s.name == m.name),
            (None, _, None) => {
                let stages: Vec<_> = Stage::ALL.iter().map(|s| s.name()).collect();
                Err(format!("unknown stage {key:?} (expected one of {}, or a module name)", stages.join(", ")))
            }
        }
    }
}

impl FromStr for ShaderSet {
    type Err = Error;

    fn from_str(text: &str) -> Result<Self> {
        let fail = |message: String| Error::Input(format!("shader set {text:?}: {message}"));
        let mut parts = text.split(',').map(str::trim);
        let mut set = match target(parts.next().unwrap_or_default()).map_err(fail)? {
            Target::Language(language) => ShaderSet::uniform(language),
            Target::Folder(dir) => {
                let mut set = ShaderSet::uniform(Language::Rust);
                set.set_where(&Target::Folder(dir), |_| true).map_err(fail)?;
                set
            }
            Target::File(file) => {
                return Err(fail(format!(
                    "{}: a base set is rust, glsl or a folder; name the module of a file (MODULE=FILE.spv)",
                    file.display()
                )))
            }
        };
        let mut named: Vec<&str> = Vec::new();
        for part in parts {
            let (key, value) = part
                .split_once('=')
                .ok_or_else(|| fail(format!("{part:?} is not STAGE=LANGUAGE (e.g. intersection=glsl)")))?;
            // Which of two answers was meant is a guess: say so instead.
            if named.contains(&key.trim()) {
                return Err(fail(format!("{:?} is named twice", key.trim())));
            }
            named.push(key.trim());
            set.apply(key.trim(), value.trim()).map_err(fail)?;
        }
        if set.from_disk() {
            let parts: Vec<&str> = text.split(',').map(str::trim).collect();
            set.text = Some(parts.join(","));
        }
        Ok(set)
    }
}

/// Several sets, comma-separated, where a `KEY=VALUE` item changes the set before it:
/// "rust,glsl,rust,intersection=glsl" is rust, glsl and a mix.
pub fn parse_sets(text: &str) -> Result<Vec<ShaderSet>> {
    let mut groups: Vec<String> = Vec::new();
    for item in text.split(',').map(str::trim) {
        match groups.last_mut() {
            Some(group) if item.contains('=') => {
                group.push(',');
                group.push_str(item);
            }
            _ => groups.push(item.to_string()),
        }
    }
    groups.iter().map(|g| g.parse()).collect()
}

/// A built-in set in the shortest form that parses to it (stage overrides in stage order, then
/// single modules); a set with modules from disk as it was written.
impl fmt::Display for ShaderSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.fmt_set(f)?;
        match self.copy {
            0 => Ok(()),
            n => write!(f, " (copy {n})"),
        }
    }
}

impl ShaderSet {
    fn fmt_set(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(text) = &self.text {
            return f.write_str(text);
        }
        let base = self.language(Stage::Raygen).unwrap_or(Language::Rust);
        f.write_str(base.name())?;
        for stage in Stage::ALL {
            match self.language(stage) {
                Some(language) if language == base => {}
                Some(language) => write!(f, ",{}={}", stage.name(), language.name())?,
                None => {
                    let in_stage = || MODULES.iter().zip(&self.origins).filter(move |(m, _)| m.stage == stage);
                    let builtin = |o: &Origin| match o {
                        Origin::Builtin(language) => Some(*language),
                        _ => None,
                    };
                    // A module named as its stage (`raygen`) cannot be named alone: `raygen=glsl`
                    // reads back as the whole stage. So the stage takes that module's language
                    // first, and the stage's other modules that differ are named after it.
                    let named = in_stage().find(|(m, _)| m.name == stage.name()).and_then(|(_, o)| builtin(o));
                    let stage_language = named.unwrap_or(base);
                    if stage_language != base {
                        write!(f, ",{}={}", stage.name(), stage_language.name())?;
                    }
                    for (spec, origin) in in_stage() {
                        match builtin(origin) {
                            Some(language) if language != stage_language => {
                                write!(f, ",{}={}", spec.name, language.name())?
                            }
                            _ => {}
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_lists_attach_stage_overrides_to_the_set_before() {
        let sets = super::parse_sets("rust, glsl,rust,intersection=glsl,miss=glsl").unwrap();
        let names: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        assert_eq!(names, ["rust", "glsl", "rust,miss=glsl,intersection=glsl"]); // stage order
        assert!(super::parse_sets("intersection=glsl").is_err(), "an override needs a set before it");
    }

    /// What `twinray bisect` prints, and hands to `--processes`' children as text: every
    /// set with one module taken from the other language reads back as itself, the `raygen`
    /// module (named as its stage) too.
    #[test]
    fn a_set_with_any_one_module_swapped_reads_back_as_itself() {
        let (rust, glsl) = (ShaderSet::uniform(Language::Rust), ShaderSet::uniform(Language::Glsl));
        for (from, to) in [(&rust, &glsl), (&glsl, &rust)] {
            for spec in MODULES {
                let swapped = from.with_modules_from(to, &[spec.name]);
                let text = swapped.to_string();
                assert_eq!(text.parse::<ShaderSet>().ok(), Some(swapped), "{} swapped: {text}", spec.name);
            }
        }
    }

    #[test]
    fn parses_plain_and_mixed_sets() {
        let mixed: ShaderSet = "rust,intersection=glsl".parse().unwrap();
        assert_eq!(mixed.language(Stage::Intersection), Some(Language::Glsl));
        assert_eq!(mixed.language(Stage::ClosestHit), Some(Language::Rust));
        assert_eq!(mixed.to_string(), "rust,intersection=glsl");
        assert_eq!("GLSL".parse::<ShaderSet>().unwrap(), ShaderSet::uniform(Language::Glsl));
        assert_eq!("glsl,closest-hit=rust".parse::<ShaderSet>().unwrap().to_string(), "glsl,closest_hit=rust");
        let one: ShaderSet = "rust,sphere_intersection=glsl".parse().unwrap();
        assert_eq!(one.language(Stage::Intersection), None, "one module of the stage differs");
        assert_eq!(one.to_string(), "rust,sphere_intersection=glsl");
        assert_eq!(one.to_string().parse::<ShaderSet>().unwrap(), one);
    }

    #[test]
    fn rejects_unknown_languages_and_stages() {
        let e = "hlsl".parse::<ShaderSet>().unwrap_err().to_string();
        assert!(e.contains("unknown language \"hlsl\""), "{e}");
        let e = "rust,anyhit=glsl".parse::<ShaderSet>().unwrap_err().to_string();
        assert!(e.contains("unknown stage \"anyhit\""), "{e}");
        let e = "rust,glsl".parse::<ShaderSet>().unwrap_err().to_string();
        assert!(e.contains("STAGE=LANGUAGE"), "{e}");
        let e = "rust,raygen=no/such/raygen.spv".parse::<ShaderSet>().unwrap_err().to_string();
        assert!(e.contains("no/such/raygen.spv: no such file or folder"), "{e}");
    }

    #[test]
    fn modules_taken_from_another_set_print_as_a_set_that_parses_back() {
        let (rust, glsl) = (ShaderSet::uniform(Language::Rust), ShaderSet::uniform(Language::Glsl));
        let swapped = rust.with_modules_from(&glsl, &["miss", "shadow_miss"]);
        assert_eq!(swapped.to_string(), "rust,miss=glsl");
        assert!(!swapped.same_module(&rust, "miss") && swapped.same_module(&glsl, "miss"));
        assert!(swapped.same_module(&rust, "raygen"));
        let file = format!("{}/../spirv/rust/sphere_naive_intersection.spv", env!("CARGO_MANIFEST_DIR"));
        let naive: ShaderSet = format!("rust,sphere_intersection={file}").parse().unwrap();
        let planted = rust.with_modules_from(&naive, &["sphere_intersection"]);
        assert_eq!(planted, naive);
        assert_eq!(planted.to_string().parse::<ShaderSet>().unwrap(), naive);
        assert!(!planted.same_module(&rust, "sphere_intersection"));
    }
}
