//! Shader sets: which language supplies each stage. A set resolves every stage to SPIR-V
//! bytes and an entry point; the pipeline code never branches on language, so any per-stage
//! mix is just another set.

use crate::error::{Error, Result};
use std::ffi::CString;
use std::fmt;
use std::str::FromStr;
pub use twinray_shared::catalog::{Language, ModuleSpec, Stage, MODULES};

/// A stage resolved to what the pipeline needs.
#[derive(Clone, Debug)]
pub struct StageModule {
    pub spec: ModuleSpec,
    pub language: Language,
    pub entry: CString,
    pub spirv: &'static [u8],
}

macro_rules! embedded {
    ($lang:literal, $name:literal) => {
        include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/../spirv/", $lang, "/", $name, ".spv"))
    };
}

fn embedded_spirv(language: Language, name: &str) -> Option<&'static [u8]> {
    Some(match (language, name) {
        (Language::Rust, "raygen") => embedded!("rust", "raygen"),
        (Language::Rust, "probe") => embedded!("rust", "probe"),
        (Language::Rust, "miss") => embedded!("rust", "miss"),
        (Language::Rust, "shadow_miss") => embedded!("rust", "shadow_miss"),
        (Language::Rust, "sphere_intersection") => embedded!("rust", "sphere_intersection"),
        (Language::Rust, "plane_intersection") => embedded!("rust", "plane_intersection"),
        (Language::Rust, "box_intersection") => embedded!("rust", "box_intersection"),
        (Language::Rust, "cylinder_intersection") => embedded!("rust", "cylinder_intersection"),
        (Language::Rust, "cone_intersection") => embedded!("rust", "cone_intersection"),
        (Language::Rust, "torus_intersection") => embedded!("rust", "torus_intersection"),
        (Language::Rust, "sphere_naive_intersection") => embedded!("rust", "sphere_naive_intersection"),
        (Language::Rust, "cylinder_naive_intersection") => embedded!("rust", "cylinder_naive_intersection"),
        (Language::Rust, "torus_naive_intersection") => embedded!("rust", "torus_naive_intersection"),
        (Language::Rust, "procedural_closest_hit") => embedded!("rust", "procedural_closest_hit"),
        (Language::Rust, "triangle_closest_hit") => embedded!("rust", "triangle_closest_hit"),
        (Language::Glsl, "raygen") => embedded!("glsl", "raygen"),
        (Language::Glsl, "probe") => embedded!("glsl", "probe"),
        (Language::Glsl, "miss") => embedded!("glsl", "miss"),
        (Language::Glsl, "shadow_miss") => embedded!("glsl", "shadow_miss"),
        (Language::Glsl, "sphere_intersection") => embedded!("glsl", "sphere_intersection"),
        (Language::Glsl, "plane_intersection") => embedded!("glsl", "plane_intersection"),
        (Language::Glsl, "box_intersection") => embedded!("glsl", "box_intersection"),
        (Language::Glsl, "cylinder_intersection") => embedded!("glsl", "cylinder_intersection"),
        (Language::Glsl, "cone_intersection") => embedded!("glsl", "cone_intersection"),
        (Language::Glsl, "torus_intersection") => embedded!("glsl", "torus_intersection"),
        (Language::Glsl, "sphere_naive_intersection") => embedded!("glsl", "sphere_naive_intersection"),
        (Language::Glsl, "cylinder_naive_intersection") => embedded!("glsl", "cylinder_naive_intersection"),
        (Language::Glsl, "torus_naive_intersection") => embedded!("glsl", "torus_naive_intersection"),
        (Language::Glsl, "procedural_closest_hit") => embedded!("glsl", "procedural_closest_hit"),
        (Language::Glsl, "triangle_closest_hit") => embedded!("glsl", "triangle_closest_hit"),
        _ => return None,
    })
}

/// Which language supplies each stage. Written `rust`, `glsl`, or a base set followed by
/// per-stage overrides: `rust,intersection=glsl`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShaderSet {
    languages: [Language; 4],
}

impl ShaderSet {
    pub fn uniform(language: Language) -> Self {
        ShaderSet { languages: [language; 4] }
    }

    pub fn language(&self, stage: Stage) -> Language {
        self.languages[stage as usize]
    }

    /// The module for `spec` in this set.
    pub fn resolve(&self, spec: &ModuleSpec) -> Result<StageModule> {
        let language = self.language(spec.stage);
        let spirv = embedded_spirv(language, spec.name)
            .ok_or_else(|| Error::Input(format!("no {} module named {}", language.name(), spec.name)))?;
        let entry = CString::new(spec.entry_point(language))
            .map_err(|_| Error::Input(format!("entry point of {} contains a NUL byte", spec.name)))?;
        Ok(StageModule { spec: *spec, language, entry, spirv })
    }
}

impl FromStr for ShaderSet {
    type Err = Error;

    fn from_str(text: &str) -> Result<Self> {
        let mut parts = text.split(',').map(str::trim);
        let base = parse_language(parts.next().unwrap_or_default(), text)?;
        let mut set = ShaderSet::uniform(base);
        for part in parts {
            let (stage, language) = part.split_once('=').ok_or_else(|| {
                Error::Input(format!("shader set {text:?}: {part:?} is not STAGE=LANGUAGE (e.g. intersection=glsl)"))
            })?;
            let stage = parse_stage(stage.trim(), text)?;
            set.languages[stage as usize] = parse_language(language.trim(), text)?;
        }
        Ok(set)
    }
}

/// Several sets, comma-separated, where a `STAGE=LANGUAGE` item changes the set before it:
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

fn parse_language(word: &str, whole: &str) -> Result<Language> {
    match word.to_ascii_lowercase().as_str() {
        "rust" => Ok(Language::Rust),
        "glsl" => Ok(Language::Glsl),
        _ => Err(Error::Input(format!("shader set {whole:?}: unknown language {word:?} (expected rust or glsl)"))),
    }
}

fn parse_stage(word: &str, whole: &str) -> Result<Stage> {
    let normalized = word.to_ascii_lowercase().replace('-', "_");
    Stage::ALL.into_iter().find(|s| s.name() == normalized).ok_or_else(|| {
        let names: Vec<_> = Stage::ALL.iter().map(|s| s.name()).collect();
        Error::Input(format!("shader set {whole:?}: unknown stage {word:?} (expected one of {})", names.join(", ")))
    })
}

/// Written back in the shortest form that parses to the same set.
impl fmt::Display for ShaderSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let base = self.languages[0];
        f.write_str(base.name())?;
        for stage in Stage::ALL {
            let language = self.language(stage);
            if language != base {
                write!(f, ",{}={}", stage.name(), language.name())?;
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

    #[test]
    fn parses_plain_and_mixed_sets() {
        let mixed: ShaderSet = "rust,intersection=glsl".parse().unwrap();
        assert_eq!(mixed.language(Stage::Intersection), Language::Glsl);
        assert_eq!(mixed.language(Stage::ClosestHit), Language::Rust);
        assert_eq!(mixed.to_string(), "rust,intersection=glsl");
        assert_eq!("GLSL".parse::<ShaderSet>().unwrap(), ShaderSet::uniform(Language::Glsl));
        assert_eq!("glsl,closest-hit=rust".parse::<ShaderSet>().unwrap().to_string(), "glsl,closest_hit=rust");
    }

    #[test]
    fn rejects_unknown_languages_and_stages() {
        let e = "hlsl".parse::<ShaderSet>().unwrap_err().to_string();
        assert!(e.contains("unknown language \"hlsl\""), "{e}");
        let e = "rust,anyhit=glsl".parse::<ShaderSet>().unwrap_err().to_string();
        assert!(e.contains("unknown stage \"anyhit\""), "{e}");
        let e = "rust,glsl".parse::<ShaderSet>().unwrap_err().to_string();
        assert!(e.contains("STAGE=LANGUAGE"), "{e}");
    }

    #[test]
    fn every_module_is_embedded_in_both_languages() {
        for spec in MODULES {
            for language in [Language::Rust, Language::Glsl] {
                assert!(embedded_spirv(language, spec.name).is_some(), "{} {}", language.name(), spec.name);
            }
        }
    }
}
