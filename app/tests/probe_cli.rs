//! `twinray probe` as a user runs it: rays made and hit per generator, and `--rays-out`, the
//! CSV that finds the ray behind a false hit.

use twinray_tests::cli::{assert_bad_input, twinray};
use twinray_tests::repo_root as repo;

/// Run as the docs write it from a folder without `probes/` (an installed `twinray`): the
/// built-in case.
#[test]
fn probe_prints_rays_per_generator_and_writes_every_ray() {
    let dir = tempfile::tempdir().unwrap();
    let case = "probes/surface-rays.toml";
    assert!(!dir.path().join(case).exists());
    let args = ["probe", case, "--shaders", "glsl", "--runs", "1", "--rays-out", "rays.csv"];
    let out = twinray(&args, dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("relative t error by source, over "), "the t error by source: {stdout}");
    // Both surface generators make every ray they are asked for.
    let line = stdout.lines().find(|l| l.trim_start().starts_with("generators:")).expect("a generators line");
    let made: Vec<&str> = line.split(';').collect();
    assert_eq!(made.len(), 2, "{line}");
    for g in made {
        assert!(g.contains("surface made 2000,"), "{line}");
    }
    let csv = std::fs::read_to_string(dir.path().join("rays.csv")).unwrap();
    let mut rows = csv.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    assert_eq!(header[..4], ["ray", "ox", "oy", "oz"]);
    assert_eq!(header.last(), Some(&"glsl_outcome"));
    let rows: Vec<Vec<&str>> = rows.map(|r| r.split(',').collect()).collect();
    assert_eq!(rows.len(), 4000, "one row per ray");
    let outcomes = ["agrees", "ambiguous", "false_hit", "false_miss", "wrong_object"];
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len(), "row {i}");
        assert_eq!(row[0], i.to_string());
        assert!(outcomes.contains(row.last().unwrap()), "row {i}: {row:?}");
    }
    // The rows agree with the summary: as many false hits in the file as printed.
    let printed = stdout.split("false hits ").nth(1).and_then(|s| s.split(',').next()).unwrap();
    let listed = rows.iter().filter(|r| r.last() == Some(&"false_hit")).count();
    assert_eq!(printed, listed.to_string());
}

/// Rays in two groups far apart are launched at an origin each, and the probe says where.
#[test]
fn a_case_that_is_neither_a_file_nor_built_in_is_refused_naming_the_built_in_ones() {
    assert_bad_input(&["probe", "probes/no-such-case.toml"], &["no-such-case", "nor a built-in case", "far-sphere"]);
    assert_bad_input(&["bisect", "--probe", "nope", "--a", "rust", "--b", "glsl"], &["probe case nope"]);
}

#[test]
fn probe_names_the_origin_each_group_of_rays_was_launched_at() {
    let dir = tempfile::tempdir().unwrap();
    let case = repo().join("probes/stability/groups-thin-box-far-mesh.toml");
    let out = twinray(&["probe", case.to_str().unwrap(), "--runs", "1", "--warmup", "0", "--json"], dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let launches = report["launches"].as_array().expect("launches");
    let origins: Vec<[f64; 3]> =
        launches.iter().map(|l| std::array::from_fn(|k| l["origin"][k].as_f64().expect("a coordinate"))).collect();
    // The mesh's rays beside the mesh (between their starts, 10 units out, and its translation),
    // the sheet's at world coordinates (its translation is the world origin).
    assert_eq!(origins.len(), 2, "{origins:?}");
    let mesh = [7000.0, -5000.0, 6500.0];
    assert!((0..3).all(|k| (origins[0][k] - mesh[k]).abs() <= 11.0), "{origins:?}");
    assert_eq!(origins[1], [0.0; 3]);
    let rays: u64 = launches.iter().map(|l| l["rays"].as_u64().unwrap()).sum();
    assert_eq!(rays, report["rays"].as_u64().unwrap(), "every ray in one launch");
}

/// `stability --against-world`: a folder's cases and random ones, each probed at its chosen
/// origins and at world coordinates; exit 1 where the chosen origin is worse (here a file that
/// asks for the camera's eye, 1.2e4 from its rays), and --random only with --against-world.
#[test]
fn stability_against_world_compares_each_case_with_world_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let (good, eye) = (dir.path().join("good"), dir.path().join("eye"));
    for (folder, file) in [
        (&good, repo().join("probes/stability/groups-two-far-shapes.toml")),
        (&eye, repo().join("bench/reports/accuracy/eye-secondary-rays.toml")),
    ] {
        std::fs::create_dir_all(folder).unwrap();
        std::fs::copy(&file, folder.join(file.file_name().unwrap())).unwrap();
    }
    let folder = good.to_string_lossy().into_owned();
    let out = twinray(&["stability", "--against-world", "--dir", &folder, "--validate"], dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("groups-two-far-shapes") && stdout.contains("not worse"), "{stdout}");
    assert!(stdout.contains("0 of 2 rows worse"), "{stdout}");

    let folder = eye.to_string_lossy().into_owned();
    let out = twinray(&["stability", "--against-world", "--dir", &folder, "--sets", "glsl", "--json"], dir.path());
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    let rows: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON rows");
    let row = &rows[0];
    assert!(row["worse_rays"].as_u64() > Some(0), "{row}");
    assert!(row["chosen"]["p99"].as_f64() > row["world"]["p99"].as_f64(), "{row}");

    let written = dir.path().join("written");
    std::fs::create_dir_all(&written).unwrap();
    let args = ["stability", "--against-world", "--random", "1", "--seed", "3", "--sets", "rust", "--write-cases"];
    let out = twinray(&[&args[..], &[written.to_str().unwrap()]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("random-3 "), "{stdout}");
    let text = std::fs::read_to_string(written.join("random-3.toml")).expect("the case written");
    assert_eq!(text, twinray_host::probe::random::origin_case(3));

    let out = twinray(&["stability", "--random", "1"], dir.path());
    assert_eq!(out.status.code(), Some(2), "--random without --against-world");
}
