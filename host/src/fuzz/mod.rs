//! What the fuzz targets (`fuzz/`, run with `cargo fuzz`) and their seed test
//! (`app/tests/fuzz_seeds.rs`, run by `cargo test`) feed arbitrary bytes. Each goes as far
//! as input can reach without a GPU: parse, check, then build what a render or probe would
//! build from the result. An `Err` is the right answer to bad input; a panic, a hang or an
//! allocation that eats the machine is a finding.

pub mod faults;
pub mod graph_faults;
pub mod mutate;
pub mod rig_faults;
pub mod rng;

use crate::probe::case::ProbeCase;
use crate::reference::scene::SceneReference;
use crate::scene::shape::Normals;
use crate::scene::{mesh, MeshFiles, Scene};

/// A scene file: parsed, checked, its GPU data built and its reference made.
pub fn scene(bytes: &[u8]) {
    let Ok(text) = std::str::from_utf8(bytes) else { return };
    if let Ok(scene) = Scene::parse(text, "fuzz.toml", MeshFiles::Builtin) {
        let _ = scene.build();
        let _ = SceneReference::new(&scene);
    }
}

/// An OBJ file, with flat and with smooth normals.
pub fn obj(bytes: &[u8]) {
    for normals in [Normals::Flat, Normals::Smooth] {
        let _ = mesh::parse_obj(bytes, "fuzz.obj", normals);
    }
}

/// A glTF file (JSON or GLB; buffer files would be looked for in a folder that does not
/// exist): parsed, its meshes read, and the scene it makes checked and built.
pub fn gltf(bytes: &[u8]) {
    if let Ok(model) = crate::scene::gltf::parse(bytes, std::path::Path::new("/nonexistent/fuzz")) {
        if let Ok(scene) = Scene::from_model(model, "fuzz.gltf") {
            let _ = scene.build();
            let _ = SceneReference::new(&scene);
        }
    }
}

/// A SPIR-V module from disk, as a damaged or hostile one reaches twinray: read, and checked
/// as every module of the catalog (entry point, bindings, what it passes between stages), and
/// its unused ray query declaration dropped. (SPIRV-Tools' validator runs before these in
/// twinray; it is a separate program, fuzzed upstream.)
pub fn module(bytes: &[u8]) {
    let Ok(info) = twinray_shared::spirv_info::parse(bytes) else { return };
    for spec in crate::sets::MODULES {
        let entry = spec.find_entry(&info).unwrap_or_else(|| spec.name.to_string());
        let _ = twinray_shared::module_check::check_module(
            spec,
            &info,
            &entry,
            twinray_shared::interface::MAX_DECLARED_DEPTH,
        );
    }
    let _ = twinray_shared::spirv_info::without_unused_ray_query(bytes);
}

/// A probe case: parsed, its scene loaded (built-in names only: the folder does not exist),
/// its rays generated and checked.
pub fn probe_case(bytes: &[u8]) {
    let Ok(text) = std::str::from_utf8(bytes) else { return };
    let _ = ProbeCase::parse(text, "fuzz.toml", std::path::PathBuf::from("/nonexistent/fuzz"));
}
