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
fn glsl_sources_include_the_generated_layout() {
    let dir = repo_root().join("shaders-glsl");
    for spec in twinray_shared::catalog::MODULES {
        let text = std::fs::read_to_string(dir.join(spec.glsl_source)).expect("GLSL source exists");
        assert!(text.contains("#include \"twinray_layout.glsl\""), "{} does not include the layout", spec.glsl_source);
    }
}
