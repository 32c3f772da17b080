//! The `twinray` command end to end: bad input gives a one-line error naming what and where,
//! exit code 2, no panic and no file written; good input renders, compares and prints JSON.
//! Renders run on lavapipe with --validate, so a validation error fails them.

use std::path::Path;
use std::process::Output;
use twinray_tests::cli::{assert_bad_input, twinray, with_capability};
use twinray_tests::repo_root as repo;

#[test]
fn missing_scene_file() {
    assert_bad_input(&["render", "no/such/scene.toml", "--out", "x.png"], &["no/such/scene.toml", "no such file"]);
    assert_bad_input(&["compare", "nosuchscene"], &["nosuchscene", "built-ins: spheres"]);
    assert_bad_input(&["probe", "no/such/case.toml"], &["probe case no/such/case.toml", "no such file"]);
}

#[test]
fn unreadable_scene_file() {
    // A directory exists but cannot be read as a file.
    assert_bad_input(&["render", ".", "--out", "x.png"], &["scene .", "cannot read"]);
}

#[test]
fn malformed_scene_file_reports_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "name = \"x\"\n[image]\nwidth = \"wide\"\n").unwrap();
    let bad = bad.to_string_lossy().into_owned();
    assert_bad_input(&["render", &bad, "--out", "x.png"], &[&bad, "line 3, column 9"]);
}

/// The default scene with `from` replaced by `to` (and `extra` appended), as a file in `dir`.
fn edited_scene(dir: &Path, from: &str, to: &str, extra: &str) -> String {
    let text = include_str!("../../scenes/spheres.toml");
    assert!(text.contains(from), "the default scene no longer contains {from:?}");
    let path = dir.join("edited.toml");
    std::fs::write(&path, text.replace(from, to) + extra).unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn impossible_values_in_scene_file_are_named() {
    let mesh = "\n[shapes.pot]\nkind = \"mesh\"\nfile = \"no-such-pot.obj\"\n";
    let spot = |keys: &str| {
        format!("\n[[lights]]\nkind = \"point\"\nposition = [0.0, 9.0, 0.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n{keys}\n")
    };
    let (wide, short) = (
        spot("spot = { direction = [0.0, -1.0, 0.0], inner_cone_degrees = 40.0, outer_cone_degrees = 30.0 }"),
        spot("range = 0.0"),
    );
    let rect = "\n[[lights]]\nkind = \"rect\"\ncenter = [0.0, 9.0, 0.0]\nu = [1.0, 0.0, 0.0]\nv = [2.0, 0.0, 0.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n";
    let glow = |emission: &str| {
        format!("\n[materials.glow]\nkind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\ntexture = {{ file = \"a.png\" }}\nemission = {emission}\n")
    };
    let (dim, turned) = (
        glow("{ color = [1.0, 0.0, 0.0], intensity = -1.0 }"),
        glow("{ color = [1.0, 0.0, 0.0], texture = { file = \"b.png\", transform = [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]] } }"),
    );
    let cases = [
        ("radius_min = 0.5", "radius_min = -1.0", "", "shape \"field\": radius_min must be > 0"),
        ("name = \"spheres\"", "name = \"spheres\"", wide.as_str(), "lights[1]: spot cone of inner_cone_degrees 40 and outer_cone_degrees 30: 0 <= inner < outer <= 90"),
        ("name = \"spheres\"", "name = \"spheres\"", short.as_str(), "lights[1]: range must be > 0 (got 0)"),
        ("name = \"spheres\"", "name = \"spheres\"", dim.as_str(), "material \"glow\": emission.intensity must be finite and not negative"),
        ("name = \"spheres\"", "name = \"spheres\"", turned.as_str(), "material \"glow\": emission.texture.transform [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]] differs from texture.transform"),
        (
            "color = [1.0, 1.0, 1.0]\nintensity = 1.0",
            "color = [nan, 1.0, 1.0]\nintensity = 1.0",
            "",
            "lights[0]: color must be finite",
        ),
        (
            "material = \"white\"",
            "material = \"whyte\"",
            "",
            "objects[0] (shape \"field\"): unknown material \"whyte\" (materials: white)",
        ),
        ("shape = \"field\"", "shape = \"feild\"", "", "objects[0] (shape \"feild\"): unknown shape"),
        ("fov_y_degrees = 45.0", "fov_y_degrees = 180.0", "", "camera.fov_y_degrees must be in (0, 180)"),
        (
            "fov_y_degrees = 45.0",
            "orthographic_height = 0.0",
            "",
            "camera.orthographic_height must be a height above 0",
        ),
        ("material = \"white\"", "material = \"white\"\nscale = [1.0, 0.0, 1.0]", "", "scale must not be zero"),
        ("name = \"spheres\"", "name = \"spheres\"", rect, "lights[1]: u and v span no area (zero-area light)"),
        ("name = \"spheres\"", "name = \"spheres\"", mesh, "shape \"pot\": cannot read mesh file"),
    ];
    for (from, to, extra, message) in cases {
        let dir = tempfile::tempdir().unwrap();
        let scene = edited_scene(dir.path(), from, to, extra);
        assert_bad_input(&["render", &scene, "--out", "x.png"], &[&scene, message]);
    }
}

#[test]
fn unknown_shader_set_or_stage() {
    assert_bad_input(&["render", "--shaders", "hlsl", "--out", "x.png"], &["--shaders", "unknown language \"hlsl\""]);
    assert_bad_input(&["render", "--shaders", "rust,anyhit=glsl", "--out", "x.png"], &["unknown stage \"anyhit\""]);
    assert_bad_input(&["compare", "--b", "rust,intersection"], &["--b", "STAGE=LANGUAGE"]);
}

#[test]
fn zero_or_oversized_resolution() {
    assert_bad_input(&["render", "--width", "0", "--out", "x.png"], &["0x512", "at least 1"]);
    assert_bad_input(&["render", "--height", "100000", "--out", "x.png"], &["512x100000", "too large"]);
    assert_bad_input(&["compare", "--width", "16384", "--height", "16384"], &["too large"]);
    // clap reads -3 as an unknown flag; the message names it.
    assert_bad_input(&["render", "--width", "-3", "--out", "x.png"], &["'-3'"]);
}

#[test]
fn unwritable_output() {
    assert_bad_input(&["render", "--out", "x.jpg"], &["x.jpg", ".png"]);
    assert_bad_input(&["render", "--out", "missing/dir/x.png"], &["missing/dir", "does not exist"]);
}

#[test]
fn help_documents_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let commands = [
        &["--help"][..],
        &["info", "--help"],
        &["scenes", "--help"],
        &["render", "--help"],
        &["compare", "--help"],
        &["probe", "--help"],
        &["stability", "--help"],
        &["reference", "--help"],
        &["explain", "--help"],
        &["view", "--help"],
    ];
    for args in commands {
        let out = twinray(args, dir.path());
        assert!(out.status.success(), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stdout).contains("Usage:"), "{args:?}");
    }
}

#[test]
fn render_writes_png_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["--validate", "render", "--shaders", "glsl,intersection=rust", "--width", "64", "--height", "48"];
    let out = twinray(&[&args[..], &["--runs", "2", "--warmup", "0", "--out", "r.png", "--json"]].concat(), dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("render --json prints JSON");
    assert_eq!((json["width"].as_u64(), json["height"].as_u64()), (Some(64), Some(48)));
    assert_eq!(json["set"], "glsl,intersection=rust");
    assert_eq!(json["gpu_ms_runs"].as_array().map(Vec::len), Some(2));
    assert_eq!(json["gpu_ms_spread"]["samples"], 2);
    assert_eq!(json["rays"]["primary"], 64 * 48, "one sample per pixel in the default scene");
    assert!(json["mrays_per_s"].as_f64().is_some_and(|r| r > 0.0));
    assert!(json["cpu_threads"].as_u64().is_some_and(|t| t >= 1), "lavapipe's threads");
    let png = image::open(dir.path().join("r.png")).expect("a readable PNG");
    assert_eq!((png.width(), png.height()), (64, 48));
}

/// `--no-shared-blases`: a glTF mesh of four primitives is four structures and four instances,
/// not one of each, and the image is the same, byte for byte.
#[test]
fn without_shared_blases_a_mesh_is_a_structure_per_primitive_and_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let colors = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
    let model = twinray_tests::gltf::strip(dir.path(), &colors, &[[0.0; 3]]);
    let render = |flags: &[&str], png: &str| {
        let args =
            ["--validate", "render", model.to_str().unwrap(), "--width", "64", "--height", "48", "--warmup", "0"];
        let out = twinray(&[&args[..], flags, &["--runs", "1", "--out", png, "--json"]].concat(), dir.path());
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("render --json prints JSON");
        let accel = &json["acceleration_structures"];
        (accel["blases"].as_u64(), accel["instances"].as_u64(), std::fs::read(dir.path().join(png)).unwrap())
    };
    let shared = render(&[], "shared.png");
    let alone = render(&["--no-shared-blases"], "alone.png");
    assert_eq!((shared.0, shared.1), (Some(1), Some(1)));
    assert_eq!((alone.0, alone.1), (Some(4), Some(4)));
    assert!(shared.2 == alone.2, "the images differ");
}

/// `--frame`, `--eye` and `--look-at` choose the still image; the camera moves the picture.
#[test]
fn a_still_image_from_another_camera_or_frame() {
    let dir = tempfile::tempdir().unwrap();
    let render = |extra: &[&str], out: &str| {
        let args = ["--validate", "render", "spheres", "--width", "48", "--height", "48", "--out", out];
        let ran = twinray(&[&args[..], extra].concat(), dir.path());
        assert!(ran.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&ran.stderr));
        image::open(dir.path().join(out)).unwrap().to_rgba8()
    };
    let scene = render(&[], "scene.png");
    let same = render(&["--eye", "0,0,4", "--look-at", "0,0,0"], "same.png");
    let above = render(&["--eye", "0,6,0.1", "--look-at", "0,0,0"], "above.png");
    assert_ne!(scene, above, "a camera above the spheres sees another picture");
    assert_ne!(same, above);
    let frame =
        ["compare", "orbit", "--frame", "47", "--width", "32", "--height", "18", "--runs", "1", "--placements", "1"];
    let ran = twinray(&[&frame[..], &["--warmup", "0", "--out-dir", "c", "--json"]].concat(), dir.path());
    assert!(ran.status.success(), "{}", String::from_utf8_lossy(&ran.stderr));
}

#[test]
fn impossible_viewpoints_are_refused() {
    assert_bad_input(
        &["render", "--eye", "0,0,0", "--look-at", "0,0,0", "--out", "x.png"],
        &["--eye/--look-at", "differ"],
    );
    assert_bad_input(&["render", "--eye", "1,2", "--out", "x.png"], &["--eye", "X,Y,Z"]);
    assert_bad_input(&["render", "--look-at", "0,nan,0", "--out", "x.png"], &["--look-at", "finite"]);
    assert_bad_input(&["compare", "orbit", "--frames", "all", "--frame", "3"], &["--frame", "--frames"]);
    assert_bad_input(&["compare", "orbit", "--frame", "48"], &["--frame 48", "48 frame(s)"]);
}

#[test]
fn compare_prints_json_with_the_documented_keys() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["--validate", "compare", "--width", "96", "--height", "96", "--runs", "2", "--warmup", "1"];
    let out = twinray(&[&args[..], &["--placements", "3", "--out-dir", "cmp", "--json"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("compare --json prints JSON");
    let keys = [
        "scene",
        "width",
        "height",
        "rmse",
        "psnr",
        "max_abs_diff",
        "pixels_over_threshold",
        "hit_mismatches",
        "gpu_ms_a",
        "gpu_ms_b",
        "ratio",
        "spread_a",
        "spread_b",
        "rays_a",
        "rays_b",
        "mrays_per_s_a",
        "mrays_per_s_b",
        "cpu_threads",
        "timing",
        "placements_a",
        "placements_b",
        "processes",
        "null_control",
        "pass",
    ];
    for key in keys {
        assert!(json.get(key).is_some(), "missing {key} in {stdout}");
    }
    // The ratio with its interval over the three timed placements, and the verdict in words.
    let timing = &json["timing"];
    for key in ["ratio", "low", "high", "log_sd", "verdict"] {
        assert!(timing.get(key).is_some(), "missing timing.{key} in {stdout}");
    }
    assert_eq!(timing["placements"], 3);
    assert_eq!(json["placements_a"]["median_ms"].as_array().unwrap().len(), 3);
    assert!(timing["verdict"].as_str().unwrap().contains("95% CI"), "{timing}");
    assert_eq!(json["null_control"], false);
    assert_eq!(json["processes"], 0);
    assert_eq!(out.status.success(), json["pass"] == true, "exit code must follow pass");
    for name in ["a.png", "b.png", "diff.png"] {
        assert!(dir.path().join("cmp").join(name).is_file(), "{name} not written");
    }
}

/// `twinray stability` on a folder of two cases: the table and the cost table, JSON rows
/// (robust only for a shape without a naive variant), exit code 1 when a target is missed,
/// and exit code 2 for a folder without cases.
#[test]
fn stability_prints_rows_costs_and_json_and_fails_on_a_missed_target() {
    let dir = tempfile::tempdir().unwrap();
    let cases = repo().join("probes/stability");
    for name in ["sphere-far-1e3.toml", "cone-apex.toml"] {
        std::fs::copy(cases.join(name), dir.path().join(name)).unwrap();
    }
    let folder = dir.path().to_string_lossy().into_owned();
    let args = ["stability", "--dir", &folder, "--runs", "1", "--warmup", "0", "--timing-rays", "0", "--validate"];
    let out = twinray(&args, dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("sphere-far-1e3") && stdout.contains("robust/naive"), "{stdout}");
    assert!(stdout.contains("stage p99") && stdout.contains("xform p99"), "the t error by source: {stdout}");
    let out = twinray(&[&args[..], &["--json"]].concat(), dir.path());
    let rows: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON rows");
    let rows = rows.as_array().unwrap();
    let count = |case: &str| rows.iter().filter(|r| r["case"] == case).count();
    assert_eq!((count("sphere-far-1e3"), count("cone-apex")), (4, 2), "rust and glsl; naive only for the sphere");
    for key in ["formula", "rays", "decided", "false_hits", "false_misses", "relative_t_error", "failures"] {
        assert!(rows[0].get(key).is_some(), "no {key} in {}", rows[0]);
    }
    let split = &rows[0]["t_error_by_source"];
    assert!(split["rays"].as_u64() > Some(0) && split["stage"]["p99"].is_f64(), "{split}");
    // An unreachable target: the same run now fails.
    let strict = std::fs::read_to_string(dir.path().join("cone-apex.toml")).unwrap().replace("1e-06", "1e-12");
    std::fs::write(dir.path().join("cone-apex.toml"), strict).unwrap();
    let out = twinray(&args, dir.path());
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).contains("MISSED: relative t p99"));
    let empty = tempfile::tempdir().unwrap();
    assert_bad_input(&["stability", "--dir", &empty.path().to_string_lossy()], &["no probe cases"]);
}

/// A suite runs what the device can: a case whose module asks for what the device was not
/// asked to enable (here the compute renderer's probe, from a folder set, declaring
/// RayTracingMotionBlurNV) is skipped with one line naming it and why, the other case is
/// judged, and the summary counts the skipped one; exit 0.
#[test]
fn stability_skips_a_case_the_device_cannot_run_and_judges_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let (cases, set) = (dir.path().join("cases"), dir.path().join("set"));
    std::fs::create_dir_all(&cases).unwrap();
    std::fs::create_dir_all(&set).unwrap();
    for module in std::fs::read_dir(repo().join("spirv/glsl")).unwrap().map(|e| e.unwrap().path()) {
        std::fs::copy(&module, set.join(module.file_name().unwrap())).unwrap();
    }
    let query = std::fs::read(set.join("probe_query.spv")).unwrap();
    std::fs::write(set.join("probe_query.spv"), with_capability(&query, 5341, "SPV_NV_ray_tracing_motion_blur"))
        .unwrap();
    let text = std::fs::read_to_string(repo().join("probes/stability/sphere-far-1e3.toml")).unwrap();
    std::fs::write(cases.join("sphere-far-1e3.toml"), &text).unwrap();
    let compute = text.replace("name = \"sphere-far-1e3\"", "name = \"sphere-far-compute\"").replacen(
        "[scene.materials.m]",
        "[scene]\nrenderer = \"compute\"\n\n[scene.materials.m]",
        1,
    );
    std::fs::write(cases.join("sphere-far-compute.toml"), compute).unwrap();
    let (cases, set) = (cases.to_string_lossy().into_owned(), set.to_string_lossy().into_owned());
    let args = ["stability", "--dir", &cases, "--sets", &set, "--runs", "1", "--warmup", "0", "--timing-rays", "0"];
    let out = twinray(&args, dir.path());
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert_eq!(out.status.code(), Some(0), "{stdout}{stderr}");
    let skip = stderr.lines().find(|l| l.starts_with("skipped sphere-far-compute: ")).unwrap_or_default();
    assert!(
        skip.contains("the probe_query module (") && skip.contains("capability RayTracingMotionBlurNV"),
        "{stderr}"
    );
    assert!(stdout.contains("sphere-far-1e3") && !stdout.contains("sphere-far-compute  "), "{stdout}");
    assert!(stdout.contains("skipped 1 of 2 cases, which need what"), "{stdout}");
}

/// `twinray reference`: renders, then reads the same key from the cache; a sample count that
/// is neither a square up to 256 nor a multiple of 256 is bad input.
#[test]
fn reference_renders_then_reads_the_cache() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--validate",
        "reference",
        "lights",
        "--spp",
        "4",
        "--width",
        "16",
        "--height",
        "16",
        "--cache",
        "c",
        "--json",
    ];
    let json = |out: Output| -> serde_json::Value { serde_json::from_slice(&out.stdout).expect("reference --json") };
    let first = json(twinray(&args, dir.path()));
    assert_eq!((first["cached"].as_bool(), first["spp"].as_u64()), (Some(false), Some(4)));
    let second = json(twinray(&[&args[..], &["--out", "r.png"]].concat(), dir.path()));
    assert_eq!((second["cached"].as_bool(), &second["path"]), (Some(true), &first["path"]));
    assert!(dir.path().join("r.png").exists());
    assert_bad_input(&["reference", "lights", "--spp", "3"], &["square up to 256", "got 3"]);
}

/// Parity belongs to comparisons and the name can come from the file: a scene with neither
/// renders, and its name is the file's stem.
#[test]
fn a_scene_without_parity_or_name_renders() {
    let dir = tempfile::tempdir().unwrap();
    let text = include_str!("../../scenes/spheres.toml");
    let parity = text.find("[parity]").expect("the default scene has a [parity] table");
    let without: String =
        text[..parity].lines().filter(|l| !l.starts_with("name =")).map(|l| format!("{l}\n")).collect();
    std::fs::write(dir.path().join("bare.toml"), without).unwrap();
    let args = ["render", "bare.toml", "--width", "16", "--height", "16", "--out", "bare.png", "--json"];
    let out = twinray(&args, dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["scene"], "bare");
}

/// `info` says what the device can do beyond what twinray requires, with the optional
/// extensions enabled under the validation layer (a feature enabled wrongly fails it).
#[test]
fn info_lists_the_optional_capabilities() {
    let dir = tempfile::tempdir().unwrap();
    let out = twinray(&["--validate", "--no-pipeline-cache", "info", "--json"], dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let info: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in ["pipeline_library", "ray_query", "host_acceleration_structure_commands"] {
        assert!(info[key].is_boolean(), "{key}: {info}");
    }
    let text = twinray(&["--no-pipeline-cache", "info"], dir.path());
    let text = String::from_utf8_lossy(&text.stdout);
    for line in ["libraries   VK_KHR_pipeline_library", "ray query   VK_KHR_ray_query", "host AS     ", "any_hit"] {
        assert!(text.contains(line), "{line:?} missing from {text}");
    }
}

// Images as other tools read them: a PNG of radiance holds it sRGB-encoded and tagged so,
// with values above 1 clipped or tone-mapped as asked; an EXR holds the linear radiance as
// rendered. Read back with the `image` and `png` crates (OpenEXR through the `exr` crate).

fn render_image(dir: &Path, out: &str, extra: &[&str]) {
    let args = [extra, &["render", "lights", "--width", "48", "--height", "36", "--out", out]].concat();
    let done = twinray(&args, dir);
    assert!(done.status.success(), "{}", String::from_utf8_lossy(&done.stderr));
}

fn srgb(c: f32) -> u8 {
    let c = c.clamp(0.0, 1.0);
    let v = if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (v * 255.0).round() as u8
}

#[test]
fn pngs_are_srgb_and_exr_is_linear() {
    let dir = tempfile::tempdir().unwrap();
    render_image(dir.path(), "linear.exr", &[]);
    render_image(dir.path(), "clip.png", &[]);
    render_image(dir.path(), "reinhard.png", &["--tone-map", "reinhard"]);
    let linear = image::open(dir.path().join("linear.exr")).unwrap().into_rgb32f();
    assert_eq!(linear.dimensions(), (48, 36));
    assert!(linear.pixels().any(|p| p.0.iter().any(|&c| c > 1.0)), "lights has radiance above 1 to clip");
    for (name, tone) in [("clip.png", (|c: f32| c) as fn(f32) -> f32), ("reinhard.png", |c: f32| c / (1.0 + c))] {
        let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(dir.path().join(name)).unwrap()));
        let reader = decoder.read_info().unwrap();
        assert!(reader.info().srgb.is_some(), "{name} is tagged sRGB");
        let picture = image::open(dir.path().join(name)).unwrap().into_rgba8();
        for (p, q) in linear.pixels().zip(picture.pixels()) {
            let want = p.0.map(|c| srgb(tone(c.max(0.0))));
            assert_eq!(&q.0[..3], &want, "{name}: linear {:?}", p.0);
        }
    }
}

#[test]
fn an_output_that_is_neither_png_nor_exr_is_refused() {
    assert_bad_input(&["render", "sphere", "--out", "x.jpg"], &["x.jpg", ".png (sRGB) or .exr (linear)"]);
}
