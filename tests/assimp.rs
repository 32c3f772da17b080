//! Models no one here made: Debian's assimp-testmodels (installed by `cargo xtask setup`).
//! Every glTF 2.0 file of its glTF2 folder is loaded as a scene. Each one twinray models renders with the Rust
//! and the GLSL set within the default parity tolerance (no hit mismatch away from a
//! silhouette), on lavapipe with validation on; each one it cannot render is refused as bad
//! input with its fault named. Which is which is not decided here: the lists below only pin
//! the models already known to render and to be malformed, so that neither kind can slip into
//! the other unnoticed. Every OBJ file of its OBJ folder loads as a mesh or is refused naming
//! the file, and two of them render alike in both sets; opened as scenes of their own, with
//! their material libraries and textures, they load or are refused the same way, and the
//! textured spider renders alike in both sets.

use std::path::Path;
use twinray_host::scene::file::MaterialDesc;
use twinray_host::scene::shape::Normals;
use twinray_host::Scene;
use twinray_tests::{render_scene, validated_context, SCENE_TEST_SIZE};

use twinray_host::scene::gltf::ASSIMP_TEST_MODELS as MODELS;

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

/// Rust against GLSL on `scene` at `SCENE_TEST_SIZE`: within its parity, and something hit.
fn renders_alike(ctx: &std::sync::Arc<twinray_host::Context>, scene: &Scene, name: &str) {
    let (rust, glsl) = (render_scene(ctx, scene, "rust"), render_scene(ctx, scene, "glsl"));
    let parity = scene.file.parity;
    let d = twinray_host::compare::scene_diff(scene, &rust, &glsl);
    let failures = twinray_host::compare::verdict(&d, &parity, u64::from(SCENE_TEST_SIZE.0 * SCENE_TEST_SIZE.1));
    eprintln!("{name}: rmse {:.6}, {} hit mismatches", d.color.rmse, d.hit_mismatches);
    assert!(failures.is_empty(), "{name}: rust against glsl: {failures:?}");
    assert!(twinray_host::compare::hit_count(&rust) > 0, "{name}: the model is not in the picture");
    // Every mesh built once, in a BLAS of its own or with the other primitives its node places
    // alike (`scene::merge`), kept no larger than built (compacted where the driver can).
    let a = rust.accel;
    let triangles: usize = scene.meshes.values().map(|m| m.indices.len() / 3).sum();
    assert_eq!(a.triangles, triangles as u64, "{name}: {a}");
    assert!((1..=scene.meshes.len()).contains(&a.blases), "{name}: {a}");
    assert!(a.blas_bytes > 0 && a.blas_bytes <= a.blas_built_bytes && a.tlas_bytes > 0, "{name}: {a}");
}

#[test]
fn every_model_renders_alike_in_both_sets_or_is_refused_with_its_fault_named() {
    let files = twinray_host::scene::gltf::models_under(Path::new(MODELS));
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
                assert!(matches!(e, twinray_host::Error::Scene { .. }), "{name}: not bad input: {e}");
                eprintln!("{name}: refused: {e}");
                refused.push((name, e.to_string()));
                continue;
            }
        };
        renders_alike(&ctx, &scene, &name);
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

const OBJ_MODELS: &str = "/usr/share/assimp/models/OBJ";

/// OBJ files that must load (odd encodings and material names included), and that must not.
const OBJ_LOADED: [&str; 7] =
    ["WusonOBJ.obj", "spider.obj", "regr01.obj", "empty_mat.obj", "box_UTF16BE.obj", "concave_polygon.obj", "box.obj"];
const OBJ_REFUSED: [(&str, &str); 3] = [
    ("number_formats.obj", "position parse error"),
    ("point_cloud.obj", "has no triangles"),
    ("testpoints.obj", "has no triangles"),
];

/// A scene of one OBJ mesh from `OBJ_MODELS`, framed by hand: the models are about 10 units wide.
fn obj_scene(file: &str) -> Scene {
    let text = format!(
        "[image]\nwidth = 160\nheight = 120\n[camera]\neye = [10.0, 8.0, 30.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_degrees = 45.0\n\
         [materials.m]\nkind = \"diffuse\"\ncolor = [0.8, 0.8, 0.8]\n[[lights]]\nkind = \"directional\"\ndirection = [1.0, 2.0, 1.5]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n\
         [shapes.s]\nkind = \"mesh\"\nfile = \"{file}\"\nnormals = \"smooth\"\n[[objects]]\nshape = \"s\"\nmaterial = \"m\"\n"
    );
    Scene::parse(&text, file, twinray_host::scene::MeshFiles::Folder(OBJ_MODELS.into()))
        .unwrap_or_else(|e| panic!("{file}: {e}"))
}

#[test]
fn every_obj_model_loads_or_is_refused_naming_the_file() {
    let mut files: Vec<_> = std::fs::read_dir(OBJ_MODELS).into_iter().flatten().flatten().map(|e| e.path()).collect();
    files.retain(|p| p.extension().is_some_and(|e| e == "obj"));
    files.sort();
    assert!(files.len() >= 20, "{OBJ_MODELS} holds {} OBJ files: run `cargo xtask setup`", files.len());
    let mut loaded = Vec::new();
    for path in &files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        match twinray_host::scene::mesh::load_obj(path, Normals::Smooth) {
            Ok(mesh) => {
                assert!(!mesh.indices.is_empty(), "{name}");
                loaded.push(name);
            }
            Err(e) => {
                eprintln!("{name}: refused: {e}");
                assert!(e.contains(&name), "{name}: {e:?} does not name the file");
                if let Some((_, fault)) = OBJ_REFUSED.iter().find(|(f, _)| *f == name) {
                    assert!(e.contains(fault), "{name}: {e:?} does not say {fault:?}");
                }
            }
        }
    }
    for want in OBJ_LOADED {
        assert!(loaded.iter().any(|l| l == want), "{want} did not load");
    }
    for (refused, _) in OBJ_REFUSED {
        assert!(!loaded.iter().any(|l| l == refused), "{refused} loaded");
    }
    let ctx = validated_context();
    for file in ["WusonOBJ.obj", "spider.obj"] {
        renders_alike(&ctx, &obj_scene(file), file);
    }
}

#[test]
fn every_obj_model_opens_as_a_scene_with_its_materials_or_is_refused_naming_the_file() {
    let mut opened = Vec::new();
    for path in std::fs::read_dir(OBJ_MODELS).into_iter().flatten().flatten().map(|e| e.path()) {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if !name.ends_with(".obj") {
            continue;
        }
        match Scene::load(path.to_str()) {
            Ok(scene) => opened.push((name, scene)),
            Err(e) => {
                let e = e.to_string();
                assert!(e.contains(&name), "{name}: {e:?} does not name the file");
                let fault = OBJ_REFUSED.iter().find(|(f, _)| *f == name).map(|(_, fault)| *fault);
                assert!(fault.is_some(), "{name} refused: {e}");
            }
        }
    }
    for want in OBJ_LOADED {
        assert!(opened.iter().any(|(l, _)| l == want), "{want} did not open");
    }
    let materials = |scene: &Scene| scene.file.materials.values().cloned().collect::<Vec<_>>();
    let textured = |m: &MaterialDesc| matches!(m, MaterialDesc::Diffuse { texture: Some(t), .. } if t.image.is_some());
    let (_, spider) = opened.iter().find(|(n, _)| n == "spider.obj").unwrap();
    // Its library names five images (one for Brusttex, a material no face uses), as `.\\name.jpg`.
    assert_eq!(materials(spider).iter().filter(|m| textured(m)).count(), 4, "{:?}", materials(spider));
    let (_, regr) = opened.iter().find(|(n, _)| n == "regr01.obj").unwrap();
    let colours: std::collections::BTreeSet<String> = materials(regr)
        .iter()
        .map(|m| match m {
            MaterialDesc::Diffuse { color, .. } => format!("{color:?}"),
            other => panic!("{other:?}"),
        })
        .collect();
    assert!(colours.len() >= 3, "regr01's library colours its groups: {colours:?}");
    renders_alike(&validated_context(), spider, "spider.obj as a scene");
}

/// The engine of assimp's glTF2 folder (75,730 triangles in 34 primitives).
const ENGINE: &str = "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

/// A scene around `body`: the engines' view, a light, and glTF shapes and objects.
fn engines(body: &str) -> Scene {
    let text = format!(
        "[image]\nwidth = 160\nheight = 120\n[camera]\neye = [2500.0, 1800.0, 3500.0]\ntarget = [600.0, 0.0, 600.0]\n\
         up = [0.0, 1.0, 0.0]\nfov_y_degrees = 45.0\n[[lights]]\nkind = \"directional\"\ndirection = [1.0, 2.0, 1.5]\n\
         color = [1.0, 1.0, 1.0]\nintensity = 1.0\n{body}"
    );
    Scene::parse(&text, "engines.toml", twinray_host::scene::MeshFiles::Folder(MODELS.into()))
        .expect("the engines' scene")
}

/// Over a million triangles of a model no one here made, placed by a scene file: 16 instances
/// of one model in a grid (its BLASes shared), and 14 copies each with BLASes of their own.
#[test]
fn a_million_triangles_of_a_real_model_render_alike_instanced_and_not() {
    let ctx = validated_context();
    let model = |name: &str| format!("[shapes.{name}]\nkind = \"gltf\"\nfile = \"{ENGINE}\"\n");
    let grid =
        "[[grids]]\nshape = \"engine\"\nmaterials = [\"\"]\ncount = [4, 2, 2]\nspacing = [400.0, 300.0, 900.0]\n";
    let instanced = engines(&format!("{}{grid}", model("engine")));
    let separate = engines(
        &(0..14)
            .map(|i| {
                let at = [(i % 4) as f32 * 400.0, ((i / 4) % 2) as f32 * 300.0, (i / 8) as f32 * 900.0];
                format!("{}[[objects]]\nshape = \"e{i}\"\ntranslate = {at:?}\n", model(&format!("e{i}")))
            })
            .collect::<String>(),
    );
    // The model's 34 primitives make 29 BLASes: a node's primitives placed alike share one.
    for (label, scene, blases) in [("instanced", &instanced, 29), ("separate", &separate, 14 * 29)] {
        let out = render_scene(&ctx, scene, "rust");
        let a = out.accel;
        eprintln!("{label}: {a}");
        assert_eq!(a.blases, blases, "{label}");
        assert!(a.instanced_triangles >= 1_000_000, "{label}: {a}");
        renders_alike(&ctx, scene, label);
    }
}
