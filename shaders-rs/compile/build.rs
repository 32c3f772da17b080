//! Embeds the sources a `twinray` binary needs where there is no checkout: the Rust stages and
//! `twinray-shared` that `twinray new` writes into a starter crate, the GLSL twins of its
//! `--glsl` folder, and the rust-gpu builder that `twinray build` compiles once per machine.
//! Each tree is listed whole (no hand-kept file list): a new source file is carried at once.

use std::fmt::Write;
use std::path::{Path, PathBuf};

/// (name of the table, folder relative to the repository root, files or folders under it).
const TREES: [(&str, &str, &[&str]); 4] = [
    ("STAGES", "shaders-rs/stages", &["Cargo.toml", "Cargo.lock", "rust-toolchain.toml", "src"]),
    ("SHARED", "shaders-rs/shared", &["Cargo.toml", "README.md", "src"]),
    ("BUILDER", "shaders-rs/builder", &["Cargo.toml", "Cargo.lock", "rust-toolchain.toml", "src"]),
    ("GLSL", "shaders-glsl", &["."]),
];

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let root = manifest.join("../..");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let mut code = String::new();
    for (name, dir, parts) in TREES {
        let base = root.join(dir);
        let mut files = Vec::new();
        for part in parts {
            let path = base.join(part);
            println!("cargo:rerun-if-changed={}", path.display());
            collect(&path, &mut files);
        }
        files.sort();
        let _ =
            writeln!(code, "/// Every file of `{dir}/` a starter crate or the builder needs: (path under it, bytes).");
        let _ = writeln!(code, "pub static {name}: &[(&str, &[u8])] = &[");
        for file in files {
            let relative = file.strip_prefix(&base).expect("collected under its base");
            let relative = relative.strip_prefix(".").unwrap_or(relative);
            let _ = writeln!(code, "    ({:?}, include_bytes!({:?})),", relative.display().to_string(), file);
        }
        code.push_str("];\n");
    }
    if let Err(e) = std::fs::write(out.join("embedded_sources.rs"), code) {
        panic!("writing the embedded sources: {e}");
    }
}

/// Every file under `path` (or `path` itself), leaving out build outputs and hidden files.
fn collect(path: &Path, files: &mut Vec<PathBuf>) {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    if name == "target" || (name.starts_with('.') && name != ".") {
        return;
    }
    if path.is_file() {
        files.push(path.to_path_buf());
        return;
    }
    let entries = std::fs::read_dir(path).unwrap_or_else(|e| panic!("listing {}: {e}", path.display()));
    for entry in entries.flatten() {
        collect(&entry.path(), files);
    }
}
