//! docs/scene-format.md stays true: its complete example loads and renders, and every kind
//! that `twinray scenes` lists is documented there and used by some built-in scene.

use twinray_host::scene::{file::kinds, MeshFiles, Scene, BUILTIN};
use twinray_host::RenderOptions;
use twinray_tests::{repo_root, set, validated_context};

fn format_doc() -> String {
    std::fs::read_to_string(repo_root().join("docs/scene-format.md")).expect("docs/scene-format.md")
}

/// The first TOML block after the heading `heading`.
fn toml_block<'a>(doc: &'a str, heading: &str) -> &'a str {
    let section = doc.find(heading).unwrap_or_else(|| panic!("no {heading:?} in the docs"));
    let start = section + doc[section..].find("```toml\n").expect("a toml example") + "```toml\n".len();
    let end = start + doc[start..].find("```").expect("the example's end");
    &doc[start..end]
}

#[test]
fn the_documented_example_loads_and_renders() {
    let doc = format_doc();
    let example = toml_block(&doc, "## A complete example");
    let scene = Scene::parse(example, "docs/scene-format.md", MeshFiles::Folder(repo_root().join("scenes")))
        .unwrap_or_else(|e| panic!("the documented example does not load: {e}"));
    let ctx = validated_context();
    let opts = RenderOptions::once(64, 36, 0, 1);
    let out = twinray_host::render(&ctx, &scene, &set("rust"), &opts).expect("the documented example renders");
    assert!(twinray_host::compare::hit_count(&out) > 0);
}

/// The animation the docs show, appended to the complete example, loads, moves what it says.
#[test]
fn the_documented_animation_loads_with_the_example() {
    let doc = format_doc();
    let text = format!("{}\n{}", toml_block(&doc, "## A complete example"), toml_block(&doc, "## Animation"));
    let scene = Scene::parse(&text, "docs/scene-format.md", MeshFiles::Folder(repo_root().join("scenes")))
        .unwrap_or_else(|e| panic!("the documented animation does not load: {e}"));
    assert_eq!(scene.frame_count(), 48);
    let (first, later) = (scene.at_frame(0).unwrap(), scene.at_frame(12).unwrap());
    assert_ne!(first.file.objects[1].translate, later.file.objects[1].translate, "the sphere bounces");
    assert_ne!(first.file.camera.eye, later.file.camera.eye, "the camera rises");
}

#[test]
fn every_kind_is_documented_and_used_by_a_builtin_scene() {
    let doc = format_doc();
    let scenes: String = BUILTIN.iter().map(|(_, text)| *text).collect();
    for (section, kinds) in kinds() {
        for kind in kinds.iter().filter(|k| !k.starts_with('(')) {
            assert!(
                doc.contains(&format!("`{kind}`")) || doc.contains(&format!("\"{kind}\"")),
                "{section} kind {kind} is not documented"
            );
            // Built-in scenes are embedded in the binary and read no model files; the glTF
            // shape is tested on assimp's models (tests/assimp.rs) instead.
            if *kind == "gltf" {
                continue;
            }
            let used =
                scenes.contains(&format!("kind = \"{kind}\"")) || scenes.contains(&format!("builtin = \"{kind}\""));
            assert!(used, "{section} kind {kind} is used by no built-in scene");
        }
    }
    assert!(scenes.contains("file = \""), "no built-in scene loads an OBJ file");
}

#[test]
fn the_shape_table_is_the_one_the_registry_generates() {
    let doc = format_doc();
    let generated = twinray_shared::shapes::with_docs_table(&doc).expect("the shape table's markers");
    assert!(generated == doc, "docs/scene-format.md's shape table is stale: run `cargo xtask shaders`");
}
