//! Animated glTF models from the command line: `--time` poses a model's animations for
//! every command that reads it, and `--frames` plays them from there at `--fps`.

use std::path::Path;
use twinray_host::scene::gltf::ASSIMP_TEST_MODELS as MODELS;
use twinray_tests::cli::{assert_bad_input, twinray};

/// `--time` reaches every command that reads a model: Khronos' morphed cube (installed by
/// `cargo xtask setup`) rendered and explained at 1.5 s is not what it is at 0 s, and a time
/// that is not one is refused in one line.
#[test]
fn a_model_is_posed_at_the_time_asked_for() {
    let model = cube();
    let dir = tempfile::tempdir().unwrap();
    let small = ["--width", "16", "--height", "16"];
    let commands: [&[&str]; 2] =
        [&["render", &model, "--out", "x.png"], &["explain", &model, "--pixel", "8,8", "--b", "glsl"]];
    for command in commands {
        let at = |time: &str| {
            let out = twinray(&[&["--time", time][..], command, &small].concat(), dir.path());
            assert!(out.status.success(), "{command:?}: {}", String::from_utf8_lossy(&out.stderr));
            let png = std::fs::read(dir.path().join("x.png")).unwrap_or_default();
            (String::from_utf8_lossy(&out.stdout).into_owned(), png)
        };
        assert_ne!(at("0"), at("1.5"), "{command:?}: the same at 0 s and 1.5 s");
    }
    for time in ["-1", "soon", "inf"] {
        assert_bad_input(&["render", &model, &format!("--time={time}"), "--out", "x.png"], &["--time", "seconds"]);
    }
}

/// With `--frames`, a model plays from `--time` at `--fps` to its last key (4.17 s): from 1.5 s
/// at 2 frames a second, frames at 1.5, 2, 2.5, 3, 3.5 and 4 s, each written; a rate that is
/// not one is refused, and `animate-bench` takes the model as it is. From past its last key it
/// is a still, whose one frame is at the time asked for.
#[test]
fn a_model_plays_from_its_time_at_its_rate() {
    let model = cube();
    let dir = tempfile::tempdir().unwrap();
    let args = ["--time", "1.5", "--fps", "2", "render", &model, "--frames", "all", "--width", "16", "--height", "16"];
    let out = twinray(&[&args[..], &["--out", "cube.png"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // The frame table's rows: frame number, then time.
    let rows = stdout.lines().filter(|l| l.split_whitespace().next().is_some_and(|f| f.parse::<u32>().is_ok()));
    let times: Vec<&str> = rows.filter_map(|l| l.split_whitespace().nth(1)).collect();
    assert_eq!(times, ["1.500", "2.000", "2.500", "3.000", "3.500", "4.000"], "{stdout}");
    assert!(dir.path().join("cube-0005.png").exists() && !dir.path().join("cube-0006.png").exists());
    for fps in ["0", "-2", "fast", "1001"] {
        assert_bad_input(
            &["render", &model, &format!("--fps={fps}"), "--frames", "all"],
            &["--fps", "frames per second"],
        );
    }
    assert_bad_input(&["animate-bench", &model, "--instances", "10"], &["--instances", "glTF"]);
    // Past its last key the model is a still at that time: one frame, shown at 5 s.
    let args = ["--time", "5", "render", &model, "--frames", "all", "--width", "16", "--height", "16", "--json"];
    let out = twinray(&[&args[..], &["--out", "still.png"]].concat(), dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("render --frames --json prints JSON");
    let times: Vec<f64> = json["frames"].as_array().unwrap().iter().filter_map(|f| f["time"].as_f64()).collect();
    assert_eq!(times, [5.0], "{json}");
}

fn cube() -> String {
    let model = Path::new(MODELS).join("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
    assert!(model.exists(), "{}: run `cargo xtask setup`", model.display());
    model.to_str().unwrap().to_string()
}
