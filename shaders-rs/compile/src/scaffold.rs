//! `twinray new DIR --shape NAME`: a shape of the crate's own, added to a starter crate or any
//! shader crate: its module in the crate's shared library (`shared/`: the GPU routine and, on
//! the CPU, its keys, primitives and f64 definition), its intersection stage in `src/`, its
//! GLSL twin where the crate has `glsl/`, and a scene and a probe case that render and probe it
//! as written. Every file is checked before any is written, and none of a user's is
//! overwritten; the crate's `lib.rs` files gain one line each, at the lines the starter marks.

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

const SHARED_MANIFEST: &str = include_str!("../starter/shared/Cargo.toml");
const SHARED_LIB: &str = include_str!("../starter/shared/src/lib.rs");
const SHAPE_SHARED: &str = include_str!("../starter/shape/shared.rs");
const SHAPE_STAGE: &str = include_str!("../starter/shape/stage.rs");
const SHAPE_TWIN: &str = include_str!("../starter/shape/twin.rint");
const SHAPE_SCENE: &str = include_str!("../starter/shape/scene.toml");
const SHAPE_PROBE: &str = include_str!("../starter/shape/probe.toml");

/// The line of `shared/src/lib.rs` after which a shape's `pub mod` goes.
const MODULES_MARK: &str = "// The shapes' modules";
/// The line of `shared/src/lib.rs` before which a shape's `SHAPE` joins the list.
const LIST_MARK: &str = "    // The shapes (";

/// Hit kinds a crate's shapes report (`twinray_shared::custom`).
const HIT_KINDS: std::ops::RangeInclusive<u32> =
    twinray_shared::custom::FIRST_HIT_KIND..=twinray_shared::custom::LAST_HIT_KIND;

/// Gives the crate `name` in `dir` a shared library (`shared/`) where it has none: the folder,
/// and the crate's manifest and lock file naming it. Returns the files written or changed.
pub fn ensure_shared(dir: &Path, name: &str) -> Result<Vec<PathBuf>> {
    if dir.join("shared/Cargo.toml").exists() {
        return Ok(Vec::new());
    }
    let shared = format!("{name}-shared");
    let manifest_path = dir.join("Cargo.toml");
    let manifest =
        std::fs::read_to_string(&manifest_path).with_context(|| format!("reading {}", manifest_path.display()))?;
    let manifest = with_shared_dependency(&manifest, &shared).with_context(|| manifest_path.display().to_string())?;
    let lock_path = dir.join("Cargo.lock");
    let lock = match std::fs::read_to_string(&lock_path) {
        Ok(text) => Some(with_locked_shared(&text, name, &shared)?),
        Err(_) => None,
    };
    let mut written = vec![(PathBuf::from("Cargo.toml"), manifest)];
    written.extend(lock.map(|l| (PathBuf::from("Cargo.lock"), l)));
    written.push(("shared/Cargo.toml".into(), SHARED_MANIFEST.replace("{name}", name)));
    written.push(("shared/src/lib.rs".into(), SHARED_LIB.to_string()));
    write_all(dir, &written)
}

/// Adds the shape `shape` to the shader crate in `dir` (see the module comment). Returns the
/// files written or changed, relative to `dir`, and the hit kind the shape reports.
pub fn add_shape(dir: &Path, shape: &str) -> Result<(Vec<PathBuf>, u32)> {
    check_shape_name(shape)?;
    let name = package_name(dir)?;
    let mut changed = ensure_shared(dir, &name)?;
    let shared_package = package_name(&dir.join("shared"))?;
    let shared_crate = shared_package.replace('-', "_");
    let hit_kind = next_hit_kind(&dir.join("shared/src"))?;
    let fill = |text: &str| {
        text.replace("{shape}", shape).replace("{hit_kind}", &hit_kind.to_string()).replace("{shared}", &shared_crate)
    };
    let mut files = vec![
        (PathBuf::from(format!("shared/src/{shape}.rs")), fill(SHAPE_SHARED)),
        (PathBuf::from(format!("src/{shape}.rs")), fill(SHAPE_STAGE)),
        (PathBuf::from(format!("scenes/{shape}.toml")), fill(SHAPE_SCENE)),
        (PathBuf::from(format!("probes/{shape}.toml")), fill(SHAPE_PROBE)),
    ];
    if dir.join("glsl/raygen.rgen").is_file() {
        files.push((PathBuf::from(format!("glsl/{shape}_intersection.rint")), fill(SHAPE_TWIN)));
    }
    for (path, _) in &files {
        if dir.join(path).exists() {
            bail!("{} exists: the crate has a shape {shape:?} already (nothing was written)", dir.join(path).display());
        }
    }
    let lib_path = dir.join("shared/src/lib.rs");
    let lib = std::fs::read_to_string(&lib_path).with_context(|| format!("reading {}", lib_path.display()))?;
    let lib = with_listed_shape(&lib, shape).with_context(|| lib_path.display().to_string())?;
    let stages_path = dir.join("src/lib.rs");
    let stages = std::fs::read_to_string(&stages_path).with_context(|| format!("reading {}", stages_path.display()))?;
    let stages = format!(
        "{}\n/// The intersection stage of the crate's own shape `{shape}`.\npub mod {shape};\n",
        stages.trim_end()
    );
    files.push(("shared/src/lib.rs".into(), lib));
    files.push(("src/lib.rs".into(), stages));
    changed.extend(write_all(dir, &files)?);
    Ok((changed, hit_kind))
}

/// A shape's name: a Rust identifier and a scene kind, none of twinray's own.
fn check_shape_name(shape: &str) -> Result<()> {
    let well_formed = shape.starts_with(|c: char| c.is_ascii_lowercase())
        && shape.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        && shape.len() <= 48;
    if !well_formed {
        bail!("{shape:?} cannot name a shape: lower-case letters, digits and _, a letter first");
    }
    const RUST_WORDS: [&str; 12] =
        ["as", "crate", "fn", "impl", "in", "loop", "mod", "move", "ref", "self", "type", "use"];
    let builtin = twinray_shared::shapes::SHAPES.iter().flat_map(|s| s.spec.kinds.iter().map(|k| k.name));
    if builtin.chain(["mesh", "gltf", "shared", "lib"]).any(|k| k == shape) || RUST_WORDS.contains(&shape) {
        bail!("{shape:?} is taken (a shape kind of twinray's, a file of the crate or a word of Rust): choose another name");
    }
    Ok(())
}

/// The package name in `dir/Cargo.toml`: the first `name = "..."` of its `[package]` table.
fn package_name(dir: &Path) -> Result<String> {
    let path = dir.join("Cargo.toml");
    let text = std::fs::read_to_string(&path).with_context(|| {
        format!("{}: no shader crate here (no Cargo.toml; `twinray new DIR` writes one)", dir.display())
    })?;
    let package = text.split("[package]").nth(1).unwrap_or_default();
    let name = package.lines().find_map(|l| l.trim().strip_prefix("name = \"")?.strip_suffix('"'));
    name.map(str::to_string).with_context(|| format!("{}: no package name", path.display()))
}

/// The first hit kind no shape module in `src` claims (`pub const HIT_KIND: u32 = N;`).
fn next_hit_kind(src: &Path) -> Result<u32> {
    let mut taken = Vec::new();
    for entry in std::fs::read_dir(src).with_context(|| format!("listing {}", src.display()))? {
        let text = std::fs::read_to_string(entry?.path()).unwrap_or_default();
        let claimed = text.lines().filter_map(|l| l.trim().strip_prefix("pub const HIT_KIND: u32 = "));
        taken.extend(claimed.filter_map(|v| v.trim_end_matches(';').trim().parse::<u32>().ok()));
    }
    HIT_KINDS.clone().find(|k| !taken.contains(k)).with_context(|| {
        format!("{}: every hit kind a crate's shape may report ({HIT_KINDS:?}) is taken", src.display())
    })
}

/// The crate's manifest naming its shared library `shared` as a dependency (and keeping it out
/// of the crate's workspace, as the contract's copy is).
fn with_shared_dependency(manifest: &str, shared: &str) -> Result<String> {
    let Some(at) = manifest.find("\ntwinray-shared = ") else {
        bail!("no `twinray-shared = ...` dependency line to add `{shared} = {{ path = \"shared\" }}` after");
    };
    let end = at + 1 + manifest[at + 1..].find('\n').unwrap_or(manifest.len() - at - 1);
    let mut text = format!("{}\n{shared} = {{ path = \"shared\" }}{}", &manifest[..end], &manifest[end..]);
    if let Some(at) = text.find("exclude = [\"twinray-shared\"") {
        text.insert_str(at + "exclude = [".len(), "\"shared\", ");
    }
    Ok(text)
}

/// The crate's lock file with its shared library locked (a path package: no network), every
/// package in cargo's order, so that a build does not rewrite it.
fn with_locked_shared(lock: &str, name: &str, shared: &str) -> Result<String> {
    let root = format!("[[package]]\nname = \"{name}\"\n");
    let Some(at) = lock.find(&root) else { bail!("Cargo.lock: no package {name:?}") };
    let list = at + lock[at..].find("dependencies = [\n").context("Cargo.lock: the crate has no dependencies")?;
    let list = list + "dependencies = [\n".len();
    let entry = format!(" \"{shared}\",\n");
    let mut text = format!("{}{entry}{}", &lock[..list], &lock[list..]);
    let end = list + text[list..].find(']').context("Cargo.lock: an unclosed list")?;
    let mut names: Vec<&str> = text[list..end].lines().collect();
    names.sort();
    let sorted = names.iter().map(|l| format!("{l}\n")).collect::<String>();
    text.replace_range(list..end, &sorted);
    text.push_str(&format!(
        "\n[[package]]\nname = \"{shared}\"\nversion = \"0.1.0\"\ndependencies = [\n \"spirv-std\",\n \"twinray-shared\",\n]\n"
    ));
    Ok(sorted_lock(&text))
}

/// A lock file's packages in cargo's order (by name, then version), as cargo writes them.
pub(crate) fn sorted_lock(text: &str) -> String {
    let mut parts: Vec<&str> = text.split("[[package]]\n").collect();
    let header = parts.remove(0);
    let key = |block: &&str| -> (String, String) {
        let field = |f: &str| block.lines().find_map(|l| l.strip_prefix(f)).unwrap_or_default().to_string();
        (field("name = "), field("version = "))
    };
    parts.sort_by_key(key);
    let mut out = header.to_string();
    for part in parts {
        out.push_str("[[package]]\n");
        out.push_str(part);
        if !out.ends_with("\n\n") {
            out.push('\n');
        }
    }
    format!("{}\n", out.trim_end())
}

/// `lib` with the module of `shape` after [`MODULES_MARK`] and its `SHAPE` before [`LIST_MARK`].
fn with_listed_shape(lib: &str, shape: &str) -> Result<String> {
    let line_after = |text: &str, mark: &str| {
        let at = text.find(mark)?;
        Some(at + text[at..].find('\n')? + 1)
    };
    let Some(modules) = line_after(lib, MODULES_MARK) else {
        bail!("no line `{MODULES_MARK} ...` to add `pub mod {shape};` after: add it and `{shape}::SHAPE` to SHAPES by hand");
    };
    let text = format!("{}pub mod {shape};\n{}", &lib[..modules], &lib[modules..]);
    let Some(list) = text.find(LIST_MARK) else {
        bail!("no line `{}...` in SHAPES to add `{shape}::SHAPE,` before", LIST_MARK.trim());
    };
    Ok(format!("{}    {shape}::SHAPE,\n{}", &text[..list], &text[list..]))
}

/// Writes each (path under `dir`, text), making folders; returns the paths.
fn write_all(dir: &Path, files: &[(PathBuf, String)]) -> Result<Vec<PathBuf>> {
    for (path, text) in files {
        let full = dir.join(path);
        if let Some(parent) = full.parent() {
            std::fs::create_dir_all(parent).with_context(|| format!("creating {}", parent.display()))?;
        }
        std::fs::write(&full, text).with_context(|| format!("writing {}", full.display()))?;
    }
    Ok(files.iter().map(|(p, _)| p.clone()).collect())
}

#[cfg(test)]
mod tests;
