//! The fuzz targets' committed corpus (`fuzz/corpus/TARGET/`), fed through the same entry
//! points (`twinray_host::fuzz`) by plain `cargo test`: CI runs the seeds, never the fuzzer.
//! A seed that panics here is a fuzz finding that came back.

use twinray_tests::repo_root as repo;

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
    run_seeds("scene", twinray_host::fuzz::scene);
}

#[test]
fn obj_seeds() {
    run_seeds("obj", twinray_host::fuzz::obj);
}

#[test]
fn module_seeds() {
    run_seeds("module", twinray_host::fuzz::module);
}

#[test]
fn probe_case_seeds() {
    run_seeds("probe_case", twinray_host::fuzz::probe_case);
}

#[test]
fn gltf_seeds() {
    run_seeds("gltf", twinray_host::fuzz::gltf);
}

/// The short run of the glTF fuzz campaign that `cargo test` makes: each committed seed
/// through 16 chains of 8 mutations of the fuzz target's own structure-aware mutator, from
/// fixed seeds (the same inputs every run), each input fed to the target. The long runs are `cargo fuzz`'s
/// (docs/testing.md); this keeps what they reached reachable.
#[test]
fn gltf_mutations_short_run() {
    use twinray_host::fuzz::mutate::{self, Rng};
    let dir = repo().join("fuzz/corpus/gltf");
    // The named seeds (assimp's models and the hand-written faults, files with an extension),
    // not the fuzzer's finds (named by their hash), which gltf_seeds feeds as they are.
    let mut seeds: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some() || p.file_name().is_some_and(|n| n == "empty"))
        .collect();
    seeds.sort();
    let mut fed = 0;
    for (i, seed) in seeds.iter().enumerate() {
        let original = std::fs::read(seed).unwrap();
        for chain in 0..16 {
            let mut rng = Rng::new((i * 16 + chain) as u64);
            let mut bytes = original.clone();
            for step in 0..8 {
                bytes = mutate::gltf(&bytes, &mut rng, &mut mutate::flip_bytes);
                let input = bytes.clone();
                let result = std::panic::catch_unwind(|| twinray_host::fuzz::gltf(&input));
                assert!(result.is_ok(), "{}: chain {chain} mutation {step} panicked", seed.display());
                fed += 1;
            }
        }
    }
    assert!(fed >= 128 * 10, "only {fed} inputs fed");
}

/// The mutator reaches the classes of fault the loader checks for: from the assimp
/// BoxTextured model, 4000 mutations include files refused for a view's stride below its
/// element, an accessor offset not a multiple of its component, an image larger than the
/// budget by its header, and the node graph rules (a second parent, a cycle, a matrix with
/// TRS).
#[test]
fn the_mutator_reaches_the_loaders_checks() {
    use twinray_host::fuzz::mutate::{self, Rng};
    let seed = repo().join("fuzz/corpus/gltf/assimp-BoxTextured-glTF-Binary-BoxTextured.glb");
    let original = std::fs::read(seed).unwrap();
    let mut errors = Vec::new();
    for k in 0..4000 {
        let bytes = mutate::gltf(&original, &mut Rng::new(k), &mut mutate::flip_bytes);
        if let Err(e) = twinray_host::scene::gltf::parse(&bytes, std::path::Path::new("/nonexistent/fuzz")) {
            errors.push(e);
        }
    }
    let classes: [&[&str]; 6] = [
        &["byteStride"],
        &["not a multiple"],
        &["bytes decoded", "on a side"],
        &["is a child of both"],
        &["its own ancestor"],
        &["both a matrix and"],
    ];
    for class in classes {
        let found = errors.iter().any(|e| class.iter().any(|c| e.contains(c)));
        assert!(found, "no mutation was refused for {class:?}: {:?}", &errors[..errors.len().min(20)]);
    }
}

/// The same from assimp's skinned model and Khronos' morphed cube: their mutations include
/// files refused for each rule on skins, morph targets and animations the mutator aims at
/// (`twinray_host::fuzz::rig_faults`), and none panics.
#[test]
fn the_mutator_reaches_the_rules_on_skins_morphs_and_animations() {
    use twinray_host::fuzz::mutate::{self, Rng};
    let mut errors = Vec::new();
    for name in
        ["assimp-simple_skin-simple_skin.glb", "assimp-glTF-Sample-Models-AnimatedMorphCube-glTF-AnimatedMorphCube.glb"]
    {
        let original = std::fs::read(repo().join("fuzz/corpus/gltf").join(name)).unwrap();
        for k in 0..3000 {
            let bytes = mutate::gltf(&original, &mut Rng::new(k), &mut mutate::flip_bytes);
            if let Err(e) = twinray_host::scene::gltf::parse(&bytes, std::path::Path::new("/nonexistent/fuzz")) {
                errors.push(e);
            }
        }
    }
    let classes = [
        "weights for its",
        "morph targets, its primitive 0",
        "inverse bind matrices",
        "drives node",
        "keys of",
        "orthographic with an xmag of 0",
        "is normalized but of",
    ];
    for class in classes {
        let found = errors.iter().any(|e| e.contains(class));
        assert!(found, "no mutation was refused for {class:?}: {:?}", &errors[..errors.len().min(20)]);
    }
}
