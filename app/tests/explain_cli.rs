//! `twinray explain` on planted differences, reached as a user reaches it: `compare` names the
//! pixels that differ and prints their explain lines; each line, run, must name the sample and
//! the stage that carries the planted difference. And bad input gets one line and exit 2.

use serde_json::Value;
use std::path::Path;
use twinray_tests::cli::{assert_bad_input, naive_sphere, planted_glsl, planted_include, twinray, UNTIMED};
use twinray_tests::repo_root as repo;

/// `compare --json` of `scene` (with `extra` arguments) between `a` and `b`: the pixels it names.
fn named_pixels(scene: &str, extra: &[&str], (a, b): (&str, &str), dir: &Path) -> Vec<Value> {
    let out_dir = dir.join("compare");
    let out_dir = out_dir.to_str().unwrap();
    let args = [&["compare", scene, "--a", a, "--b", b], extra, &UNTIMED].concat();
    let out = twinray(&[&args[..], &["--out-dir", out_dir, "--json"]].concat(), dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let json: Value = serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("{e}: {stdout}"));
    json["pixels"].as_array().unwrap().clone()
}

/// Runs a pixel's explain line (with validation, as JSON): the report.
fn run_explain_line(pixel: &Value, dir: &Path) -> Value {
    let line = pixel["explain"].as_str().unwrap();
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(words[..2], ["twinray", "explain"], "{line}");
    let args = [&["--validate"], &words[1..], &["--json"]].concat();
    let out = twinray(&args, dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{line}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("{e}: {stdout}"))
}

/// Every pixel `compare` names is explained at a ray of its first sample (the scenes here take
/// one) by `stage`, and set A is not blamed.
fn assert_explained(pixels: &[Value], stage: &str, dir: &Path) {
    assert!(!pixels.is_empty(), "compare named no pixel");
    for pixel in pixels {
        let report = run_explain_line(pixel, dir);
        let parting = &report["parting"];
        let named = parting["stage"].as_str().unwrap_or_else(|| panic!("no stage named: {parting}"));
        assert!(named.starts_with("set B's "), "{named}: {parting}");
        assert!(named.contains(stage), "{named} is not {stage}: {parting}");
        assert_eq!(parting["sample"], 0, "{parting}");
    }
}

#[test]
fn the_naive_sphere_formula_is_explained_at_the_ray_it_gets_wrong() {
    let dir = tempfile::tempdir().unwrap();
    let scene = repo().join("tests/bisect/far-sphere.toml").to_string_lossy().into_owned();
    let pixels = named_pixels(&scene, &[], ("rust", &naive_sphere()), dir.path());
    assert_eq!(pixels.len(), 6, "3 largest differences and 3 hit mismatches: {pixels:?}");
    assert!(pixels.iter().any(|p| p["hit_mismatch"] == true));
    assert_explained(&pixels, "sphere_intersection", dir.path());
}

#[test]
fn a_miss_stage_with_another_background_is_explained_at_a_missing_ray() {
    let dir = tempfile::tempdir().unwrap();
    let edit = ("payload.color = frame.background;", "payload.color = frame.background * 0.5;");
    let b = format!("glsl,miss={}", planted_glsl("miss.rmiss", edit, dir.path()).display());
    let pixels = named_pixels("cutout", &["--width", "64", "--height", "48"], ("glsl", &b), dir.path());
    assert_explained(&pixels, "miss", dir.path());
    let report = run_explain_line(&pixels[0], dir.path());
    let text = report["parting"]["text"].as_str().unwrap();
    assert!(text.contains("the scene's background is (0.300000, 0.300000, 0.300000)"), "{text}");
}

#[test]
fn an_any_hit_stage_that_fills_the_holes_is_explained_at_a_ray_through_one() {
    let dir = tempfile::tempdir().unwrap();
    let spv = planted_glsl("cutout.rahit", ("ignoreIntersectionEXT;", ""), dir.path());
    let b = format!("glsl,cutout_any_hit={}", spv.display());
    let pixels = named_pixels("cutout", &["--width", "64", "--height", "48"], ("glsl", &b), dir.path());
    assert_explained(&pixels, "cutout_any_hit", dir.path());
}

/// A ray generation stage that takes sample indices one off: every ray it traces is one the
/// shared code also makes, so no ray parts, but its pixel is not what the rays add up to.
#[test]
fn a_ray_generation_stage_that_shades_otherwise_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let edit =
        ("uint sample_index = sy * SAMPLES_PER_SIDE + sx;", "uint sample_index = sy * SAMPLES_PER_SIDE + sx + 1u;");
    let spv = planted_include("raygen.rgen", "raygen_main.glsl", edit, dir.path());
    let b = format!("glsl,raygen={}", spv.display());
    let args = ["--validate", "explain", "showcase", "--width", "64", "--height", "36", "--pixel", "28,24"];
    let out = twinray(&[&args[..], &["--a", "glsl", "--b", &b, "--json"]].concat(), dir.path());
    let report: Value = serde_json::from_slice(&out.stdout).expect("json");
    let parting = &report["parting"];
    assert_eq!(parting["sample"], Value::Null, "no ray parts: {parting}");
    assert_eq!(parting["stage"], "set B's raygen", "{parting}");
}

#[test]
fn explain_prints_every_ray_and_the_parting_in_words() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["explain", "showcase", "--width", "64", "--height", "36", "--pixel", "28,24", "--b", "glsl"];
    let out = twinray(&args, dir.path());
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    // Showcase takes 2 x 2 samples and a rect light of 4 x 4 shadow samples.
    assert_eq!(text.matches("\nsample ").count(), 4, "{text}");
    assert!(text.contains("    light 0 sample (3, 3) at "), "{text}");
    assert!(text.contains("first place they part: all rays agree"), "{text}");
}

/// On a textured glTF model no one here made, each hit names its node, mesh primitive and
/// material, and the triangle, texture coordinates and level of detail it reads: the same in
/// both sets as the f64 reference finds them. Seen small, the 256-texel texture is read at a
/// coarser level.
#[test]
fn a_hit_on_a_model_names_its_node_triangle_texture_and_level() {
    let model = "/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
    assert!(Path::new(model).exists(), "{model}: run `cargo xtask setup`");
    let dir = tempfile::tempdir().unwrap();
    let levels = |size: [&str; 2], pixel: &str| -> Vec<f64> {
        let args = ["--validate", "explain", model, "--width", size[0], "--height", size[1], "--pixel", pixel];
        let out = twinray(&[&args[..], &["--b", "glsl", "--json"]].concat(), dir.path());
        assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
        let report: Value = serde_json::from_slice(&out.stdout).expect("json");
        let mut levels = Vec::new();
        for sample in report["samples"].as_array().unwrap() {
            let truth = &sample["reference"]["surface"];
            assert!(truth["object"].as_str().unwrap().starts_with("node "), "{truth}");
            assert!(truth["shape"].as_str().unwrap().contains("primitive 0"), "{truth}");
            assert_eq!(truth["material"], "material 0 \"Texture\"", "{truth}");
            let texel = &truth["textures"][0];
            assert!(texel["file"].as_str().unwrap().ends_with("BoxTextured.glb#image 0"), "{texel}");
            for set in sample["sets"].as_array().unwrap() {
                let on = &set["surface"];
                assert_eq!((&on["object"], &on["triangle"]), (&truth["object"], &truth["triangle"]), "{on}");
                let (uv, want) = (&on["textures"][0]["uv"], &texel["uv"]);
                for c in 0..2 {
                    let (a, b) = (uv[c].as_f64().unwrap(), want[c].as_f64().unwrap());
                    assert!((a - b).abs() < 1e-4, "uv {uv} against the reference's {want}");
                }
                let level = on["textures"][0]["level"].as_f64().unwrap();
                assert!((level - texel["level"].as_f64().unwrap()).abs() < 1e-3, "{on} against {texel}");
                levels.push(texel["level"].as_f64().unwrap());
            }
        }
        levels
    };
    let near = levels(["640", "480"], "320,240");
    let far = levels(["64", "48"], "32,24");
    assert!(near.iter().all(|&l| l < 0.5) && far.iter().all(|&l| l > 1.5), "near {near:?}, far {far:?}");
}

#[test]
fn bad_input_gets_one_line_and_exit_2() {
    assert_bad_input(&["explain", "spheres", "--pixel", "512,3"], &["pixel 512,3", "outside the 512x512 image"]);
    assert_bad_input(&["explain", "spheres", "--pixel", "3"], &["--pixel", "X,Y"]);
    assert_bad_input(&["explain", "spheres", "--pixel", "-1,3"], &["--pixel"]);
    assert_bad_input(&["explain", "orbit", "--pixel", "1,1", "--frame", "48"], &["--frame 48", "48 frame(s)"]);
    assert_bad_input(&["explain", "spheres", "--pixel", "1,1", "--frame", "1"], &["--frame 1", "1 frame(s)"]);
    assert_bad_input(&["explain", "spheres", "--pixel", "1,1", "--a", "/no/such/set"], &["/no/such/set"]);
    assert_bad_input(&["explain", "no-such-scene", "--pixel", "1,1"], &["no-such-scene"]);
    // A folder of modules built before explain existed.
    let folder = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(repo().join("spirv/glsl")).unwrap() {
        let path = entry.unwrap().path();
        if !path.file_stem().unwrap().to_string_lossy().starts_with("explain") {
            std::fs::copy(&path, folder.path().join(path.file_name().unwrap())).unwrap();
        }
    }
    let a = folder.path().to_string_lossy().into_owned();
    assert_bad_input(
        &["explain", "spheres", "--pixel", "1,1", "--a", &a],
        &["has no explain module", "rebuild the folder"],
    );
}
