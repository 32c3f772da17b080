//! Generates the tables the host embeds, so that none is kept by hand: the SPIR-V of every
//! module of the catalog (`twinray_shared::catalog::MODULES`) in both languages, from
//! `spirv/`, and every scene file of `scenes/` with the mesh files of `scenes/meshes/`.

use std::fmt::Write;
use std::path::{Path, PathBuf};
use twinray_shared::catalog::{Language, MODULES};

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    for watched in ["spirv", "scenes"] {
        println!("cargo:rerun-if-changed={}", root.join(watched).display());
    }
    write(&out.join("embedded_spirv.rs"), &embedded_spirv(&root));
    write(&out.join("builtin_scenes.rs"), &builtin_scenes(&root));
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
