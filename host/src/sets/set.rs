//! A loaded shader set: where each module of the catalog comes from, every module read from
//! disk already checked. Sets are written as text (`super::spec::SetSpec`) and loaded by a
//! `super::load::Loader`; a loaded set prints as the text that loads it back.

use super::module::{Origin, StageModule};
use super::own::{CrateKinds, OwnKinds};
use super::spec::SetSpec;
use crate::error::{Error, Result};
use std::fmt;
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
    /// The shapes and materials of the crate the set was built from, when it has any.
    own: Option<&'static OwnKinds>,
}

impl PartialEq for ShaderSet {
    fn eq(&self, other: &Self) -> bool {
        self.origins == other.origins && self.copy == other.copy && self.own == other.own
    }
}

impl Eq for ShaderSet {}

impl ShaderSet {
    /// Every module from the built-in set of `language`.
    pub fn uniform(language: Language) -> Self {
        ShaderSet { origins: vec![Origin::Builtin(language); MODULES.len()], text: None, copy: 0, own: None }
    }

    /// Copy `n` of this set (n > 0): every module salted (`copies::salted`) so that the driver
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
        let own = self.own.iter().flat_map(|o| o.modules.iter().map(|(m, o)| (m, o)));
        MODULES.iter().zip(&self.origins).chain(own).any(|(m, o)| m.name == name && matches!(o, Origin::Missing(_)))
    }

    /// The crates of `sets`, each once: the shape and material kinds a scene rendered with them may
    /// name beside twinray's.
    pub fn own_kinds(sets: &[&ShaderSet]) -> Vec<&'static CrateKinds> {
        let mut out: Vec<&'static CrateKinds> = Vec::new();
        for own in sets.iter().filter_map(|s| s.own.and_then(|o| o.kinds.as_ref())) {
            if !out.iter().any(|o| std::ptr::eq(*o, own)) {
                out.push(own);
            }
        }
        out
    }

    /// Whether every module of the set is one of twinray's built-in ones (a built-in set, or a
    /// per-stage mix of them): nothing from disk.
    pub fn all_builtin(&self) -> bool {
        self.own.is_none() && self.origins.iter().all(|o| matches!(o, Origin::Builtin(_)))
    }

    /// The recursion depth of the set's pipelines: twinray's 1, or what its crate declares.
    pub fn recursion_depth(&self) -> u32 {
        let depth = self.own.and_then(|o| o.kinds.as_ref()).map(|k| k.recursion_depth);
        depth.unwrap_or(twinray_shared::interface::MAX_RECURSION_DEPTH)
    }

    /// Gives the set its crate's kinds, kept for the rest of the run (a scene and the
    /// reference refer to them as long as the set's pipelines may run).
    pub(super) fn set_own(&mut self, own: OwnKinds) {
        self.own = Some(Box::leak(Box::new(own)));
    }

    /// The module called `name` in this set: one of the catalog, or of the crate's own shapes and
    /// materials.
    pub fn module(&self, name: &str) -> Result<StageModule> {
        if let Some(spec) = twinray_shared::catalog::module(name) {
            return self.resolve(&spec);
        }
        let own = self.own.iter().flat_map(|o| o.modules.iter()).find(|(m, _)| m.name == name);
        match own {
            Some((spec, origin)) => self.resolve_from(spec, origin),
            None if name.ends_with("_intersection") => Err(Error::Input(format!(
                "shader set {self}: no module {name}, the intersection stage of a crate's own shape: the set was \
                 not built from a crate (or its GLSL twins) that has the shape"
            ))),
            None if name.ends_with("_material") => Err(Error::Input(format!(
                "shader set {self}: no module {name}, the callable of a crate's own material: the set was \
                 not built from a crate (or its GLSL twins) that has the material"
            ))),
            None => Err(Error::Input(format!("shader set {self}: no module {name} in twinray's catalog"))),
        }
    }

    /// The module for `spec` in this set.
    pub fn resolve(&self, spec: &ModuleSpec) -> Result<StageModule> {
        let index = MODULES.iter().position(|m| m.name == spec.name);
        let origin = index.and_then(|i| self.origins.get(i)).ok_or_else(|| {
            Error::Unsupported(format!("module {} is not in the catalog this build knows", spec.name))
        })?;
        self.resolve_from(spec, origin)
    }

    fn resolve_from(&self, spec: &ModuleSpec, origin: &Origin) -> Result<StageModule> {
        let module = origin.resolve(spec).map_err(|e| Error::Input(format!("shader set {self}: {e}")))?;
        if self.copy == 0 {
            return Ok(module);
        }
        let spirv = super::copies::salted(&module.spirv, self.copy)
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

    /// Which of the modules called `names` differ from both built-in sets' module of the name
    /// (a crate's own shapes' always do): where a stage that never returns can be, since the
    /// built-in modules return, and a module built unchanged from them is the same bytes.
    pub fn changed_modules<'a>(&self, names: &[&'a str]) -> Vec<&'a str> {
        let builtin = [ShaderSet::uniform(Language::Rust), ShaderSet::uniform(Language::Glsl)];
        let original = self.original();
        let changed = |name: &&str| !builtin.iter().any(|b| original.same_module(b, name));
        names.iter().copied().filter(changed).collect()
    }

    /// `names`, the modules of a pipeline of this set, as an error names them: each, or where
    /// some are built-in code, the others first as the ones where a stage may not return.
    pub fn describe_modules(&self, names: &[&str]) -> String {
        let changed = self.changed_modules(names);
        if changed.is_empty() || changed.len() == names.len() {
            return names.join(", ");
        }
        let same: Vec<&str> = names.iter().copied().filter(|n| !changed.contains(n)).collect();
        format!("changed from the built-in sets: {}; as built in: {}", changed.join(", "), same.join(", "))
    }

    /// Whether any module comes from disk.
    pub fn from_disk(&self) -> bool {
        self.origins.iter().any(|o| !matches!(o, Origin::Builtin(_)))
    }

    /// Each module `which` picks taken from `origin`.
    pub(super) fn set_where(
        &mut self,
        mut which: impl FnMut(&ModuleSpec) -> bool,
        origin: impl Fn(&ModuleSpec) -> Result<Origin, String>,
    ) -> Result<(), String> {
        for (spec, slot) in MODULES.iter().zip(self.origins.iter_mut()) {
            if which(spec) {
                *slot = origin(spec)?;
            }
        }
        Ok(())
    }

    /// Names a set loaded from `spec` by its text, when it reads files (built-in sets print
    /// canonically).
    pub(super) fn named(&mut self, spec: &SetSpec) {
        self.text = self.from_disk().then(|| spec.to_string());
    }
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
    use super::super::load::Loader;
    use super::*;

    fn load(text: &str) -> Result<ShaderSet> {
        Loader::default().load(&text.parse()?)
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
                assert_eq!(load(&text).ok(), Some(swapped), "{} swapped: {text}", spec.name);
            }
        }
    }

    #[test]
    fn loads_plain_and_mixed_sets() {
        let mixed = load("rust,intersection=glsl").unwrap();
        assert_eq!(mixed.language(Stage::Intersection), Some(Language::Glsl));
        assert_eq!(mixed.language(Stage::ClosestHit), Some(Language::Rust));
        assert_eq!(mixed.to_string(), "rust,intersection=glsl");
        assert_eq!(load("GLSL").unwrap(), ShaderSet::uniform(Language::Glsl));
        assert_eq!(load("glsl,closest-hit=rust").unwrap().to_string(), "glsl,closest_hit=rust");
        let one = load("rust,sphere_intersection=glsl").unwrap();
        assert_eq!(one.language(Stage::Intersection), None, "one module of the stage differs");
        assert_eq!(one.to_string(), "rust,sphere_intersection=glsl");
        assert_eq!(load(&one.to_string()).unwrap(), one);
    }

    #[test]
    fn refuses_unknown_languages_and_missing_files_when_loaded() {
        let e = load("hlsl").unwrap_err().to_string();
        assert!(e.contains("unknown language \"hlsl\""), "{e}");
        let e = load("rust,raygen=no/such/raygen.spv").unwrap_err().to_string();
        assert!(e.contains("no/such/raygen.spv: no such file or folder"), "{e}");
    }

    #[test]
    fn modules_taken_from_another_set_print_as_a_set_that_loads_back() {
        let (rust, glsl) = (ShaderSet::uniform(Language::Rust), ShaderSet::uniform(Language::Glsl));
        let swapped = rust.with_modules_from(&glsl, &["miss", "shadow_miss"]);
        assert_eq!(swapped.to_string(), "rust,miss=glsl");
        assert!(!swapped.same_module(&rust, "miss") && swapped.same_module(&glsl, "miss"));
        assert!(swapped.same_module(&rust, "raygen"));
        let file = format!("{}/../spirv/rust/sphere_naive_intersection.spv", env!("CARGO_MANIFEST_DIR"));
        let naive = load(&format!("rust,sphere_intersection={file}")).unwrap();
        let planted = rust.with_modules_from(&naive, &["sphere_intersection"]);
        assert_eq!(planted, naive);
        assert_eq!(load(&planted.to_string()).unwrap(), naive);
        assert!(!planted.same_module(&rust, "sphere_intersection"));
    }
}
