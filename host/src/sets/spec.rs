//! A shader set as text, parsed without touching a file: a base followed by overrides, each
//! `KEY=VALUE`:
//!
//! - the base: `rust`, `glsl` (the built-in sets), a folder of compiled modules (`NAME.spv`
//!   for each module of the catalog, as `cargo xtask shaders` writes them), or a folder of
//!   stage sources (a Rust shader crate, GLSL twins), built when the set is loaded;
//! - `STAGE=LANGUAGE` or `STAGE=FOLDER`: every module of a stage (`raygen`, `miss`,
//!   `intersection`, `closest_hit`) from that set;
//! - `MODULE=LANGUAGE`, `MODULE=FOLDER` or `MODULE=FILE.spv`: one module of the catalog
//!   (`sphere_intersection`, `raygen`, ...) from there; `raygen=FILE.spv` and `miss=FILE.spv`
//!   name the module of that name.
//!
//! Parsing checks the words (known stages and modules, no key named twice); what a path
//! names is found when the set is loaded (`super::load::Loader`), once, after the command's
//! options and log are in place, so a build's deadline and messages are the command's.

use crate::error::{Error, Result};
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use twinray_shared::catalog::{Language, Stage, MODULES};

/// What one item of a set names, before anything is read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Source {
    /// A built-in set.
    Language(Language),
    /// A folder (of modules or of sources) or a `.spv` file, found when loaded.
    Path(PathBuf),
}

/// Which modules an override replaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    Stage(Stage),
    Module(&'static str),
}

/// A set as written: its base and overrides, in order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SetSpec {
    pub base: Source,
    pub overrides: Vec<(Key, Source)>,
    /// The text it was parsed from, trimmed, for messages and for the loaded set's name.
    text: String,
}

impl SetSpec {
    /// The built-in set of `language`.
    pub fn builtin(language: Language) -> SetSpec {
        SetSpec { base: Source::Language(language), overrides: Vec::new(), text: language.name().to_string() }
    }

    /// Whether loading it reads any file (a folder or a `.spv` file is named).
    pub fn names_paths(&self) -> bool {
        self.paths().next().is_some()
    }

    /// Every folder or `.spv` file it names, base first, as written.
    pub fn paths(&self) -> impl Iterator<Item = &Path> {
        std::iter::once(&self.base).chain(self.overrides.iter().map(|(_, s)| s)).filter_map(|s| match s {
            Source::Path(p) => Some(p.as_path()),
            Source::Language(_) => None,
        })
    }
}

fn source(word: &str) -> Source {
    match word.to_ascii_lowercase().as_str() {
        "rust" => Source::Language(Language::Rust),
        "glsl" => Source::Language(Language::Glsl),
        _ => Source::Path(PathBuf::from(word)),
    }
}

fn key(word: &str) -> Result<Key, String> {
    let normalized = word.to_ascii_lowercase().replace('-', "_");
    // A module named as its stage (`raygen`, `miss`) is the stage: `raygen=FILE.spv` names the
    // module when the value turns out to be a file (see `Loader`).
    if let Some(stage) = Stage::ALL.into_iter().find(|s| s.name() == normalized) {
        return Ok(Key::Stage(stage));
    }
    if let Some(m) = MODULES.iter().find(|m| m.name == word) {
        return Ok(Key::Module(m.name));
    }
    let stages: Vec<_> = Stage::ALL.iter().map(|s| s.name()).collect();
    Err(format!("unknown stage {word:?} (expected one of {}, or a module name)", stages.join(", ")))
}

impl FromStr for SetSpec {
    type Err = Error;

    fn from_str(text: &str) -> Result<Self> {
        let fail = |message: String| Error::Input(format!("shader set {text:?}: {message}"));
        let mut parts = text.split(',').map(str::trim);
        let first = parts.next().unwrap_or_default();
        if first.is_empty() {
            return Err(fail("no set named (rust, glsl, a shader crate or a folder of modules)".into()));
        }
        if first.contains('=') {
            return Err(fail(format!("{first:?} changes a set, but no set comes before it (e.g. rust,{first})")));
        }
        let base = source(first);
        let mut overrides = Vec::new();
        let mut named: Vec<&str> = Vec::new();
        for part in parts {
            let (k, v) = part
                .split_once('=')
                .ok_or_else(|| fail(format!("{part:?} is not STAGE=LANGUAGE (e.g. intersection=glsl)")))?;
            let (k, v) = (k.trim(), v.trim());
            // Which of two answers was meant is a guess: say so instead.
            if named.contains(&k) {
                return Err(fail(format!("{k:?} is named twice")));
            }
            named.push(k);
            if v.is_empty() {
                return Err(fail(format!("{k}= names no set")));
            }
            overrides.push((key(k).map_err(fail)?, source(v)));
        }
        let text = text.split(',').map(str::trim).collect::<Vec<_>>().join(",");
        Ok(SetSpec { base, overrides, text })
    }
}

impl fmt::Display for SetSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// Several sets, comma-separated, where a `KEY=VALUE` item changes the set before it:
/// "rust,glsl,rust,intersection=glsl" is rust, glsl and a mix.
pub fn parse_specs(text: &str) -> Result<Vec<SetSpec>> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_lists_attach_stage_overrides_to_the_set_before() {
        let specs = parse_specs("rust, glsl,rust,intersection=glsl,miss=glsl").unwrap();
        let names: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
        assert_eq!(names, ["rust", "glsl", "rust,intersection=glsl,miss=glsl"]);
        assert!(parse_specs("intersection=glsl").is_err(), "an override needs a set before it");
    }

    #[test]
    fn words_are_checked_and_paths_left_for_the_loader() {
        let e = "rust,anyhit=glsl".parse::<SetSpec>().unwrap_err().to_string();
        assert!(e.contains("unknown stage \"anyhit\""), "{e}");
        let e = "rust,glsl".parse::<SetSpec>().unwrap_err().to_string();
        assert!(e.contains("STAGE=LANGUAGE"), "{e}");
        let e = "rust,miss=glsl,miss=rust".parse::<SetSpec>().unwrap_err().to_string();
        assert!(e.contains("named twice"), "{e}");
        let far: SetSpec = "rust,raygen=no/such/raygen.spv,closest-hit=GLSL".parse().unwrap();
        assert_eq!(far.overrides[0], (Key::Stage(Stage::Raygen), Source::Path("no/such/raygen.spv".into())));
        assert_eq!(far.overrides[1], (Key::Stage(Stage::ClosestHit), Source::Language(Language::Glsl)));
        assert!(far.names_paths() && !SetSpec::builtin(Language::Glsl).names_paths());
    }

    #[test]
    fn paths_are_the_base_and_overrides_that_name_files_in_order() {
        let spec: SetSpec = "./mine,miss=glsl,closest_hit=twins/glsl".parse().unwrap();
        let paths: Vec<&Path> = spec.paths().collect();
        assert_eq!(paths, [Path::new("./mine"), Path::new("twins/glsl")]);
        assert_eq!(SetSpec::builtin(Language::Rust).paths().count(), 0);
    }
}
