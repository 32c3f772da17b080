//! glTF models no one here made: every glTF 2.0 file of Debian's assimp-testmodels (installed
//! by `cargo xtask setup`), loaded as a scene. Each one twinray models renders with the Rust
//! and the GLSL set within the default parity tolerance (no hit mismatch away from a
//! silhouette), on lavapipe with validation on; each one it cannot render is refused as bad
//! input with its fault named. Which is which is not decided here: the lists below only pin
//! the models already known to render and to be malformed, so that neither kind can slip into
//! the other unnoticed.

use std::path::Path;
use twinray::Scene;
use twinray_tests::{render_scene, validated_context, SCENE_TEST_SIZE};

use twinray::scene::gltf::ASSIMP_TEST_MODELS as MODELS;

/// Models that must render, relative to `MODELS`.
const RENDERED: [&str; 14] = [
    "2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
    "BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
    "BoxTexcoords-glTF/boxTexcoords.gltf",
    "BoxTextured-glTF-Binary/BoxTextured.glb",
    "BoxTextured-glTF-Embedded/BoxTextured.gltf",
    "BoxTextured-glTF/BoxTextured.gltf",
    "ClearCoat-glTF/ClearCoatTest.gltf",
    "cameras/Cameras.gltf",
    "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf",
    "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf",
    "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf",
    "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
    "simple_skin/simple_skin.gltf",
    "textureTransform/TextureTransformTest.gltf",
];

/// Models that must be refused, and words of their fault.
const REFUSED: [(&str, &str); 10] = [
    ("IndexOutOfRange/IndexOutOfRange.gltf", "indexes vertex 255, past its 24 vertices"),
    ("IndexOutOfRange/AllIndicesOutOfRange.gltf", "past its 24 vertices"),
    ("MissingBin/BoxTextured.gltf", "buffer 0: cannot read"),
    ("RecursiveNodes/RecursiveNodes.gltf", "has a cycle"),
    ("BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf", "requires the extension KHR_technique_webgl"),
    ("draco/2CylinderEngine.gltf", "requires the extension KHR_draco_mesh_compression"),
    ("SchemaFailures/sceneWrongType.gltf", "not a valid glTF 2.0 file"),
    ("wrongTypes/badNumber.gltf", "not a valid glTF 2.0 file"),
    ("glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf", "places no triangles (ignored: Points"),
    ("TestNoRootNode/NoScene.gltf", "not a valid glTF 2.0 file"),
];

#[test]
fn every_model_renders_alike_in_both_sets_or_is_refused_with_its_fault_named() {
    let files = twinray::scene::gltf::models_under(Path::new(MODELS));
    assert!(
        files.len() >= 40,
        "{MODELS} holds {} glTF files: run `cargo xtask setup` (assimp-testmodels)",
        files.len()
    );
    let ctx = validated_context();
    let (mut rendered, mut refused) = (Vec::new(), Vec::new());
    for path in &files {
        let name = path.strip_prefix(MODELS).unwrap().display().to_string();
        let scene = match Scene::load(path.to_str()) {
            Ok(scene) => scene,
            Err(e) => {
                assert!(matches!(e, twinray::Error::Scene { .. }), "{name}: not bad input: {e}");
                eprintln!("{name}: refused: {e}");
                refused.push((name, e.to_string()));
                continue;
            }
        };
        let (rust, glsl) = (render_scene(&ctx, &scene, "rust"), render_scene(&ctx, &scene, "glsl"));
        let parity = scene.file.parity;
        let d = twinray::compare::diff(&rust, &glsl, parity.pixel_threshold);
        let failures = twinray::compare::verdict(&d, &parity, u64::from(SCENE_TEST_SIZE.0 * SCENE_TEST_SIZE.1));
        eprintln!("{name}: rmse {:.6}, {} hit mismatches", d.color.rmse, d.hit_mismatches);
        assert!(failures.is_empty(), "{name}: rust against glsl: {failures:?}");
        assert!(twinray::compare::hit_count(&rust) > 0, "{name}: the model is not in the picture");
        rendered.push(name);
    }
    for want in RENDERED {
        assert!(rendered.iter().any(|r| r == want), "{want} did not render: {refused:?}");
    }
    for (want, fault) in REFUSED {
        let Some((_, e)) = refused.iter().find(|(r, _)| r == want) else { panic!("{want} was not refused") };
        assert!(e.contains(fault) && e.contains(want), "{want}: {e:?} does not name {fault:?} and the file");
    }
}
