//! Generates the tables the host embeds, so that none is kept by hand: the SPIR-V of every
//! module of the catalog (`twinray_shared::catalog::MODULES`) in both languages, from
//! `spirv/`, every scene file of `scenes/` with the mesh files of `scenes/meshes/`, and every
//! probe case of `probes/`.

use std::fmt::Write;
use std::path::{Path, PathBuf};
use twinray_shared::catalog::{Language, MODULES};

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    for watched in ["spirv", "scenes", "probes"] {
        println!("cargo:rerun-if-changed={}", root.join(watched).display());
    }
    write(&out.join("embedded_spirv.rs"), &embedded_spirv(&root));
    write(&out.join("builtin_scenes.rs"), &builtin_scenes(&root));
    write(&out.join("builtin_probes.rs"), &builtin_probes(&root));
}

fn write(path: &Path, text: &str) {
    if let Err(e) = std::fs::write(path, text) {
        panic!("writing {}: {e}", path.display());
    }
}

fn embedded_spirv(root: &Path) -> String {
    let mut code = String::from("/// (language, module, SPIR-V) of every module of the catalog.\n");
    code.push_str("pub(crate) static EMBEDDED: &[(Language, &str, &[u8])] = &[\n");
    for spec in MODULES {
        for language in Language::ALL {
            let path = root.join(spec.spirv_path(language));
            if !path.is_file() {
                panic!("{} is missing: run `cargo xtask shaders` to build the modules of the catalog", path.display());
            }
            let _ = writeln!(code, "    (Language::{language:?}, {:?}, include_bytes!({:?})),", spec.name, path);
        }
    }
    code.push_str("];\n");
    code
}

/// Files of `dir` with extension `ext`, sorted by name.
fn files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("listing {}: {e}", dir.display()));
    let mut list: Vec<PathBuf> =
        entries.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|x| x == ext)).collect();
    list.sort();
    list
}

/// Every probe case of probes/ and its folders, by its path there without `.toml`
/// (`far-sphere`, `stability/sphere-far-1e5`).
fn builtin_probes(root: &Path) -> String {
    let mut code =
        String::from("/// Probe cases shipped inside the binary, by their path in probes/ without `.toml`.\n");
    code.push_str("pub const BUILTIN_PROBES: &[(&str, &str)] = &[\n");
    let probes = root.join("probes");
    let mut folders = vec![probes.clone()];
    folders.extend(std::fs::read_dir(&probes).into_iter().flatten().flatten().map(|e| e.path()).filter(|p| p.is_dir()));
    folders.sort();
    for folder in folders {
        for path in files(&folder, "toml") {
            let relative = path.strip_prefix(&probes).unwrap_or(&path).with_extension("");
            let name = relative.to_string_lossy().replace('\\', "/");
            let _ = writeln!(code, "    ({name:?}, include_str!({path:?})),");
        }
    }
    code.push_str("];\n");
    code
}

fn builtin_scenes(root: &Path) -> String {
    let mut code = String::from("/// Scenes shipped inside the binary, by name: every file of scenes/.\n");
    code.push_str("pub const BUILTIN: &[(&str, &str)] = &[\n");
    for path in files(&root.join("scenes"), "toml") {
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let _ = writeln!(code, "    ({name:?}, include_str!({path:?})),");
    }
    code.push_str(
        "];\n\n/// Mesh files the built-in scenes use, by the path they name: every file of scenes/meshes/.\n",
    );
    code.push_str("pub const BUILTIN_MESH_FILES: &[(&str, &str)] = &[\n");
    for path in files(&root.join("scenes/meshes"), "obj") {
        let name = path.file_name().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let _ = writeln!(code, "    (\"meshes/{name}\", include_str!({path:?})),");
    }
    code.push_str("];\n");
    code
}
