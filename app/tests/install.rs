//! What `cargo install --path app` gives: a `twinray` that works from any directory (its
//! shaders, built-in scenes and probe cases are inside it), from a package that carries them.

use std::process::Command;

#[test]
fn the_binary_renders_a_builtin_scene_from_a_foreign_directory() {
    let elsewhere = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_twinray"))
        .args(["render", "spheres", "--shaders", "glsl", "--width", "32", "--height", "32", "--out", "s.png"])
        .current_dir(elsewhere.path())
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{said}{}", String::from_utf8_lossy(&out.stdout));
    assert!(elsewhere.path().join("s.png").is_file());
}

#[test]
fn the_package_carries_the_shaders_scenes_probes_and_readme() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args(["package", "--list", "--allow-dirty", "-p", "twinray-host"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let list = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let files = ["README.md", "build.rs", "spirv/rust/raygen.spv", "spirv/glsl/raygen.spv", "scenes/spheres.toml"];
    let probes = ["probes/far-sphere.toml", "probes/stability/sphere-far-1e5.toml"];
    for file in files.iter().chain(&probes) {
        assert!(list.lines().any(|l| l == *file), "the package lacks {file}:\n{list}");
    }
}
