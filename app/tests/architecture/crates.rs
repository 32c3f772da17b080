//! Every crate of the repository and every build target in it, found from the files alone:
//! a folder with a Cargo.toml is a crate, and a file no other declares as a module is a
//! target's root, so a new crate, binary or test harness is checked without a list to update.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use twinray_tests::repo_root as repo;

/// Every `.rs` file under `dir`, by its path relative to `dir`.
pub fn sources(dir: &Path) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path.strip_prefix(dir).unwrap().to_string_lossy().replace('\\', "/");
                out.insert(relative, std::fs::read_to_string(&path).unwrap());
            }
        }
    }
    out
}

/// Folders no crate's sources are in: build outputs, git's, and the fuzzers' corpora.
fn skipped(dir: &Path) -> bool {
    let name = dir.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    name == "target" || name.starts_with('.') || name == "corpus"
}

/// Every crate folder of the repository (each folder with a Cargo.toml, the workspace's
/// members and the crates it excludes alike), relative to the root.
pub fn crate_dirs() -> Vec<String> {
    let root = repo();
    let mut out = Vec::new();
    let mut stack = vec![root.clone()];
    while let Some(d) = stack.pop() {
        if d.join("Cargo.toml").is_file() && d != root {
            out.push(d.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/"));
        }
        for entry in std::fs::read_dir(&d).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() && !skipped(&path) {
                stack.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The `.rs` files of the crate in `dir`, by path relative to it, without those of crates
/// nested in it.
pub fn crate_sources(dir: &Path) -> BTreeMap<String, String> {
    let nested: Vec<String> = crate_dirs()
        .iter()
        .map(|c| repo().join(c))
        .filter(|c| c != dir && c.starts_with(dir))
        .map(|c| c.strip_prefix(dir).unwrap().to_string_lossy().replace('\\', "/") + "/")
        .collect();
    sources(dir)
        .into_iter()
        .filter(|(f, _)| !nested.iter().any(|n| f.starts_with(n.as_str())) && !f.split('/').any(|p| p == "target"))
        .collect()
}

/// The files a file declares as its modules (`mod x;`, `#[path = ".."] mod x;`), by name and
/// path relative to the crate folder. `root` says whether the file's children sit beside it
/// (a crate root or a `mod.rs`) or in a folder named after it.
fn declared(file: &str, text: &str, root: bool, files: &BTreeMap<String, String>) -> Vec<(String, String)> {
    let here = file.rsplit_once('/').map_or(String::new(), |(d, _)| format!("{d}/"));
    let folder = if root || file == "mod.rs" || file.ends_with("/mod.rs") {
        here.clone()
    } else {
        format!("{}/", file.trim_end_matches(".rs"))
    };
    let mut path_attr: Option<String> = None;
    let mut out = Vec::new();
    for line in text.lines().map(str::trim) {
        if let Some(rest) = line.strip_prefix("#[path = \"") {
            path_attr = rest.split('"').next().map(|p| format!("{here}{p}"));
            continue;
        }
        let decl = line.strip_prefix("pub(crate) ").or_else(|| line.strip_prefix("pub ")).unwrap_or(line);
        if let Some(name) = decl.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
            let candidates = [format!("{folder}{name}.rs"), format!("{folder}{name}/mod.rs")];
            let found = path_attr.take().or_else(|| candidates.into_iter().find(|c| files.contains_key(c)));
            if let Some(found) = found {
                out.push((name.to_string(), found));
            }
        } else if !line.starts_with("#[") {
            path_attr = None;
        }
    }
    out
}

/// Every build target of the crate in `dir` (each file no other declares as a module is a
/// root: `lib.rs`, `main.rs`, a test harness, a fuzz target, `build.rs`), with the files its
/// `mod` declarations reach, each named as `graph` reads a module path: `a/b.rs` for
/// `crate::a::b`, `lib.rs` for the root.
pub fn targets(dir: &Path) -> Vec<(String, BTreeMap<String, String>)> {
    let files = crate_sources(dir);
    let is_root = |f: &str, children: &BTreeSet<String>| !children.contains(f);
    let mut children = BTreeSet::new();
    for (file, text) in &files {
        // A file's children are found as a root's or a module's; either way they are children.
        for root in [true, false] {
            children.extend(declared(file, text, root, &files).into_iter().map(|(_, f)| f));
        }
    }
    let mut out = Vec::new();
    for root in files.keys().filter(|f| is_root(f, &children)) {
        let mut named = BTreeMap::new();
        let mut queue = vec![(root.clone(), Vec::<String>::new())];
        while let Some((file, module)) = queue.pop() {
            let Some(text) = files.get(&file) else { continue };
            for (name, child) in declared(&file, text, module.is_empty(), &files) {
                let mut m = module.clone();
                m.push(name);
                queue.push((child, m));
            }
            let key = if module.is_empty() { "lib.rs".to_string() } else { module.join("/") + ".rs" };
            named.insert(key, text.clone());
        }
        out.push((root.clone(), named));
    }
    out
}
