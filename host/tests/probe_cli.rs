//! `twinray probe` as a user runs it: rays made and hit per generator, and `--rays-out`, the
//! CSV that finds the ray behind a false hit.

use twinray_tests::cli::twinray;
use twinray_tests::repo_root as repo;

#[test]
fn probe_prints_rays_per_generator_and_writes_every_ray() {
    let dir = tempfile::tempdir().unwrap();
    let case = repo().join("probes/surface-rays.toml");
    let args = ["probe", case.to_str().unwrap(), "--shaders", "glsl", "--runs", "1", "--rays-out", "rays.csv"];
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
