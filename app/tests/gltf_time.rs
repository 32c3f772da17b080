//! Animated glTF models from the command line: `--time` poses a model's first animation for
//! every command that reads it.

use std::path::Path;
use twinray_host::scene::gltf::ASSIMP_TEST_MODELS as MODELS;
use twinray_tests::cli::{assert_bad_input, twinray};

/// `--time` reaches every command that reads a model: Khronos' morphed cube (installed by
/// `cargo xtask setup`) rendered and explained at 1.5 s says it is posed there, and a time
/// that is not one is refused in one line.
#[test]
fn a_model_is_posed_at_the_time_asked_for() {
    let model = Path::new(MODELS).join("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
    assert!(model.exists(), "{}: run `cargo xtask setup`", model.display());
    let model = model.to_str().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let small = ["--width", "16", "--height", "16"];
    let commands: [&[&str]; 2] =
        [&["render", model, "--out", "x.png"], &["explain", model, "--pixel", "8,8", "--b", "glsl"]];
    for command in commands {
        let out = twinray(&[&["--time", "1.5"][..], command, &small].concat(), dir.path());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{command:?}: {stderr}");
        assert!(stderr.contains("the first posed at 1.5 s"), "{command:?}: {stderr}");
    }
    for time in ["-1", "soon", "inf"] {
        assert_bad_input(&["render", model, &format!("--time={time}"), "--out", "x.png"], &["--time", "seconds"]);
    }
}
