//! The GLSL set reads the layout the Rust set does: the committed include is exactly what
//! twinray-shared generates (its own tests check each field against std140/std430 rules).

use twinray_tests::repo_root;

#[test]
fn committed_glsl_layout_include_is_generated_from_twinray_shared() {
    let want = twinray_shared::glsl::layout_include().expect("every shared struct has a valid GLSL mirror");
    let path = repo_root().join("shaders-glsl/twinray_layout.glsl");
    let have = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(have == want, "{} is stale: run `cargo xtask shaders`", path.display());
}

#[test]
fn committed_shape_dispatch_is_generated_from_the_registry() {
    let path = repo_root().join("shaders-glsl/shape_dispatch.glsl");
    let have = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        have == twinray_shared::glsl::shape_dispatch_include(),
        "{} is stale: run `cargo xtask shaders`",
        path.display()
    );
}

#[test]
fn glsl_sources_include_the_generated_layout() {
    use twinray_shared::catalog::GlslSource;
    let dir = repo_root().join("shaders-glsl");
    for spec in twinray_shared::catalog::MODULES {
        let (file, text) = match spec.glsl {
            GlslSource::File(file) | GlslSource::Variant { file, .. } => {
                (file.to_string(), std::fs::read_to_string(dir.join(file)))
            }
            // A shape's stage is generated around its file, which must include the layout itself.
            GlslSource::Shape { shape, .. } => {
                let file = format!("shapes/{shape}.glsl");
                let text = std::fs::read_to_string(dir.join(&file));
                (file, text)
            }
        };
        let text = text.unwrap_or_else(|e| panic!("{file}: {e}"));
        assert!(text.contains("#include \"twinray_layout.glsl\""), "{file} does not include the layout");
    }
}

#[test]
fn every_registered_shape_has_its_glsl_twin_and_nothing_else_is_in_shapes() {
    let dir = repo_root().join("shaders-glsl/shapes");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let mut want: Vec<String> = twinray_shared::shapes::SHAPES.iter().map(|s| format!("{}.glsl", s.name)).collect();
    want.sort();
    assert_eq!(files, want, "shaders-glsl/shapes/ holds one twin per registered shape");
}
