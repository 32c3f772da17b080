//! Malformed glTF and OBJ files no one here wrote (Debian's assimp-testmodels, installed by
//! `cargo xtask setup`), given to every command that loads a scene: each ends with exit code 2
//! and one line naming the file, writes nothing and never panics. Which files are malformed is
//! what the loader says (tests/assimp.rs pins the known ones); a file that loads is skipped.

mod common;

use common::assert_bad_input;
use std::path::{Path, PathBuf};

use twinray::scene::gltf::ASSIMP_TEST_MODELS as MODELS;

#[test]
fn every_command_refuses_a_malformed_model_in_one_line() {
    let malformed: Vec<PathBuf> = twinray::scene::gltf::models_under(Path::new(MODELS))
        .into_iter()
        .filter(|p| twinray::Scene::load(p.to_str()).is_err())
        .collect();
    assert!(malformed.len() >= 10, "{} malformed models in {MODELS}: run `cargo xtask setup`", malformed.len());
    every_command_refuses(&malformed);
}

/// OBJ files opened as scenes: those that do not parse or have no faces.
#[test]
fn every_command_refuses_a_malformed_obj_file_in_one_line() {
    let folder = Path::new("/usr/share/assimp/models/OBJ");
    let mut malformed: Vec<PathBuf> =
        std::fs::read_dir(folder).into_iter().flatten().flatten().map(|e| e.path()).collect();
    malformed.retain(|p| p.extension().is_some_and(|e| e == "obj") && twinray::Scene::load(p.to_str()).is_err());
    assert!(
        malformed.len() >= 3,
        "{} malformed OBJ files in {}: run `cargo xtask setup`",
        malformed.len(),
        folder.display()
    );
    every_command_refuses(&malformed);
}

fn every_command_refuses(malformed: &[PathBuf]) {
    for path in malformed {
        let file = path.to_str().unwrap();
        for command in [
            &["render", file, "--out", "x.png"][..],
            &["compare", file, "--out-dir", "out"],
            &["bisect", file],
            &["explain", file, "--pixel", "1,1"],
            &["reference", file, "--out", "ref.png"],
            &["bench", file, "--out", "bench"],
        ] {
            assert_bad_input(command, &[file]);
        }
    }
}
