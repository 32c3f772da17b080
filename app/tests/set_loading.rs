//! Parsing a set is not loading it: the text of a set is read without touching a file, and the
//! set is loaded once the command's options are in place, so every command that takes a set
//! keeps `--build-timeout` (exit 2, one line), and a build's error is the command's, not the
//! command line's.

use std::path::Path;
use std::time::{Duration, Instant};
use twinray_host::sets::{parse_specs, SetSpec};
use twinray_tests::cli::twinray;
use twinray_tests::repo_root as repo;

/// A shader crate whose build never ends (its build script sleeps forever).
fn endless_crate(dir: &Path) {
    let out = twinray(&["new", "c"], dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let script = "fn main() { loop { std::thread::sleep(std::time::Duration::from_secs(1)); } }\n";
    std::fs::write(dir.join("c/build.rs"), script).unwrap();
}

#[test]
fn parsing_names_paths_without_reading_them() {
    let scratch = tempfile::tempdir().unwrap();
    endless_crate(scratch.path());
    let crate_dir = scratch.path().join("c");
    let started = Instant::now();
    let text = format!("{},miss=glsl,glsl,raygen=/no/such/raygen.spv,rust", crate_dir.display());
    let specs: Vec<SetSpec> = parse_specs(&text).unwrap();
    assert!(started.elapsed() < Duration::from_millis(100), "parsing took {:?}", started.elapsed());
    assert_eq!(specs.len(), 3);
    assert!(specs[0].names_paths() && specs[1].names_paths() && !specs[2].names_paths());
    assert!(!crate_dir.join("target").exists(), "parsing built the crate");
    // The words are still checked when parsed: a typo is an error before any loading.
    assert!("rust,raygen=glsl,raygen=rust".parse::<SetSpec>().is_err());
    assert!("rust,anyhit=/no/such".parse::<SetSpec>().is_err());
}

#[test]
fn the_set_parser_reads_no_files() {
    let source = std::fs::read_to_string(repo().join("host/src/sets/spec.rs")).unwrap();
    for call in ["std::fs", "File::", ".exists(", ".is_dir(", ".is_file(", ".canonicalize(", "read_dir", "metadata("] {
        assert!(!source.contains(call), "host/src/sets/spec.rs calls {call}: parsing a set must not touch files");
    }
}

/// Every command that takes a set, naming the endless crate: each must stop at the build's
/// deadline with exit 2 and one line.
#[test]
fn every_command_that_takes_a_set_keeps_the_build_deadline() {
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    endless_crate(dir);
    let probes = repo().join("probes");
    let probe_case = probes.join("far-sphere.toml").display().to_string();
    let suite = probes.join("stability").display().to_string();
    let small = ["--width", "16", "--height", "16"];
    let commands: Vec<Vec<&str>> = vec![
        vec!["build", "c"],
        [&["render", "spheres", "--shaders", "./c"][..], &small].concat(),
        [&["compare", "spheres", "--a", "rust", "--b", "./c"][..], &small].concat(),
        [&["bisect", "spheres", "--a", "./c"][..], &small].concat(),
        vec!["explain", "spheres", "--pixel", "1,1", "--b", "./c"],
        vec!["inspect", "./c"],
        vec!["inspect", "--a", "rust", "--b", "./c"],
        vec!["probe", &probe_case, "--shaders", "./c"],
        vec!["stability", "--dir", &suite, "--sets", "rust;./c"],
        [&["reference", "spheres", "--shaders", "./c"][..], &small].concat(),
        vec!["bench", "spheres", "--sets", "rust,./c"],
        vec!["bench", "spheres", "--reference-set", "./c"],
        vec!["animate-bench", "--shaders", "./c"],
        vec!["stage-bench", "spheres", "--sets", "./c"],
        vec!["places", "spheres", "--sets", "./c"],
        // With --python, the Mitsuba side is rendered after the sets load, so none is needed here.
        vec!["crosscheck", "--python", "/bin/false", "--shaders", "./c"],
        vec!["view", "spheres", "--a", "./c"],
    ];
    for command in commands {
        let args = [&["--build-timeout", "1"][..], &command].concat();
        let started = Instant::now();
        let out = twinray(&args, dir);
        let took = started.elapsed();
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        let said = format!("twinray {}: exit {:?} after {took:?}\n{err}", args.join(" "), out.status.code());
        assert_eq!(out.status.code(), Some(2), "{said}");
        assert!(err.contains("did not finish within 1 s"), "{said}");
        assert_eq!(err.lines().count(), 1, "{said}");
        assert!(took < Duration::from_secs(30), "{said}");
    }
}
