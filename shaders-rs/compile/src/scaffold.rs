//! `twinray new DIR --shape NAME` and `--material NAME`: a shape or material of the crate's
//! own, added to a starter crate or any shader crate. A shape: its module in the crate's shared
//! library (`shared/`: the GPU routine and, on the CPU, its keys, primitives and f64
//! definition), its intersection stage in `src/`, its GLSL twin where the crate has `glsl/`,
//! and a scene and a probe case that render and probe it as written. A material: its module in
//! `shared/` (the GPU colour and, on the CPU, its keys and parameters), its callable stage in
//! `src/`, its GLSL twin, and a scene. Every file is checked before any is written, and none
//! of a user's is overwritten; the crate's `lib.rs` files gain a line each, at the lines the
//! starter marks.

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

const SHARED_MANIFEST: &str = include_str!("../starter/shared/Cargo.toml");
const SHARED_LIB: &str = include_str!("../starter/shared/src/lib.rs");
const SHAPE_SHARED: &str = include_str!("../starter/shape/shared.rs");
const SHAPE_STAGE: &str = include_str!("../starter/shape/stage.rs");
const SHAPE_TWIN: &str = include_str!("../starter/shape/twin.rint");
const SHAPE_SCENE: &str = include_str!("../starter/shape/scene.toml");
const SHAPE_PROBE: &str = include_str!("../starter/shape/probe.toml");
const MATERIAL_SHARED: &str = include_str!("../starter/material/shared.rs");
const MATERIAL_STAGE: &str = include_str!("../starter/material/stage.rs");
const MATERIAL_TWIN: &str = include_str!("../starter/material/twin.rcall");
const MATERIAL_SCENE: &str = include_str!("../starter/material/scene.toml");

/// The line of `shared/src/lib.rs` after which a shape's or material's `pub mod` goes.
const MODULES_MARK: &str = "// The shapes' ";
/// The line of `shared/src/lib.rs` before which a shape's `SHAPE` joins the list.
const LIST_MARK: &str = "    // The shapes (";
/// The line of `shared/src/lib.rs` before which a material's `MATERIAL` joins the list.
const MATERIALS_MARK: &str = "    // The materials (";
/// The list of materials, for a crate made before materials could be added.
const MATERIALS_LIST: &str = "
/// The materials scenes may name (`kind = \"NAME\"`), which twinray reads from the CPU build.
#[cfg(not(target_arch = \"spirv\"))]
pub const MATERIALS: &[twinray_shared::custom::CustomMaterial] = &[
    // The materials (`twinray new . --material NAME` adds each before this line).
];
";

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
    check_name("shape", shape)?;
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
    let item = Item { what: "shape", name: shape, list: LIST_MARK, constant: "SHAPE", stage: "intersection stage" };
    changed.extend(add_item(dir, files, &item)?);
    Ok((changed, hit_kind))
}

/// Adds the material `material` to the shader crate in `dir` (see the module comment).
/// Returns the files written or changed, relative to `dir`.
pub fn add_material(dir: &Path, material: &str) -> Result<Vec<PathBuf>> {
    check_name("material", material)?;
    let name = package_name(dir)?;
    let mut changed = ensure_shared(dir, &name)?;
    let shared_crate = package_name(&dir.join("shared"))?.replace('-', "_");
    let fill = |text: &str| text.replace("{material}", material).replace("{shared}", &shared_crate);
    let mut files = vec![
        (PathBuf::from(format!("shared/src/{material}.rs")), fill(MATERIAL_SHARED)),
        (PathBuf::from(format!("src/{material}.rs")), fill(MATERIAL_STAGE)),
        (PathBuf::from(format!("scenes/{material}.toml")), fill(MATERIAL_SCENE)),
    ];
    if dir.join("glsl/raygen.rgen").is_file() {
        files.push((PathBuf::from(format!("glsl/{material}_material.rcall")), fill(MATERIAL_TWIN)));
    }
    let item = Item { what: "material", name: material, list: MATERIALS_MARK, constant: "MATERIAL", stage: "callable" };
    changed.extend(add_item(dir, files, &item)?);
    Ok(changed)
}

/// A shape or material being added: what it is, its name, the marked line of its list in
/// `shared/src/lib.rs`, the constant of its module that joins the list, and its stage kind.
struct Item<'a> {
    what: &'static str,
    name: &'a str,
    list: &'static str,
    constant: &'static str,
    stage: &'static str,
}

/// Writes `files` of `item` and lists it in both `lib.rs` files of the crate in `dir`, once
/// every file is known to be new and every marked line found; returns the paths written.
fn add_item(dir: &Path, mut files: Vec<(PathBuf, String)>, item: &Item) -> Result<Vec<PathBuf>> {
    let Item { what, name, .. } = *item;
    for (path, _) in &files {
        if dir.join(path).exists() {
            bail!("{} exists: the crate has a {what} {name:?} already (nothing was written)", dir.join(path).display());
        }
    }
    let lib_path = dir.join("shared/src/lib.rs");
    let lib = std::fs::read_to_string(&lib_path).with_context(|| format!("reading {}", lib_path.display()))?;
    let lib = with_listed(&lib, item).with_context(|| lib_path.display().to_string())?;
    let stages_path = dir.join("src/lib.rs");
    let stages = std::fs::read_to_string(&stages_path).with_context(|| format!("reading {}", stages_path.display()))?;
    let stages =
        format!("{}\n/// The {} of the crate's own {what} `{name}`.\npub mod {name};\n", stages.trim_end(), item.stage);
    files.push(("shared/src/lib.rs".into(), lib));
    files.push(("src/lib.rs".into(), stages));
    write_all(dir, &files)
}

/// A shape's or material's (`what`) name: a Rust identifier and a scene kind, none of
/// twinray's own.
fn check_name(what: &str, name: &str) -> Result<()> {
    let well_formed = name.starts_with(|c: char| c.is_ascii_lowercase())
        && name.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        && name.len() <= 48;
    if !well_formed {
        bail!("{name:?} cannot name a {what}: lower-case letters, digits and _, a letter first");
    }
    const RUST_WORDS: [&str; 12] =
        ["as", "crate", "fn", "impl", "in", "loop", "mod", "move", "ref", "self", "type", "use"];
    let shapes = twinray_shared::shapes::SHAPES.iter().flat_map(|s| s.spec.kinds.iter().map(|k| k.name));
    let mut builtin = shapes.chain(["mesh", "gltf"]).chain(twinray_shared::custom::BUILTIN_MATERIALS);
    if builtin.any(|k| k == name) || ["shared", "lib"].contains(&name) || RUST_WORDS.contains(&name) {
        bail!(
            "{name:?} is taken (a shape or material kind of twinray's, a file of the crate or a word of Rust): \
             choose another name"
        );
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

/// `lib` with the module of `item` after [`MODULES_MARK`] and its constant before its list's
/// marked line (a list of materials added first where the crate has none).
fn with_listed(lib: &str, item: &Item) -> Result<String> {
    let Item { name, constant, .. } = *item;
    let line_after = |text: &str, mark: &str| {
        let at = text.find(mark)?;
        Some(at + text[at..].find('\n')? + 1)
    };
    let Some(modules) = line_after(lib, MODULES_MARK) else {
        bail!("no line `{MODULES_MARK}...` to add `pub mod {name};` after: add it and `{name}::{constant}` to its list by hand");
    };
    let mut text = format!("{}pub mod {name};\n{}", &lib[..modules], &lib[modules..]);
    if item.list == MATERIALS_MARK && !text.contains("pub const MATERIALS") {
        text = format!("{}\n{MATERIALS_LIST}", text.trim_end());
    }
    let Some(list) = text.find(item.list) else {
        bail!("no line `{}...` to add `{name}::{constant},` before", item.list.trim());
    };
    Ok(format!("{}    {name}::{constant},\n{}", &text[..list], &text[list..]))
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
