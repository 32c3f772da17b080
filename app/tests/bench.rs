//! `twinray bench` end to end on lavapipe, small: two scenes, two sample counts, both sets.
//! Every report file exists and parses, and what results.json names is there.

use twinray_tests::cli::{assert_bad_input, twinray};

#[test]
fn a_small_bench_writes_every_report_file() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--validate",
        "bench",
        "lights",
        "--spp",
        "1,4",
        "--width",
        "48",
        "--height",
        "32",
        "--runs",
        "10",
        "--warmup",
        "1",
        "--placements",
        "2",
        "--null",
        "--reference-spp",
        "64",
        "--shadow-spp",
        "1,4",
        "--images",
        "last",
        "--probes",
        "cases",
        "--timing-rays",
        "0",
        "--out",
        "report",
        "--cache",
        "cache",
    ];
    std::fs::create_dir(dir.path().join("cases")).unwrap();
    for case in ["sphere-far-1e5.toml", "cone-apex.toml"] {
        std::fs::copy(
            twinray_tests::repo_root().join("probes/stability").join(case),
            dir.path().join("cases").join(case),
        )
        .unwrap();
    }
    let out = twinray(&args, dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report = dir.path().join("report");
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(report.join("results.json")).unwrap()).expect("results.json parses");
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2 * 3, "spp x sets (rust, glsl and the null control's copy of rust)");
    assert_eq!(json["reference_set"], "glsl", "by default the pair's other set renders the reference");
    for row in rows {
        for key in ["image", "error_map"] {
            // --images last: only the 4-spp renders are kept.
            if row["spp"] == 1 {
                assert!(row[key].is_null(), "{row}");
                continue;
            }
            let png = report.join(row[key].as_str().unwrap());
            assert_eq!(image::open(&png).expect("a readable PNG").width(), 48, "{}", png.display());
        }
        assert!(row["rmse"].as_f64().unwrap() > 0.0 && row["flip"].as_f64().unwrap() > 0.0, "{row}");
        // 10 timed traces in each of the two timed placements (the warm-up placement's dropped).
        assert_eq!(row["gpu_ms"]["samples"], 20);
        assert_eq!(row["placements"]["median_ms"].as_array().unwrap().len(), 2, "{row}");
        assert!(row["raygen_stack_bytes"].as_u64().unwrap() > 0, "{row}");
        assert!(row["mrays_per_s"].as_f64().unwrap() > 0.0);
    }
    // Identical images across sets: the second set's hit mismatches against the first are 0.
    assert!(rows.iter().filter(|r| r["set"] == "glsl").all(|r| r["hit_mismatches"] == 0));
    let csv = std::fs::read_to_string(report.join("results.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + rows.len());
    // Every pair of the three sets per scene and sample count, each with its interval; the
    // null control is rust against its copy.
    let ratios = json["ratios"].as_array().unwrap();
    assert_eq!(ratios.len(), 2 * 3, "spp x pairs");
    let null: Vec<_> = ratios.iter().filter(|r| r["null_control"] == true).collect();
    assert_eq!(null.len(), 2, "{ratios:?}");
    assert!(null.iter().all(|r| r["a"] == "rust" && r["b"] == "rust (copy 1)"), "{null:?}");
    for r in ratios {
        let i = &r["interval"];
        let (low, ratio, high) =
            (i["low"].as_f64().unwrap(), i["ratio"].as_f64().unwrap(), i["high"].as_f64().unwrap());
        assert!(low <= ratio && ratio <= high && i["placements"] == 2, "{r}");
        assert!(r["verdict"].as_str().unwrap().contains("95% CI"), "{r}");
    }
    let ratio_csv = std::fs::read_to_string(report.join("ratios.csv")).unwrap();
    assert_eq!(ratio_csv.lines().next().unwrap(), twinray::bench::tables::RATIO_CSV_HEADER);
    assert_eq!(ratio_csv.lines().count(), 1 + ratios.len());
    assert_eq!(csv.lines().next().unwrap(), twinray::bench::tables::CSV_HEADER);
    // The sampler study of the soft-shadow scene (lights): two samplers at two counts.
    assert_eq!(json["samplers"].as_array().unwrap().len(), 4);
    let samplers = std::fs::read_to_string(report.join("samplers.csv")).unwrap();
    assert_eq!(samplers.lines().next().unwrap(), twinray::bench::tables::SAMPLER_CSV_HEADER);
    assert_eq!(samplers.lines().count(), 5);
    // SPIR-V sizes of every module of both sets.
    let spirv = json["spirv"].as_array().unwrap();
    assert_eq!(spirv.len(), twinray_host::sets::MODULES.len());
    assert!(spirv
        .iter()
        .all(|m| m["rust_instructions"].as_u64().unwrap() > 0 && m["glsl_bytes"].as_u64().unwrap() > 0));
    // The intersection variants: the sphere case in both formulas; the cone has no naive one.
    let variants = std::fs::read_to_string(report.join("variants.csv")).unwrap();
    assert_eq!(variants.lines().next().unwrap(), twinray::bench::tables::VARIANT_CSV_HEADER);
    assert_eq!(variants.lines().filter(|l| l.starts_with("\"sphere-far-1e5\"")).count(), 2, "{variants}");
    assert!(!variants.contains("cone-apex"));
    for plot in ["error-spp", "error-time", "ratio", "places", "sampler-spp", "sampler-time", "variants"] {
        let png = image::open(report.join("plots").join(format!("{plot}.png"))).expect("a readable plot").to_rgb8();
        // Drawn: a white page with axes, labels and points, not one colour.
        let colours: std::collections::HashSet<_> = png.pixels().map(|p| p.0).collect();
        assert!(png.dimensions() == (900, 600) && colours.len() > 2, "{plot}.png: {} colours", colours.len());
        let svg = std::fs::read_to_string(report.join("plots").join(format!("{plot}.svg"))).unwrap();
        assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"), "{plot}.svg");
    }
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    for needle in [
        "plots/error-spp.svg",
        "plots/places.svg",
        "images/lights-reference.png",
        "Convergence",
        "Rust / GLSL",
        "Shadow samplers",
    ] {
        assert!(html.contains(needle), "index.html lacks {needle}");
    }
    // The references went to the cache: a second run reads them back.
    assert_eq!(
        std::fs::read_dir(dir.path().join("cache")).unwrap().count(),
        2,
        "one pixel reference, one shadow reference"
    );
}

/// `--processes 2`: every set timed alone in two child processes (rounds in alternating
/// orders), each row's times those of its processes, and every ratio's interval over the
/// rounds; the global flags (here `--validate`) reach the children. `--alone-in devices`: the
/// same rounds, each on a fresh device in the bench's process.
#[test]
fn sets_are_timed_alone_in_processes_of_their_own() {
    for alone_in in ["processes", "devices"] {
        timed_alone(alone_in);
    }
}

fn timed_alone(alone_in: &str) {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--validate",
        "bench",
        "sphere",
        "--sets",
        "glsl,rust",
        "--null",
        "--spp",
        "1",
        "--width",
        "32",
        "--height",
        "24",
        "--runs",
        "10",
        "--warmup",
        "1",
        "--placements",
        "2",
        "--processes",
        "2",
        "--first-placement",
        "100",
        "--alone-in",
        alone_in,
        "--reference-spp",
        "16",
        "--shadow-spp",
        "none",
        "--probes",
        "none",
        "--images",
        "none",
        "--out",
        "report",
        "--cache",
        "cache",
    ];
    let out = twinray(&args, dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("report/results.json")).unwrap()).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for (i, row) in rows.iter().enumerate() {
        // One time per process; the rounds go forwards, then backwards.
        assert_eq!(row["placements"]["median_ms"].as_array().unwrap().len(), 2, "{row}");
        let positions: Vec<u64> =
            row["placements"]["position"].as_array().unwrap().iter().map(|p| p.as_u64().unwrap()).collect();
        assert_eq!(positions, [i as u64, 2 - i as u64], "{row}");
        // Every placement of both processes.
        assert_eq!(row["gpu_ms"]["samples"], 4, "{row}");
        // Each process at places of its own, the null control's too: round r of set i starts
        // past the two placements of every process before it, (3r + i) * 2, all of them
        // past --first-placement, so that a second run times other places.
        let firsts = serde_json::json!([100 + 2 * i, 106 + 2 * i]);
        assert_eq!(row["placements"]["first_placement"], firsts, "{row}");
    }
    for r in json["ratios"].as_array().unwrap() {
        assert_eq!(r["interval"]["placements"], 2, "over the two rounds: {r}");
    }
    let left: Vec<_> = std::fs::read_dir(std::env::temp_dir())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with("twinray-alone-"))
        .filter(|e| e.path().join("results.json").exists())
        .collect();
    assert!(left.is_empty(), "child folders left behind: {left:?}");
    eprintln!("timed alone in {alone_in}: {}", json["ratios"]);
}

/// `compare --processes 3`: each set timed alone in three child benches of two placements, one
/// time per process in alternating orders and the interval over the rounds, the images from
/// the parent (in-process timing would give one time per placement, two); the same on fresh
/// devices (`--alone-in devices`); and the flags a child cannot honour refused before anything
/// renders.
#[test]
fn compare_times_each_set_alone_in_processes_of_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "32", "--height", "24", "--warmup", "1", "--placements", "2"];
    let args = [&["--validate", "compare", "sphere", "--a", "glsl", "--b", "rust"][..], &size[..]].concat();
    let out = twinray(&[&args[..], &["--processes", "3", "--out-dir", "cmp", "--json"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("compare --json prints JSON");
    assert_eq!(json["processes"], 3);
    assert_eq!(json["timing"]["placements"], 3, "over the three rounds: {json}");
    for (key, first, places) in [("placements_a", 0, [0, 4, 8]), ("placements_b", 1, [2, 6, 10])] {
        let positions: Vec<u64> =
            json[key]["position"].as_array().unwrap().iter().map(|p| p.as_u64().unwrap()).collect();
        assert_eq!(positions, [first, 1 - first, first], "{key}: the rounds go forwards, then backwards");
        assert_eq!(json[key]["median_ms"].as_array().unwrap().len(), 3, "one time per process: {json}");
        assert_eq!(json[key]["first_placement"], serde_json::json!(places), "places of its own: {json}");
    }
    assert!(dir.path().join("cmp/diff.png").is_file());
    // The same rounds on fresh devices in compare's own process.
    let on_devices = ["--processes", "3", "--alone-in", "devices", "--out-dir", "cmp"];
    let text = twinray(&[&args[..], &on_devices[..]].concat(), dir.path());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("each set alone in 3 devices of 2 placements"), "{text}");
    assert_bad_input(&["compare", "--processes", "2", "--eye", "1,2,3"], &["--processes", "--eye"]);
    assert_bad_input(&["compare", "orbit", "--processes", "2", "--frames", "0..2"], &["not with --frames"]);
    assert_bad_input(&["compare", "--processes", "2", "--runs", "3"], &["at least 10", "got 3"]);
}

/// `bisect --processes 3`: every set of the bisect timed alone in three child benches, the
/// swap of the `raygen` module (named as its stage) among them; not with --probe.
#[test]
fn bisect_times_each_set_alone_in_processes_of_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["bisect", "sphere", "--a", "glsl", "--b", "glsl,raygen=rust", "--width", "32", "--height", "24"];
    let out = twinray(&[&args[..], &["--placements", "1", "--processes", "3", "--json"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    // Exit code 1 says a difference was left unpinned: here a time difference, which on
    // lavapipe at 32x24 is resolved in some runs (the Rust raygen is a few percent slower
    // there, bench/reports/nvidia-code) and not in others. 2 would be an error.
    assert!(matches!(out.status.code(), Some(0 | 1)), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("bisect --json prints JSON");
    let clean = json["pinned"] == true && json["failures"].as_array().is_some_and(|f| f.is_empty());
    assert_eq!(out.status.code() == Some(0), clean, "the exit code follows pinned and failures: {json}");
    assert_eq!(json["processes"], 3);
    // One placement in each process: an interval at all is one over the three rounds.
    assert_eq!(json["ratio"]["placements"], 3, "{json}");
    let swap = &json["stages"][0];
    assert_eq!(swap["unit"], "raygen", "{json}");
    assert_eq!(swap["ratio_forward"]["placements"], 3, "{swap}");
    assert_bad_input(&["bisect", "--probe", "probes/far-sphere.toml", "--processes", "2"], &["--processes"]);
}

#[test]
fn bench_rejects_bad_input_before_rendering() {
    assert_bad_input(&["bench", "lights", "--spp", "1,3"], &["squares up to 256", "got 3"]);
    assert_bad_input(&["bench", "lights", "--runs", "5"], &["--runs must be at least 10"]);
    assert_bad_input(&["bench", "lights", "--sets", "rust,cuda"], &["unknown language \"cuda\""]);
    assert_bad_input(&["bench", "nosuchscene"], &["nosuchscene"]);
    assert_bad_input(&["bench", "lights", "--reference-spp", "300"], &["square up to 256"]);
    assert_bad_input(&["bench", "lights", "--probes", "no/such/dir"], &["--probes no/such/dir: no such folder"]);
}

/// `twinray places`: each set at each place of each move, the moves doing what they say (pads
/// only where a pad moves something, spacers only where the code is moved, the SBT moved by
/// its pad), under the validation layer; and its bad input refused.
#[test]
fn places_times_each_set_at_each_place_of_each_move() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["--validate", "places", "sphere", "--width", "32", "--height", "24", "--places", "3", "--runs", "2"];
    let out = twinray(&[&args[..], &["--out", "places.json"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    for line in ["none     glsl", "code     rust", "sbt      glsl", "buffers  rust"] {
        assert!(stdout.contains(line), "a row per move and set: {stdout}");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("places.json")).unwrap()).unwrap();
    let places = json["places"].as_array().unwrap();
    assert_eq!(places.len(), 4 * 2 * 3, "moves x sets x places");
    let of = |moved: &'static str| places.iter().filter(move |p| p["move"] == moved);
    assert!(of("none").all(|p| p["pad_bytes"] == 0 && p["spacers"] == 0), "{json}");
    assert!(of("code").all(|p| p["pad_bytes"] == 0), "{json}");
    assert!(of("code").all(|p| p["spacers"].as_u64() > Some(0)), "every place of the code move makes spacers: {json}");
    assert!(of("sbt").chain(of("buffers")).all(|p| p["pad_bytes"].as_u64() > Some(0) && p["spacers"] == 0));
    let sbts: std::collections::HashSet<u64> = of("sbt").filter_map(|p| p["sbt_address"].as_u64()).collect();
    assert!(sbts.len() > 1, "the pads move the SBT: {json}");
    assert!(of("none").all(|p| p["median_ms"].as_f64() > Some(0.0) && !p["warm_ms"].as_array().unwrap().is_empty()));
    assert_eq!(json["spreads"].as_array().unwrap().len(), 4 * 2, "{json}");
    assert_bad_input(&["places", "--places", "1"], &["--places"]);
    assert_bad_input(&["places", "--moves", "tlas"], &["tlas"]);
}
