//! One build of every dependency: `cargo build -p twinray` (what a user installs and what the
//! tutorial's copy runs) and the workspace's tests give every crate of the library's build the
//! same features, so cargo builds it once for both. A dependency of the tests that turns on
//! another feature of one of them builds it, and all that depends on it, this library
//! included, a second time; host/Cargo.toml turns such features on for the library too.

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
    assert!(differ.is_empty(), "turn these on in host/Cargo.toml:\n{}", differ.join("\n"));
}
