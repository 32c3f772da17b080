//! `cargo xtask new-shape NAME`: scaffolds a procedural shape in both languages — its module
//! in `twinray-shared` (a placeholder robust intersection, its scene kind and CPU tests), its
//! line in the registry, its Rust intersection stage, its GLSL twin and a built-in scene —
//! then builds the shaders and
//! compares the scene's renders with both sets. The placeholder is a sphere, so everything
//! passes from the start; the user then writes the shape's own math in both languages.

use crate::process::{cargo, repo_root};
use anyhow::{bail, Context, Result};
use std::path::Path;

const REGISTRY: &str = "shaders-rs/shared/src/shapes/mod.rs";
const SHAPE_TEMPLATE: &str = include_str!("../templates/shape.rs.in");
const GLSL_TEMPLATE: &str = include_str!("../templates/shape.glsl.in");
const SCENE_TEMPLATE: &str = include_str!("../templates/scene.toml.in");
/// Where the shapes' Rust intersection stages are, each written out.
const STAGES: &str = "shaders-rs/stages/src/intersection.rs";
const STAGE_TEMPLATE: &str = include_str!("../templates/intersection.rs.in");

/// Words a shape cannot be called: Rust keywords (its module), the registry's own modules and
/// the host's own kind.
const RESERVED: &[&str] = &[
    "as", "async", "await", "box", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern", "false",
    "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "self", "static", "struct", "super", "trait", "true", "try", "type", "unsafe", "use", "where", "while", "yield",
    "spec", "mesh", "main",
];

/// The files a new shape `name` adds, relative to the repository root.
pub fn added_files(name: &str) -> [String; 3] {
    [
        format!("shaders-rs/shared/src/shapes/{name}.rs"),
        format!("shaders-glsl/shapes/{name}.glsl"),
        format!("scenes/{name}.toml"),
    ]
}

pub fn run(name: &str) -> Result<()> {
    let root = repo_root();
    check_name(name, &root)?;
    let registry_path = root.join(REGISTRY);
    let registry = std::fs::read_to_string(&registry_path).with_context(|| format!("reading {REGISTRY}"))?;
    let (registry, hit_kind) = register(&registry, name)?;
    let stages_path = root.join(STAGES);
    let stages = std::fs::read_to_string(&stages_path).with_context(|| format!("reading {STAGES}"))?;
    let stages = with_stage(&stages, name)?;
    let [rust, glsl, scene] = added_files(name);
    let fill = |template: &str| {
        let capital = name[..1].to_uppercase() + &name[1..];
        template.replace("__UPPER__", &name.to_uppercase()).replace("__CAPITAL__", &capital).replace("__NAME__", name)
    };
    for (path, text) in [(&rust, fill(SHAPE_TEMPLATE)), (&glsl, fill(GLSL_TEMPLATE)), (&scene, fill(SCENE_TEMPLATE))] {
        std::fs::write(root.join(path), text).with_context(|| format!("writing {path}"))?;
        println!("new-shape: wrote {path}");
    }
    std::fs::write(&registry_path, registry).with_context(|| format!("writing {REGISTRY}"))?;
    println!("new-shape: registered {name} in {REGISTRY} (hit kind {hit_kind})");
    std::fs::write(&stages_path, stages).with_context(|| format!("writing {STAGES}"))?;
    println!("new-shape: wrote its stage {name}_intersection in {STAGES}");
    // A fresh cargo for each: this xtask was compiled before the registry had the shape.
    cargo(&["xtask", "shaders"], &[]).context("building the shaders with the new shape")?;
    let out = root.join("target/new-shape").join(name);
    let out = out.to_string_lossy();
    // Built with cargo's progress shown (the host has the new shape), then run quietly.
    cargo(&["build", "--release", "-p", "twinray"], &[])?;
    // The verdict is the check here, so the sets are timed in one placement, not six: on
    // lavapipe the default timing took most of the compare's time.
    let compare = ["compare", name, "--out-dir", &out, "--placements", "1"];
    cargo(&[&["run", "--release", "--quiet", "-p", "twinray", "--"][..], &compare].concat(), &[])
        .with_context(|| format!("comparing the Rust and GLSL renders of scene {name}"))?;
    println!(
        "\nnew-shape: {name} renders alike with both sets. Next:\n\
         - write its intersection in {rust} (robust forms: docs/numerics.md) and its twin in {glsl};\n\
         - set its scene keys and primitive in SHAPE (same file), and its scene in {scene};\n\
         - `cargo xtask watch {name}` rebuilds and compares both sets on every save;\n\
         - `cargo xtask golden {name}` writes its golden images; review them, then `cargo xtask ci`;\n\
         - to probe it against the f64 reference, add its distance to TRACED in host/src/reference/traced.rs;\n\
         - the guide's tutorial, docs/tutorial.md, takes a capsule through all of this."
    );
    Ok(())
}

fn check_name(name: &str, root: &Path) -> Result<()> {
    let mut chars = name.chars();
    let valid = chars.next().is_some_and(|c| c.is_ascii_lowercase())
        && chars.all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    if !valid || name.ends_with('_') || name.contains("__") {
        bail!("shape name {name:?}: use lowercase letters, digits and single underscores, starting with a letter");
    }
    if RESERVED.contains(&name) {
        bail!("shape name {name:?} is reserved (a Rust keyword or a name twinray uses); pick another");
    }
    if twinray_shared::shapes::shape(name).is_some() || twinray_shared::shapes::kind(name).is_some() {
        bail!("a shape or scene kind called {name:?} is already registered");
    }
    for path in added_files(name) {
        if root.join(&path).exists() {
            bail!("{path} already exists; remove it or pick another name");
        }
    }
    Ok(())
}

/// The intersection stages of `stages` with NAME's appended: its routine, bound and hit kind
/// reported as every built-in shape's are.
fn with_stage(stages: &str, name: &str) -> Result<String> {
    if stages.contains(&format!("pub fn {name}_intersection(")) {
        bail!("{STAGES} already has a stage {name}_intersection; remove it or pick another name");
    }
    Ok(format!("{}\n{}", stages.trim_end(), STAGE_TEMPLATE.replace("__NAME__", name)))
}

/// The registry with `pub mod NAME;` and NAME's line added, and the hit kind it gets (one more
/// than the largest so far).
fn register(registry: &str, name: &str) -> Result<(String, u32)> {
    let lines: Vec<&str> = registry.lines().collect();
    // `"name" => module (kind): entry;`, and no other line that starts with a quote.
    let is_entry = |l: &str| l.trim_start().starts_with('"') && l.contains("=>") && l.trim_end().ends_with(';');
    let entries: Vec<usize> = (0..lines.len()).filter(|&i| is_entry(lines[i])).collect();
    let (Some(&last_entry), Some(last_mod)) = (entries.last(), lines.iter().rposition(|l| l.starts_with("pub mod ")))
    else {
        bail!("{REGISTRY}: cannot find the registry lines of procedural_shapes! and the module list");
    };
    let hit_kind = entries
        .iter()
        .filter_map(|&i| lines[i].split_once('(').and_then(|(_, rest)| rest.split_once(')')))
        .filter_map(|(kind, _)| kind.trim().parse::<u32>().ok())
        .max()
        .unwrap_or(0)
        + 1;
    let indent: String = lines[last_entry].chars().take_while(|c| c.is_whitespace()).collect();
    let entry = format!("{indent}\"{name}\" => {name} ({hit_kind}): {name}_intersection;");
    let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    out.insert(last_entry + 1, entry);
    out.insert(last_mod + 1, format!("pub mod {name};"));
    Ok((out.join("\n") + "\n", hit_kind))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registers_after_the_last_line_with_the_next_hit_kind() {
        let registry = std::fs::read_to_string(repo_root().join(REGISTRY)).unwrap();
        let (out, kind) = register(&registry, "capsule").unwrap();
        let max = twinray_shared::shapes::SHAPES.iter().map(|s| s.hit_kind).max().unwrap();
        assert_eq!(kind, max + 1);
        assert!(out.contains(&format!("\"capsule\" => capsule ({kind}): capsule_intersection;\n")), "{out}");
        assert!(out.contains("pub mod capsule;\n"));
        assert_eq!(out.lines().count(), registry.lines().count() + 2);
        // A string that rustfmt wraps onto its own line later in the file is no entry.
        let wrapped = format!("{registry}fn f() {{\n    g(\n        \"| `x` | a long row |\".into(),\n    );\n}}\n");
        let (out, _) = register(&wrapped, "capsule").unwrap();
        let at = |needle: &str| out.find(needle).unwrap();
        assert!(at("\"capsule\" =>") < at("fn f()"), "{out}");
    }

    #[test]
    fn a_new_shapes_stage_is_written_as_the_built_in_ones_are() {
        let stages = std::fs::read_to_string(repo_root().join(STAGES)).unwrap();
        // The template is the sphere's stage, with the sphere's name: no drift between them.
        let sphere = STAGE_TEMPLATE.replace("__NAME__", "sphere");
        assert!(stages.contains(sphere.trim()), "{STAGES} no longer holds its template's form:\n{sphere}");
        let out = with_stage(&stages, "capsule").unwrap();
        assert!(out.starts_with(stages.trim_end()) && out.contains("pub fn capsule_intersection("));
        assert!(out.contains("shapes::capsule::bound(&p)") && out.contains("shapes::capsule::intersect(ray.origin"));
        assert!(out.contains("report(hit, &ray, t_max, hit_kind::capsule, normal);"));
        assert!(with_stage(&stages, "sphere").is_err(), "the sphere's stage is there already");
    }

    #[test]
    fn refuses_bad_reserved_and_taken_names() {
        let root = repo_root();
        for bad in ["Capsule", "2d", "cap-sule", "cap__sule", "box", "mesh", "sphere", "sphere_field", "rectangle", ""]
        {
            assert!(check_name(bad, &root).is_err(), "{bad:?} accepted");
        }
        assert!(check_name("not_a_shape_yet", &root).is_ok());
    }
}
