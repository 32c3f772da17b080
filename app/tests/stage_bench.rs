//! `twinray stage-bench` on lavapipe: every variant of the cutout scene is measured against the
//! first; cutouts without holes cost any-hit but give the opaque image, and ray-query shadows
//! give the image `traceRay` shadows give, as the compute renderer gives the pipeline's; variants that mean nothing for a scene are
//! reported, not measured; bad input exits 2.

use twinray_tests::cli::twinray;

#[test]
fn stage_bench_measures_every_variant_against_the_first() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let args = [
        "stage-bench",
        "cutout",
        "spheres",
        "--variants",
        "as-is,query-shadows,opaque,solid-cutouts,compute",
        "--sets",
        "rust",
        "--rounds",
        "1",
        "--runs",
        "1",
        "--warmup",
        "0",
        "--width",
        "64",
        "--height",
        "48",
        "--out",
    ];
    let mut args: Vec<&str> = args.to_vec();
    let out_text = out.to_string_lossy().into_owned();
    args.push(&out_text);
    let run = twinray(&args, dir.path());
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let rows = json["rows"].as_array().unwrap();
    let row = |variant: &str| rows.iter().find(|r| r["scene"] == "cutout" && r["variant"] == variant).unwrap();
    assert_eq!(rows.len(), 5 + 2, "five cutout variants, spheres as-is and compute: {rows:#?}");
    // Each round is a placement; the first variant against itself is 1 in every round.
    let first = &row("as-is")["against_first"];
    assert_eq!(
        (first["ratio"].as_f64(), first["low"].as_f64(), first["high"].as_f64()),
        (Some(1.0), Some(1.0), Some(1.0))
    );
    assert_eq!(first["placements"], row("as-is")["round_ms"].as_array().unwrap().len(), "{first}");
    assert_eq!(row("query-shadows")["rmse"], 0.0, "query shadows are traced shadows");
    assert_eq!(row("query-shadows")["shadow_rays"], row("as-is")["shadow_rays"]);
    for compute in rows.iter().filter(|r| r["variant"] == "compute") {
        assert_eq!(compute["rmse"], 0.0, "the compute renderer gives the pipeline's image: {compute}");
        assert_eq!(compute["hit_mismatches"], 0, "{compute}");
        assert_eq!(compute["raygen_stack_bytes"], 0, "{compute}");
    }
    assert!(row("opaque")["rmse"].as_f64().unwrap() > 0.01, "the holes are gone");
    let solid = row("solid-cutouts");
    assert_eq!(solid["rmse"], row("opaque")["rmse"], "no holes: the opaque image");
    assert!(solid["gpu_ms"]["median"].as_f64().unwrap() > 0.0);
    // Spheres has no cutouts and no shadows: those variants are skipped, with the reason.
    let skipped = json["skipped"].as_array().unwrap();
    assert_eq!(skipped.len(), 3, "{skipped:#?}");
    assert!(skipped.iter().all(|s| s["scene"] == "spheres" && s["why"].as_str().unwrap().contains("nothing")));
    let table = std::fs::read_to_string(out.join("table.md")).unwrap();
    assert!(table.contains("| cutout | solid-cutouts | rust |") && table.contains("not measured"), "{table}");
}

/// `--alone`: each round's render of each variant and set timed in a child stage-bench of its
/// own, one time per round (in-process, a row pools every timed trace), the images still
/// compared here; the global flags (`--validate`) reach the children, and each child its
/// round's number (it says which it timed, and a child that timed another fails the run).
#[test]
fn stage_bench_alone_times_each_render_in_a_process_of_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "48", "--height", "32", "--runs", "3", "--warmup", "1"];
    let args =
        [&["--validate", "stage-bench", "cutout", "--variants", "opaque,as-is", "--sets", "glsl,rust"][..], &size];
    let run = twinray(
        &[&args.concat()[..], &["--rounds", "2", "--first-round", "5", "--alone", "--out", "report"]].concat(),
        dir.path(),
    );
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report/results.json")).unwrap()).unwrap();
    assert_eq!(json["alone"], true);
    assert_eq!(json["first_round"], 5, "rounds 5 and 6");
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4, "{rows:#?}");
    for row in rows {
        assert_eq!(row["round_ms"].as_array().unwrap().len(), 2, "{row}");
        assert_eq!(row["gpu_ms"]["samples"], 2, "one time per round, not 3 traces each: {row}");
        assert_eq!(row["against_first_set"]["placements"], 2, "{row}");
    }
    let as_is = rows.iter().find(|r| r["variant"] == "as-is" && r["set"] == "rust").unwrap();
    assert!(as_is["rmse"].as_f64().unwrap() > 0.01, "the holes, against the opaque image: {as_is}");
}

#[test]
fn stage_bench_refuses_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    for (args, want) in [
        (vec!["stage-bench", "--variants", "opaque,glowing"], "glowing"),
        (vec!["stage-bench", "no-such-scene"], "no-such-scene"),
        (vec!["stage-bench", "--sets", "rust,fortran"], "fortran"),
        (vec!["stage-bench", "--placements", "3"], "give --rounds instead of --placements"),
        (vec!["stage-bench", "--rounds", "0"], "rounds"),
    ] {
        let out = twinray(&args, dir.path());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want) && err.lines().count() == 1, "{args:?}: {err}");
    }
}
