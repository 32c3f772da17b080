//! The shape of the code, checked in the rust-analyzer "tidy" style by reading the sources:
//! the library's layers import only downwards (`docs/architecture.md`), no target of any crate
//! of the repository (its library, binaries, test harnesses, build script, fuzz targets)
//! imports a module back through others, and no source file of any crate is over 500 lines.

use std::collections::{BTreeMap, BTreeSet};
use twinray_tests::repo_root as repo;

mod crates;
use crates::{crate_dirs, crate_sources, targets};

/// The library's top-level modules from the bottom up; a module may import from its own layer
/// and the layers before it. The Vulkan layer is third: it sees only the error type and util.
const LAYERS: &[&str] =
    &["error", "util", "vk", "sets", "scene", "render", "reference", "probe", "explain", "compare", "fuzz"];

/// The app's library (`app/src/lib.rs`), in layers of its own above every layer of the render
/// library, which it names as the crate `twinray_host`.
const APP_LAYERS: &[&str] = &["bench", "crosscheck", "view"];

/// Longest source file, in lines.
const MAX_LINES: usize = 500;

type Module = Vec<String>;

/// The module a file defines: `a/b.rs` and `a/b/mod.rs` are `[a, b]`, `lib.rs` is `[]`.
fn module_of(file: &str) -> Module {
    let trimmed = file.trim_end_matches(".rs");
    let mut parts: Module = trimmed.split('/').map(String::from).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// The source with comments, strings and character literals blanked out.
fn code_only(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            let end = text[i + 2..].find("*/").map_or(b.len(), |e| i + 2 + e + 2);
            i = end;
            out.push(' ');
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if b[i] == b'\'' && i + 2 < b.len() && (b[i + 2] == b'\'' || b[i + 1] == b'\\') {
            // A character literal; a lifetime ('a) has no closing quote two bytes on.
            let end = text[i + 1..].find('\'').map_or(b.len(), |e| i + 1 + e + 1);
            i = end;
            out.push_str("' '");
        } else {
            out.push(b[i] as char);
            i += 1;
        }
    }
    out
}

/// Tokens: identifiers, `::`, and single punctuation characters.
fn tokens(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let chars: Vec<char> = code.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(chars[start..i].iter().collect());
        } else if c == ':' && chars.get(i + 1) == Some(&':') {
            out.push("::".into());
            i += 2;
        } else {
            if !c.is_whitespace() {
                out.push(c.to_string());
            }
            i += 1;
        }
    }
    out
}

/// The paths that follow `tokens[i]` (a path's first segment, already resolved to `base`):
/// `a::b::C`, and groups `a::{b::C, d}` expanded into one path each.
fn paths_from(tokens: &[String], mut i: usize, base: Module, out: &mut Vec<Module>) {
    let mut path = base;
    while tokens.get(i).map(String::as_str) == Some("::") {
        match tokens.get(i + 1).map(String::as_str) {
            Some("{") => {
                // Each item of the group starts a path from here.
                let mut depth = 0;
                let mut j = i + 1;
                let mut item_start = true;
                while j < tokens.len() {
                    match tokens[j].as_str() {
                        "{" => {
                            depth += 1;
                            item_start = depth == 1;
                        }
                        "}" => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        "," if depth == 1 => item_start = true,
                        word if depth == 1 && item_start => {
                            item_start = false;
                            if word == "self" {
                                out.push(path.clone());
                            } else if word != "*" {
                                let mut p = path.clone();
                                p.push(word.to_string());
                                let mut q = Vec::new();
                                paths_from(tokens, j + 1, p.clone(), &mut q);
                                out.extend(if q.is_empty() { vec![p] } else { q });
                            }
                        }
                        _ => {}
                    }
                    j += 1;
                }
                return;
            }
            Some(word) if word.chars().all(|c| c.is_alphanumeric() || c == '_') => {
                path.push(word.to_string());
                i += 2;
            }
            _ => break,
        }
    }
    out.push(path);
}

/// Every module path a file names: `crate::`, `super::` and its own child modules. Inline
/// modules (`mod tests { .. }`) are followed, so that their `super` is the file's module.
fn named_paths(file: &str, text: &str) -> Vec<Module> {
    let tokens = tokens(&code_only(text));
    let children: BTreeSet<&str> =
        tokens.windows(3).filter(|w| w[0] == "mod" && w[2] == ";").map(|w| w[1].as_str()).collect();
    // The module at each point: the file's, or an inline module's, with the depth it opened at.
    let mut scopes: Vec<(Module, usize)> = vec![(module_of(file), 0)];
    let mut depth = 0;
    let mut out = Vec::new();
    for (i, t) in tokens.iter().enumerate() {
        match t.as_str() {
            "{" => {
                depth += 1;
                if i >= 2 && tokens[i - 2] == "mod" {
                    let mut inner = scopes.last().map(|s| s.0.clone()).unwrap_or_default();
                    inner.push(tokens[i - 1].clone());
                    scopes.push((inner, depth));
                }
                continue;
            }
            "}" => {
                if scopes.len() > 1 && scopes.last().is_some_and(|s| s.1 == depth) {
                    scopes.pop();
                }
                depth = depth.saturating_sub(1);
                continue;
            }
            _ => {}
        }
        let after_path = i > 0 && (tokens[i - 1] == "::" || tokens[i - 1] == ".");
        if after_path || tokens.get(i + 1).map(String::as_str) != Some("::") {
            continue;
        }
        let here = scopes.last().map(|s| s.0.clone()).unwrap_or_default();
        let (base, from) = match t.as_str() {
            "crate" => (Vec::new(), i + 1),
            "super" => {
                let mut base = here;
                base.pop();
                let mut j = i;
                // super::super:: climbs one more level each time.
                while tokens.get(j + 2).map(String::as_str) == Some("super") {
                    base.pop();
                    j += 2;
                }
                (base, j + 1)
            }
            word if children.contains(word) && scopes.len() == 1 => {
                let mut base = here;
                base.push(word.to_string());
                (base, i + 1)
            }
            _ => continue,
        };
        paths_from(&tokens, from, base, &mut out);
    }
    out
}

/// The file a path lands in: the longest prefix of it that is a module of `files`.
fn resolve<'a>(path: &Module, modules: &'a BTreeMap<Module, String>) -> Option<&'a String> {
    (0..=path.len()).rev().find_map(|n| modules.get(&path[..n].to_vec()))
}

/// Edges file -> file of the imports of a crate's sources.
fn graph(files: &BTreeMap<String, String>) -> BTreeMap<String, BTreeSet<String>> {
    let modules: BTreeMap<Module, String> = files.keys().map(|f| (module_of(f), f.clone())).collect();
    files
        .iter()
        .map(|(file, text)| {
            // A file's unit tests may reach back into its parents (`super::super::x`): they are
            // not part of the module's dependencies, so they are left out.
            let code = text.split("#[cfg(test)]\nmod tests").next().unwrap_or(text);
            let targets = named_paths(file, code)
                .iter()
                .filter_map(|p| resolve(p, &modules))
                .filter(|t| *t != file)
                .cloned()
                .collect();
            (file.clone(), targets)
        })
        .collect()
}

/// Imports from a layer above the importing file's own.
fn upward_imports(edges: &BTreeMap<String, BTreeSet<String>>, layers: &[&str]) -> Vec<String> {
    let rank = |file: &str| {
        let top = module_of(file).first().cloned().unwrap_or_default();
        layers.iter().position(|l| *l == top)
    };
    let mut bad = Vec::new();
    for (from, targets) in edges {
        if module_of(from).is_empty() {
            continue; // lib.rs declares and re-exports every layer
        }
        let Some(own) = rank(from) else {
            bad.push(format!("{from}: its top-level module is in no layer (add it to LAYERS and the docs)"));
            continue;
        };
        for to in targets {
            if rank(to).is_some_and(|r| r > own) {
                bad.push(format!("{from} imports {to}, a layer above it"));
            } else if module_of(to).is_empty() {
                // The root re-exports every layer's public face: through it, a module could
                // name anything, so it names the layer's own module instead.
                bad.push(format!("{from} imports through {to}, the crate root: name the layer's module"));
            }
        }
    }
    bad
}

/// Every import cycle, as the files of each strongly connected component (Tarjan).
fn cycles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        found: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        for w in s.edges.get(v).into_iter().flatten() {
            if !s.index.contains_key(w.as_str()) {
                visit(s, w);
                let low = s.low[v].min(s.low[w.as_str()]);
                s.low.insert(v, low);
            } else if s.stack.contains(&w.as_str()) {
                let low = s.low[v].min(s.index[w.as_str()]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                component.push(w.to_string());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                s.found.push(component);
            }
        }
    }
    let mut s = State { edges, index: BTreeMap::new(), low: BTreeMap::new(), stack: Vec::new(), found: Vec::new() };
    for v in edges.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    s.found
}

/// The files of the library target of the crate in `dir`.
fn library_of(dir: &str) -> BTreeMap<String, String> {
    targets(&repo().join(dir))
        .into_iter()
        .find(|(root, _)| root == "src/lib.rs")
        .map(|(_, files)| files)
        .unwrap_or_else(|| panic!("{dir}/src/lib.rs is a target"))
}

#[test]
fn layers_import_only_downwards() {
    for (dir, layers) in [("host", LAYERS), ("app", APP_LAYERS)] {
        let bad = upward_imports(&graph(&library_of(dir)), layers);
        assert!(bad.is_empty(), "imports against the layer order in {dir} (docs/architecture.md):\n{}", bad.join("\n"));
    }
}

#[test]
fn no_import_cycles_in_any_crate() {
    let mut checked = 0;
    let mut found = Vec::new();
    for dir in crate_dirs() {
        for (root, files) in targets(&repo().join(&dir)) {
            checked += files.len();
            found.extend(cycles(&graph(&files)).into_iter().map(|c| format!("{dir}/{root}: {c:?}")));
        }
    }
    assert!(checked > 300, "only {checked} files found in the crates: is the walk right?");
    assert!(found.is_empty(), "import cycles (file names are module paths of each target):\n{}", found.join("\n"));
}

#[test]
fn every_layer_exists_and_is_a_module_of_its_library() {
    let doc = std::fs::read_to_string(repo().join("docs/architecture.md")).unwrap();
    for (dir, layers) in [("host", LAYERS), ("app", APP_LAYERS)] {
        let lib = std::fs::read_to_string(repo().join(dir).join("src/lib.rs")).unwrap();
        for layer in layers {
            assert!(lib.contains(&format!("pub mod {layer};")), "{dir}/src/lib.rs does not declare the layer {layer}");
            assert!(doc.contains(&format!("`{layer}")), "docs/architecture.md does not describe {layer}");
        }
    }
}

#[test]
fn the_checks_catch_what_they_are_for() {
    let files = |list: &[(&str, &str)]| list.iter().map(|(f, t)| (f.to_string(), t.to_string())).collect();
    // A cycle through a parent's re-export, a `super` path and a group import.
    let cyclic = files(&[
        ("a/mod.rs", "mod x; mod y; pub use x::Thing;"),
        ("a/x.rs", "use super::y::{Other, self};"),
        ("a/y.rs", "// crate::b::Z in a comment is no import\nfn f() -> crate::a::Thing { todo!() }"),
        ("b.rs", "const S: &str = \"crate::a::x\";"),
    ]);
    assert_eq!(cycles(&graph(&cyclic)), vec![vec!["a/mod.rs", "a/x.rs", "a/y.rs"]]);
    let acyclic =
        files(&[("a/mod.rs", "mod x;"), ("a/x.rs", "use crate::b::{c::D, E};"), ("b/mod.rs", ""), ("b/c.rs", "")]);
    let edges = graph(&acyclic);
    assert!(cycles(&edges).is_empty());
    assert_eq!(edges["a/x.rs"], ["b/c.rs", "b/mod.rs"].iter().map(|s| s.to_string()).collect());
    // The Vulkan layer naming a scene type, and a module in no layer.
    let upward = files(&[("vk/accel.rs", "use crate::scene::Aabb;"), ("scene/mod.rs", ""), ("extra.rs", "")]);
    let bad = upward_imports(&graph(&upward), LAYERS);
    assert!(bad.iter().any(|b| b.contains("vk/accel.rs imports scene/mod.rs")), "{bad:?}");
    assert!(bad.iter().any(|b| b.contains("extra.rs: its top-level module is in no layer")), "{bad:?}");
    // The error type named through the crate root's re-export.
    let root = files(&[
        ("lib.rs", "pub mod error; pub use error::Error;"),
        ("error.rs", ""),
        ("vk/a.rs", "fn f() -> crate::Error { todo!() }"),
    ]);
    let bad = upward_imports(&graph(&root), LAYERS);
    assert!(bad.iter().any(|b| b.contains("vk/a.rs imports through lib.rs")), "{bad:?}");
}

#[test]
fn no_source_file_is_over_500_lines() {
    let mut long = Vec::new();
    for dir in crate_dirs() {
        for (file, text) in crate_sources(&repo().join(&dir)) {
            let lines = text.lines().count();
            if lines > MAX_LINES {
                long.push(format!("{dir}/{file} ({lines} lines)"));
            }
        }
    }
    let mut glsl = vec![repo().join("shaders-glsl")];
    while let Some(dir) = glsl.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                glsl.push(path);
                continue;
            }
            let lines = std::fs::read_to_string(&path).map(|t| t.lines().count()).unwrap_or(0);
            if lines > MAX_LINES {
                long.push(format!("{} ({lines} lines)", path.display()));
            }
        }
    }
    assert!(long.is_empty(), "files over {MAX_LINES} lines; split them by responsibility: {long:?}");
}
