//! The fuzz targets' committed corpus (`fuzz/corpus/TARGET/`), fed through the same entry
//! points (`twinray::fuzz`) by plain `cargo test`: CI runs the seeds, never the fuzzer.
//! A seed that panics here is a fuzz finding that came back.

mod common;

use common::repo;

fn run_seeds(target: &str, feed: fn(&[u8])) {
    let dir = repo().join("fuzz/corpus").join(target);
    let mut seeds: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    seeds.sort();
    assert!(seeds.len() >= 10, "{target}: only {} seeds in {}", seeds.len(), dir.display());
    for seed in seeds {
        let bytes = std::fs::read(&seed).unwrap();
        let fed = std::panic::catch_unwind(|| feed(&bytes));
        assert!(fed.is_ok(), "{target}: seed {} panicked", seed.display());
    }
}

#[test]
fn scene_seeds() {
    run_seeds("scene", twinray::fuzz::scene);
}

#[test]
fn obj_seeds() {
    run_seeds("obj", twinray::fuzz::obj);
}

#[test]
fn module_seeds() {
    run_seeds("module", twinray::fuzz::module);
}

#[test]
fn probe_case_seeds() {
    run_seeds("probe_case", twinray::fuzz::probe_case);
}

#[test]
fn gltf_seeds() {
    run_seeds("gltf", twinray::fuzz::gltf);
}
