//! One build of every dependency: `cargo build -p twinray` (what a user installs and what the
//! tutorial's copy runs) and the workspace's tests give every crate of the library's build the
//! same features, so cargo builds it once for both. A dependency of the tests that turns on
//! another feature of one of them builds it, and all that depends on it, this library
//! included, a second time; app/Cargo.toml turns such features on for the app too. And the
//! render library (`twinray-host`) links none of the app's crates: no command line, web
//! server or plotting.

use std::collections::{BTreeMap, BTreeSet};
use std::process::Command;

/// Each package of `cargo tree ARGS` with the features it is built with.
fn features(args: &[&str]) -> BTreeMap<String, BTreeSet<String>> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args(["tree", "--offline", "--no-dedupe", "--prefix", "none", "--format", "{p}|{f}"])
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("running cargo tree");
    assert!(out.status.success(), "cargo tree {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    let mut packages = BTreeMap::new();
    // A line ending in `(*)` repeats a package printed before (the tests' dependency cycle).
    for line in String::from_utf8_lossy(&out.stdout).lines().filter(|l| !l.ends_with("(*)")) {
        let (package, features) = line.split_once('|').unwrap_or((line, ""));
        let features = features.split(',').filter(|f| !f.is_empty()).map(str::to_string);
        packages.entry(package.to_string()).or_insert_with(BTreeSet::new).extend(features);
    }
    packages
}

#[test]
fn the_library_and_the_tests_build_its_dependencies_with_the_same_features() {
    let library = features(&["-p", "twinray", "--edges", "normal,build"]);
    let tests = features(&["--workspace", "--edges", "normal,build,dev"]);
    assert!(library.len() > 100, "cargo tree listed {} packages", library.len());
    let differ: Vec<String> = library
        .iter()
        .filter(|(package, features)| tests.get(*package).is_some_and(|t| t != *features))
        .map(|(package, features)| {
            let more: Vec<&String> = tests[package].difference(features).collect();
            format!("{package}: the tests add {more:?}")
        })
        .collect();
    assert!(differ.is_empty(), "turn these on in app/Cargo.toml:\n{}", differ.join("\n"));
}

/// Crates a program that renders with twinray should not have to link: the command line's,
/// the live viewer's web server and file watching, and the bench's plots.
const APP_ONLY: &[&str] =
    &["clap", "axum", "tokio", "tokio-stream", "hyper", "hyper-util", "notify", "plotters", "env_logger", "indicatif"];

#[test]
fn the_render_library_links_no_crate_of_the_app() {
    for args in [&["-p", "twinray-host", "--edges", "normal"][..], &["-p", "twinray-host", "--edges", "normal,build"]] {
        let packages = features(args);
        assert!(packages.len() > 50, "cargo tree listed {} packages", packages.len());
        let linked: Vec<&String> =
            packages.keys().filter(|p| APP_ONLY.contains(&p.split(' ').next().unwrap_or_default())).collect();
        assert!(linked.is_empty(), "twinray-host ({args:?}) depends on the app's {linked:?}");
    }
    // The check can fail: the app itself links them.
    let app = features(&["-p", "twinray", "--edges", "normal"]);
    assert!(app.keys().any(|p| p.starts_with("axum ")) && app.keys().any(|p| p.starts_with("clap ")));
}
