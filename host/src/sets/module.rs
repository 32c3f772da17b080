//! One module of a set, resolved for the pipeline, and modules read from disk: each checked as
//! `cargo xtask shaders` checks the ones it builds (valid SPIR-V 1.4 for Vulkan by SPIRV-Tools'
//! validator, an entry point with the stage's execution model, only bindings of the shared
//! layout that the stage can see, and the payloads and attributes of `twinray_shared::interface`),
//! and refused first where it records another contract than this build's
//! (`twinray_shared::contract`).

use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use twinray_shared::catalog::{Language, ModuleSpec};
use twinray_shared::spirv_info;

/// A stage resolved to what the pipeline needs.
#[derive(Clone, Debug)]
pub struct StageModule {
    pub spec: ModuleSpec,
    /// Where it came from, for reports and errors: `rust`, `glsl` or the file.
    pub origin: String,
    pub entry: CString,
    pub spirv: Arc<[u8]>,
}

/// Where one module of a set comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Origin {
    Builtin(Language),
    Disk(Arc<DiskModule>),
    /// Asked for from a folder that has no file for it: an error only if a pipeline needs it.
    Missing(PathBuf),
}

/// A module read from a file and checked.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct DiskModule {
    pub path: PathBuf,
    pub spirv: Arc<[u8]>,
    pub entry: String,
    /// Its accesses of descriptor arrays at non-uniform indices without `NonUniform`, in words.
    pub non_uniform: Vec<String>,
}

/// Reads `path` as the module `spec` and checks it, for pipelines of recursion `depth`; the
/// error names the file and what is wrong.
pub(crate) fn load(spec: &ModuleSpec, path: &Path, depth: u32) -> Result<DiskModule, String> {
    let file = path.display();
    let bytes = std::fs::read(path).map_err(|e| format!("{file}: cannot read: {e}"))?;
    // twinray's own checks first, whose words say what a module for this stage must be; the
    // validator's after, for everything else a driver would trip on.
    let info = spirv_info::parse(&bytes).map_err(|e| format!("{file}: not a SPIR-V module ({e})"))?;
    // A module twinray built records the contract it was built against: one of another
    // contract is refused before anything reads its layout as this one's.
    if let Some(refusal) = info.contract().and_then(twinray_shared::contract::refusal) {
        return Err(format!("{file}: {refusal}"));
    }
    let entry = spec.find_entry(&info).unwrap_or_else(|| spec.name.to_string());
    twinray_shared::module_check::check_module(spec, &info, &entry, depth)
        .map_err(|e| format!("{file}: {e}, so it cannot be the {} module", spec.name))?;
    super::validate::validate(&bytes).map_err(|e| format!("{file}: {e}"))?;
    let faults = twinray_compile::uniformity::check(&bytes).map_err(|e| format!("{file}: {e}"))?;
    let non_uniform = faults.iter().map(|f| format!("{file} ({} stage): {f}", spec.stage.name())).collect();
    Ok(DiskModule { path: path.to_path_buf(), spirv: bytes.into(), entry, non_uniform })
}

/// Says, once per process for each, what `module` indexes without `NonUniform`: every device
/// twinray has run on reads the right descriptor without the decoration, so no render would
/// show the fault, and it is said on every device. (When the module is used, not when it is
/// read: a set loaded and never rendered says nothing.)
fn report_non_uniform(module: &DiskModule) {
    static SAID: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());
    let mut said = SAID.lock().unwrap_or_else(|e| e.into_inner());
    if !module.non_uniform.is_empty() && !said.contains(&module.path) {
        said.push(module.path.clone());
        for line in &module.non_uniform {
            log::warn!("{line}");
        }
    }
}

impl Origin {
    /// The module `spec` from here, ready for the pipeline.
    pub(crate) fn resolve(&self, spec: &ModuleSpec) -> Result<StageModule, String> {
        let (origin, entry, spirv): (String, &str, Arc<[u8]>) = match self {
            Origin::Builtin(language) => {
                let spirv = super::builtin::spirv(*language, spec.name)
                    .ok_or_else(|| format!("no built-in {} module {}", language.name(), spec.name))?;
                (language.name().into(), spec.entry_point(*language), spirv.into())
            }
            Origin::Disk(m) => {
                report_non_uniform(m);
                (m.path.display().to_string(), &m.entry, m.spirv.clone())
            }
            Origin::Missing(path) => {
                return Err(format!("no module {} ({} does not exist)", spec.name, path.display()));
            }
        };
        let entry = CString::new(entry).map_err(|_| format!("entry point of {} contains a NUL byte", spec.name))?;
        Ok(StageModule { spec: *spec, origin, entry, spirv })
    }
}
