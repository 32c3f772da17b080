//! A folder of stage sources as a set: a Rust shader crate (a `Cargo.toml` depending on
//! `twinray-shared`), built by rust-gpu through the builder this binary carries, or a folder
//! of GLSL twins (`raygen.rgen` and its includes), built by glslang. The modules land in the
//! folder's `target/twinray/set/`, and nothing else of the folder is written; a folder whose
//! files have not changed since its last build is not built again.

use crate::builder::{self, NIGHTLY};
use crate::metadata::{metadata, package};
use crate::process::{output_within, Finished};
use crate::{postprocess, process::have, run_builder, Output};
use anyhow::{anyhow, bail, Context, Result};
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use twinray_shared::catalog::{Language, MODULES};
use twinray_shared::contract;

/// What kind of sources a folder holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sources {
    /// A Rust shader crate: a `Cargo.toml`.
    Crate,
    /// GLSL twins: a `raygen.rgen`.
    Glsl,
}

/// The kind of sources `dir` holds, if it holds any.
pub fn sources_in(dir: &Path) -> Option<Sources> {
    if dir.join("Cargo.toml").is_file() {
        Some(Sources::Crate)
    } else if dir.join("raygen.rgen").is_file() {
        Some(Sources::Glsl)
    } else {
        None
    }
}

/// How long a build may take, and whether an up-to-date one is built again.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// The deadline of the crate's compilation (the backend's first build has its own).
    pub timeout: Duration,
    pub force: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options { timeout: Duration::from_secs(20 * 60), force: false }
    }
}

/// A folder's built set.
#[derive(Debug)]
pub struct Built {
    /// The folder of modules, `NAME.spv` for each module the sources define.
    pub set: PathBuf,
    /// Whether it was built now (false: its sources had not changed).
    pub rebuilt: bool,
    /// The contract version the modules record.
    pub contract: String,
    pub modules: usize,
    pub seconds: f64,
}

/// Where a folder's build goes, under its `target/`.
pub fn set_dir(dir: &Path) -> PathBuf {
    dir.join("target/twinray/set")
}

/// Builds the set of the sources in `dir`, or finds it up to date. A crate that does not
/// compile has its compiler's errors printed to standard error as they were written.
pub fn build(dir: &Path, options: Options) -> Result<Built> {
    let start = Instant::now();
    let kind = sources_in(dir).ok_or_else(|| {
        anyhow!("{}: no shader sources (a folder of them holds a Cargo.toml or a raygen.rgen)", dir.display())
    })?;
    // glslang only for GLSL twins: a user of Rust stages needs SPIRV-Tools alone.
    let tools: &[&str] =
        if kind == Sources::Crate { &["spirv-val", "spirv-opt"] } else { &["glslangValidator", "spirv-val"] };
    require(tools)?;
    let version = match kind {
        Sources::Crate => crate_contract(dir)?,
        Sources::Glsl => glsl_contract(dir)?,
    };
    if let Some(refusal) = contract::refusal(&version) {
        bail!("{}: {refusal}", dir.display());
    }
    // One build of a folder at a time: two commands naming it at once take turns.
    std::fs::create_dir_all(dir.join("target/twinray"))?;
    let lock = std::fs::File::create(dir.join("target/twinray/build.lock"))?;
    lock.lock()?;
    let set = set_dir(dir);
    let stamp = dir.join("target/twinray/set.stamp");
    // The crate whose shared library is built for the CPU beside the modules: the folder's own,
    // or, for GLSL twins inside a crate, the crate's, whose shapes the twins draw.
    let cpu_crate = match kind {
        Sources::Crate => Some(dir),
        Sources::Glsl => dir.parent(),
    }
    .filter(|d| crate::cpu::has_shared(d));
    let mut hash = content_hash(dir, &version)?;
    if let Some(owner) = cpu_crate.filter(|d| *d != dir) {
        hash ^= content_hash(&owner.join(crate::cpu::SHARED_DIR), &version)?.rotate_left(1);
    }
    let hash = format!("{hash:016x}");
    let unchanged = std::fs::read_to_string(&stamp).is_ok_and(|s| s.trim() == hash) && set.is_dir();
    if unchanged && !options.force {
        let modules = count_modules(&set);
        return Ok(Built { set, rebuilt: false, contract: version, modules, seconds: start.elapsed().as_secs_f64() });
    }
    let _ = std::fs::remove_file(&stamp);
    let building = dir.join("target/twinray/building");
    if building.exists() {
        std::fs::remove_dir_all(&building)?;
    }
    std::fs::create_dir_all(&building)?;
    let names = match kind {
        Sources::Crate => compile_crate(dir, &building, options.timeout)?,
        Sources::Glsl => {
            crate::build_glsl(dir, &building, Output::OnFailure, 0)?;
            let mut names: Vec<String> = MODULES.iter().map(|m| m.name.to_string()).collect();
            names.extend(crate::build_own_glsl(dir, &building, Output::OnFailure)?);
            names
        }
    };
    if let Some(owner) = cpu_crate {
        crate::cpu::build(owner, &building, options.timeout)?;
    }
    let language = if kind == Sources::Crate { Language::Rust } else { Language::Glsl };
    // Any depth a crate may declare: the host checks the modules again for the one it declares.
    let depth = twinray_shared::interface::MAX_DECLARED_DEPTH;
    postprocess(&building, &names, language, (&format!("{}{version}", contract::RECORD_PREFIX), depth))?;
    if set.exists() {
        std::fs::remove_dir_all(&set)?;
    }
    std::fs::rename(&building, &set)?;
    std::fs::write(&stamp, &hash)?;
    let modules = names.len();
    Ok(Built { set, rebuilt: true, contract: version, modules, seconds: start.elapsed().as_secs_f64() })
}

/// Fails naming the first of `tools` that cannot be started, and the Debian packages.
fn require(tools: &[&str]) -> Result<()> {
    match tools.iter().find(|t| !have(t)) {
        Some(tool) => bail!("{tool} not found: install Debian's spirv-tools (and glslang-tools for GLSL twins)"),
        None => Ok(()),
    }
}

fn count_modules(set: &Path) -> usize {
    let files = std::fs::read_dir(set).into_iter().flatten().flatten();
    files.filter(|e| e.path().extension().is_some_and(|x| x == "spv")).count()
}

/// Compiles the crate in `dir` into `out` under `timeout`, and returns its entry points, each
/// a module of the catalog.
fn compile_crate(dir: &Path, out: &Path, timeout: Duration) -> Result<Vec<String>> {
    let builder = builder::embedded()?;
    // Absolute: spirv-builder takes a relative target folder as relative to the crate's own
    // `target/` (`twinray build mine` once built in `mine/target/mine/target/twinray/cargo`).
    let target = std::path::absolute(dir.join("target/twinray/cargo"))?;
    let mut command = run_builder(&builder, dir, out, &target, &[]);
    // A user's crate is not held to twinray's own rule: its warnings are shown, not fatal.
    command.env("TWINRAY_BUILDER_WARNINGS", "allow");
    let finished = output_within(&mut command, timeout)?;
    let Finished { status, stderr, .. } = finished;
    match status {
        None => bail!(
            "{}: the build did not finish within {} s and was stopped (--build-timeout sets the deadline)",
            dir.display(),
            timeout.as_secs()
        ),
        Some(s) if !s.success() => {
            // The compiler's words, as cargo printed them, then the one line of the error.
            eprint!("{}", compiler_words(&stderr));
            bail!("{}: the crate does not build (the compiler's errors are above)", dir.display())
        }
        Some(_) if stderr.contains("warning") => eprint!("{}", compiler_words(&stderr)),
        Some(_) => {}
    }
    entry_points(dir, out)
}

/// The compiler's errors and warnings in cargo's output, each block as cargo printed it,
/// without cargo's progress and summary lines and without two notes of rust-gpu that are no
/// fault of the crate (so that an error does not come after screens of them): that spirv-opt is off (twinray's builder turns it off), and that a slice should
/// replace `&RuntimeArray<T>`, which rust-gpu says of any unsized parameter, also of a struct
/// with a header that no slice can hold (the built-in stages' lights).
fn compiler_words(stderr: &str) -> String {
    const NOT_THE_CRATES: [&str; 2] = ["but was disabled by `--no-spirv-opt`", "use &[T] instead of &RuntimeArray<T>"];
    let progress = ["Compiling ", "Finished ", "Blocking ", "Updating ", "Locking ", "Downloaded ", "Downloading "];
    let summary = |l: &str| l.starts_with("warning: `") && l.contains(" generated ");
    let kept: Vec<&str> =
        stderr.lines().filter(|l| !progress.iter().any(|p| l.trim_start().starts_with(p)) && !summary(l)).collect();
    let text = kept.join("\n");
    let blocks = text.split("\n\n").filter(|block| {
        let first = block.trim_start().lines().next().unwrap_or_default();
        !block.trim().is_empty() && !NOT_THE_CRATES.iter().any(|n| first.contains(n))
    });
    blocks.map(|b| format!("{}\n\n", b.trim_end())).collect()
}

/// The modules rust-gpu wrote to `out`, each checked to be a module of the catalog.
fn entry_points(dir: &Path, out: &Path) -> Result<Vec<String>> {
    crate::name_modules_plainly(out).with_context(|| dir.display().to_string())?;
    let mut names = Vec::new();
    for entry in std::fs::read_dir(out)? {
        let path = entry?.path();
        let Some(name) = path.file_stem().map(|s| s.to_string_lossy().into_owned()) else { continue };
        if path.extension().is_some_and(|e| e == "spv") {
            // A crate with a shared library may add shapes and materials, whose intersection
            // and callable modules the host checks against what the library lists.
            let own = name.ends_with("_intersection") || name.ends_with("_material");
            let own = own && crate::cpu::has_shared(dir);
            if !own && !MODULES.iter().any(|m| m.name == name) {
                bail!(
                    "{}: entry point `{name}` is no module of twinray's catalog (twinray_shared::catalog names them all)",
                    dir.display()
                );
            }
            names.push(name);
        }
    }
    if names.is_empty() {
        bail!("{}: the crate has no stage entry points (no `#[spirv(...)]` stage function)", dir.display());
    }
    names.sort();
    Ok(names)
}

/// The version of `twinray-shared` the crate in `dir` depends on, by `cargo metadata`: read
/// from the dependency's own manifest where it is a path (nothing resolved, so nothing of the
/// crate is written, its lock file included), else from the crate's resolved graph.
fn crate_contract(dir: &Path) -> Result<String> {
    builder::ensure_toolchain()?;
    let root = package(dir)?;
    let dylib = root["targets"].as_array().is_some_and(|ts| {
        ts.iter().any(|t| t["crate_types"].as_array().is_some_and(|c| c.iter().any(|c| c == "dylib")))
    });
    if !dylib {
        bail!("{}: not a shader crate (rust-gpu builds a `crate-type = [\"dylib\"]` library)", dir.display());
    }
    let dependencies = root["dependencies"].as_array().cloned().unwrap_or_default();
    let Some(shared) = dependencies.iter().find(|d| d["name"] == "twinray-shared") else {
        bail!(
            "{}: the crate does not depend on twinray-shared, the contract its stages are read by (`twinray new` writes one that does)",
            dir.display()
        );
    };
    let version = match shared["path"].as_str() {
        Some(path) => package(Path::new(path))?["version"].as_str().map(str::to_string),
        None => {
            let resolved = metadata(dir, false)?;
            let packages = resolved["packages"].as_array().cloned().unwrap_or_default();
            packages
                .iter()
                .find(|p| p["name"] == "twinray-shared")
                .and_then(|p| p["version"].as_str().map(str::to_string))
        }
    };
    version.ok_or_else(|| anyhow!("{}: cargo names no version of twinray-shared", dir.display()))
}

/// The contract a GLSL folder was written for: the version its generated layout include names.
fn glsl_contract(dir: &Path) -> Result<String> {
    let include = dir.join("twinray_layout.glsl");
    let text = std::fs::read_to_string(&include)
        .with_context(|| format!("{}: the GLSL twins need twinray_layout.glsl", dir.display()))?;
    let first = text.lines().next().unwrap_or_default();
    first
        .split_whitespace()
        .skip_while(|w| *w != "twinray-shared")
        .nth(1)
        .map(str::to_string)
        .ok_or_else(|| anyhow!("{}: names no twinray-shared version in its first line", include.display()))
}

/// A hash of every file under `dir` but those in `target/` folders and hidden ones, with the builder's and the
/// contract's versions: equal hashes, the same modules.
fn content_hash(dir: &Path, version: &str) -> Result<u64> {
    let mut hasher = std::hash::DefaultHasher::new();
    (NIGHTLY, version, crate::starter::builder_sources()).hash(&mut hasher);
    for path in source_files(dir)? {
        path.hash(&mut hasher);
        std::fs::read(dir.join(&path)).with_context(|| format!("reading {}", path.display()))?.hash(&mut hasher);
    }
    Ok(hasher.finish())
}

/// The files of the sources in `dir` a build reads, relative to it, sorted: every file but
/// those in `target/` folders and hidden ones, and for a crate none of its GLSL twins (a set
/// of their own, whose edits do not rebuild the crate) and none of its `scenes/` and `probes/`
/// (what it is rendered and probed on, not built from).
pub fn source_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    collect(dir, dir, &mut files)?;
    if sources_in(dir) == Some(Sources::Crate) {
        let twin = |a: &Path| !a.as_os_str().is_empty() && dir.join(a).join("raygen.rgen").is_file();
        files.retain(|f| !f.ancestors().skip(1).any(twin));
        files.retain(|f| !f.starts_with("scenes") && !f.starts_with("probes"));
    }
    files.sort();
    Ok(files)
}

fn collect(root: &Path, dir: &Path, files: &mut Vec<PathBuf>) -> Result<()> {
    for entry in std::fs::read_dir(dir).with_context(|| format!("listing {}", dir.display()))? {
        let entry = entry?;
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if name.starts_with('.') || name == "target" {
            continue;
        }
        let path = entry.path();
        if entry.file_type()?.is_dir() {
            collect(root, &path, files)?;
        } else {
            files.push(path.strip_prefix(root).unwrap_or(&path).to_path_buf());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    /// What `twinray build` printed of a crate whose shared routine iterated an array by value:
    /// rust-gpu's notes on `&RuntimeArray<T>` about the starter's lights came first.
    const FAILED: &str = "   Compiling m2-shared v0.1.0 (/tmp/m2/shared)
   Compiling m2 v0.1.0 (/tmp/m2)
warning: use &[T] instead of &RuntimeArray<T>
   --> src/lib.rs:71:71
    |
 71 |     #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] lights: &RuntimeArray<Lights>,
    |                                                                       ^^^^^^^^^^^^^^^^^^^^

error: cannot cast between pointer types
   --> <shared/src/capsule.rs>:52:9
    |

warning: `m2` (lib) generated 3 warnings
error: could not compile `m2` (lib) due to 1 previous error; 3 warnings emitted
";

    #[test]
    fn a_failed_build_shows_the_crates_error_without_notes_that_are_not_its_fault() {
        let shown = super::compiler_words(FAILED);
        assert!(
            shown.starts_with("error: cannot cast between pointer types\n   --> <shared/src/capsule.rs>:52:9"),
            "{shown}"
        );
        assert!(
            !shown.contains("RuntimeArray") && !shown.contains("Compiling") && !shown.contains("generated 3"),
            "{shown}"
        );
        assert!(shown.contains("error: could not compile `m2`"), "{shown}");
    }
}
