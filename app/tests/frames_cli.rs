//! `render --frames` and `compare --frames` end to end on lavapipe with --validate: numbered
//! PNGs and an animated PNG, per-frame JSON, the worst frame, and bad ranges, modes and
//! animation files refused with exit code 2 and nothing written.

use twinray_tests::cli::{assert_bad_input, planted_glsl, twinray};

const SMALL: [&str; 4] = ["--width", "64", "--height", "48"];

#[test]
fn render_frames_writes_numbered_pngs_an_animated_png_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let args =
        [&["--validate", "render", "orbit", "--frames", "2..=4", "--out", "o.png", "--json"][..], &SMALL].concat();
    let out = twinray(&args, dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let frames = json["frames"].as_array().expect("frames");
    let indices: Vec<_> = frames.iter().map(|f| f["frame"].as_u64().unwrap()).collect();
    assert_eq!(indices, [2, 3, 4]);
    let work: Vec<_> = frames.iter().map(|f| f["as_work"].as_str().unwrap()).collect();
    assert_eq!(work, ["build", "update", "update"], "the first frame builds, then --tlas update refits");
    for f in frames {
        assert!(f["as_ms"].as_f64().is_some_and(|ms| ms >= 0.0) && f["trace_ms"].as_f64().is_some());
        assert_eq!(f["rays"]["primary"], 64 * 48 * 4, "2 x 2 samples per pixel");
    }
    assert_eq!(json["tlas"], "update (rebuild every 30)");
    for k in 2..=4 {
        assert!(dir.path().join(format!("o-{k:04}.png")).is_file(), "frame {k}");
    }
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(dir.path().join("o.png")).unwrap()));
    let reader = decoder.read_info().expect("a readable PNG");
    let control = reader.info().animation_control.expect("an animated PNG");
    assert_eq!(control.num_frames, 3);
}

#[test]
fn tlas_modes_name_their_work_per_frame() {
    let dir = tempfile::tempdir().unwrap();
    for (mode, every, expected) in [
        ("rebuild", "30", ["build", "build", "build"]),
        ("fast-build", "30", ["build", "build", "build"]),
        ("update", "2", ["build", "update", "build"]),
    ] {
        let flags = ["render", "swarm", "--frames", "0..3", "--tlas", mode, "--rebuild-every", every, "--json"];
        let out = twinray(&[&flags[..], &SMALL].concat(), dir.path());
        assert!(out.status.success(), "{mode}: {}", String::from_utf8_lossy(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let work: Vec<_> = json["frames"].as_array().unwrap().iter().map(|f| f["as_work"].clone()).collect();
        assert_eq!(work, expected, "{mode}");
    }
}

#[test]
fn compare_frames_judges_every_frame_and_names_the_worst() {
    let dir = tempfile::tempdir().unwrap();
    let args = [&["--validate", "compare", "orbit", "--frames", "0..2", "--runs", "1", "--warmup", "0"][..], &SMALL];
    let out = twinray(&[&args.concat()[..], &["--out-dir", "cmp", "--json"]].concat(), dir.path());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let frames = json["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 2);
    for key in ["as_ms", "trace_ms_a", "trace_ms_b", "rmse", "hit_mismatches", "pass", "rays_a"] {
        assert!(frames[0].get(key).is_some(), "missing {key}");
    }
    assert!(json["worst_frame"].as_u64().is_some_and(|w| w < 2));
    assert_eq!(out.status.success(), json["pass"] == true);
    for name in ["a.png", "b.png", "diff.png"] {
        assert!(dir.path().join("cmp").join(name).is_file(), "{name}");
    }
    let text = twinray(&[&args.concat()[..], &["--out-dir", "cmp"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&text.stdout);
    assert!(stdout.contains("worst frame") && stdout.contains("frames within"), "{stdout}");
}

/// Per frame, a compare names the pixels to explain, as a still compare does, each with its
/// `twinray explain --frame K` line: here B's miss stage shows half the background.
#[test]
fn compare_frames_names_pixels_to_explain_per_frame() {
    let dir = tempfile::tempdir().unwrap();
    let miss = planted_glsl(
        "miss.rmiss",
        ("payload.color = frame.background;", "payload.color = frame.background * 0.5;"),
        dir.path(),
    );
    let b = format!("glsl,miss={}", miss.display());
    let args = ["compare", "orbit", "--frames", "1..3", "--runs", "1", "--warmup", "0", "--a", "glsl", "--b", &b];
    let out = twinray(&[&args[..], &SMALL, &["--out-dir", "cmp", "--json"]].concat(), dir.path());
    assert_eq!(out.status.code(), Some(1), "the background differs: {}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    for (k, frame) in json["frames"].as_array().unwrap().iter().enumerate() {
        let pixels = frame["pixels"].as_array().unwrap();
        assert!(!pixels.is_empty(), "frame {k} names no pixel: {frame}");
        let line = pixels[0]["explain"].as_str().unwrap();
        assert!(
            line.starts_with("twinray explain orbit --pixel ") && line.ends_with(&format!(" --frame {}", k + 1)),
            "{line}"
        );
    }
    let text = twinray(&[&args[..], &SMALL, &["--out-dir", "cmp"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&text.stdout);
    assert!(stdout.contains("pixel ") && stdout.contains(" --frame 2"), "{stdout}");
}

#[test]
fn bad_frame_ranges_and_modes_are_refused() {
    assert_bad_input(&["render", "orbit", "--frames", "5..2"], &["--frames", "empty range"]);
    assert_bad_input(&["render", "orbit", "--frames", "soon"], &["--frames", "expected A..B"]);
    assert_bad_input(&["render", "orbit", "--frames", "40..60"], &["frames 40..60", "orbit has frames 0..48"]);
    assert_bad_input(&["render", "spheres", "--frames", "0..2"], &["a still scene has one frame"]);
    assert_bad_input(&["compare", "orbit", "--frames", "0..2", "--tlas", "sideways"], &["--tlas", "sideways"]);
}

#[test]
fn bad_animation_in_a_scene_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let text = include_str!("../../scenes/orbit.toml").replace("period = 1.0", "period = 0.0");
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, text).unwrap();
    let path = path.to_string_lossy().into_owned();
    assert_bad_input(&["render", &path, "--frames", "all"], &["animation.motions[3] (bounce).period"]);
    let text = include_str!("../../scenes/orbit.toml").replace("frames = 48", "frames = 0");
    std::fs::write(&path, text).unwrap();
    assert_bad_input(&["render", &path], &["animation.frames must be in 1..=100000 (got 0)"]);
}
