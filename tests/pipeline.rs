//! The host builds only what a scene needs: the pipeline of the spheres-only scene has the
//! sphere hit group and no shadow miss shader; a scene whose light casts shadows adds it; and
//! every stage is specialised on the features the scene uses (twinray_shared::features), in
//! both sets alike: specialising changes no pixel, and dropping a used feature changes the
//! image the same way in Rust and GLSL (so each language reads each feature's bit).

use twinray_host::render::layout::LayoutDraw;
use twinray_host::render::pipeline::ScenePipeline;
use twinray_host::scene::{MeshFiles, Renderer, Scene};
use twinray_shared::features;
use twinray_tests::{assert_same_render, default_scene, render_scene, set, validated_context, SCENE_TEST_SIZE};

#[test]
fn spheres_only_scene_builds_one_hit_group_and_no_shadow_miss() {
    let scene = default_scene();
    let plan = scene.build().plan;
    let groups: Vec<_> = plan.hit_groups.iter().map(|g| g.name()).collect();
    assert_eq!(groups, ["sphere"]);
    assert!(!plan.shadows, "the sphere scene's light casts no shadows");
    let ctx = validated_context();
    let pipeline =
        ScenePipeline::new(&ctx, &set("rust"), &plan, ("raygen", LayoutDraw::Sbt), Some(&Default::default()))
            .expect("pipeline");
    assert_eq!(pipeline.modules, ["raygen", "miss", "sphere_intersection", "procedural_closest_hit"]);
    assert_eq!(pipeline.sbt_records, [vec![0], vec![1], vec![2], vec![]]);
    drop(pipeline);
    ctx.check_validation().expect("no validation errors");
}

#[test]
fn a_shadow_casting_light_adds_the_shadow_miss_shader() {
    let mut scene = default_scene();
    for light in &mut scene.file.lights {
        if let twinray_host::scene::file::LightDesc::Directional { shadows, .. } = light {
            *shadows = true;
        }
    }
    let plan = scene.build().plan;
    assert!(plan.shadows);
    let ctx = validated_context();
    let pipeline =
        ScenePipeline::new(&ctx, &set("glsl"), &plan, ("raygen", LayoutDraw::Sbt), Some(&Default::default()))
            .expect("pipeline");
    assert!(pipeline.modules.contains(&"shadow_miss"));
    assert_eq!(pipeline.sbt_records, [vec![0], vec![1, 2], vec![3], vec![]]);
}

/// Callable materials add one callable group per callable the scene's material kinds use, and
/// a callable record for every material kind, each pointing at its kind's callable.
#[test]
fn callable_materials_get_a_record_per_material_kind() {
    let mut scene = twinray_host::scene::Scene::load(Some("showcase")).expect("showcase");
    scene.file.material_shading = twinray_host::scene::MaterialShading::Callable;
    let plan = scene.build().plan;
    assert_eq!(plan.callables(), ["flat_material", "checker_material"]);
    let ctx = validated_context();
    let pipeline =
        ScenePipeline::new(&ctx, &set("rust"), &plan, ("raygen", LayoutDraw::Sbt), Some(&Default::default()))
            .expect("pipeline");
    let hits = plan.hit_groups.len() as u32;
    let (flat, checker) = (3 + hits, 4 + hits);
    // Kinds: diffuse, emissive, checker, cutout.
    assert_eq!(pipeline.sbt_records[3], [flat, flat, checker, flat]);
    assert_eq!(pipeline.group_count, checker + 1);
    assert!(pipeline.modules.contains(&"procedural_closest_hit_callable"));
    assert!(!pipeline.modules.contains(&"procedural_closest_hit"));
}

/// `scene` specialised on the features `names` instead of those it uses.
fn with_features(scene: &Scene, names: &[&str]) -> Scene {
    let mut s = scene.clone();
    s.file.features = Some(names.iter().map(|n| n.to_string()).collect());
    s
}

/// A sphere that emits a 2x2 checker texture (written into `dir`) beside a diffuse one.
fn textured_scene(dir: &std::path::Path) -> Scene {
    let texture = image::RgbaImage::from_fn(2, 2, |x, y| {
        let v = if (x + y) % 2 == 0 { 255 } else { 40 };
        image::Rgba([v, 255 - v, 128, 255])
    });
    texture.save(dir.join("checker.png")).unwrap();
    let text = r#"
[image]
width = 160
height = 120
[camera]
eye = [0.0, 1.0, 6.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 40.0
[materials.lit]
kind = "diffuse"
color = [0.2, 0.2, 0.2]
emission = { color = [1.0, 1.0, 1.0], intensity = 1.0, texture = { file = "checker.png" } }
[[lights]]
kind = "directional"
direction = [-1.0, -1.0, -1.0]
color = [1.0, 1.0, 1.0]
intensity = 2.0
[shapes.ball]
kind = "sphere"
radius = 1.5
[[objects]]
shape = "ball"
material = "lit"
"#;
    let path = dir.join("textured.toml");
    std::fs::write(&path, text).unwrap();
    Scene::load(Some(path.to_str().unwrap())).expect("the textured scene loads")
}

#[test]
fn a_scene_uses_the_features_its_materials_and_lights_need() {
    let uses = |name: &str| features::names(Scene::load(Some(name)).unwrap().build().plan.features);
    assert_eq!(uses("spheres"), "none");
    assert_eq!(uses("lights"), "area-lights,emission");
    assert_eq!(uses("cutout"), "alpha-masks");
    assert_eq!(uses("materials"), "emission");
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(features::names(textured_scene(dir.path()).build().plan.features), "textures,emission");
    let all = features::names(features::ALL);
    let all: Vec<&str> = all.split(',').collect();
    assert_eq!(with_features(&default_scene(), &all).build().plan.features, features::ALL);
    let text = "features = [\"shading\"]\n[image]\nwidth = 8\nheight = 8\n[camera]\neye = [0.0, 0.0, 1.0]\n\
                target = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_degrees = 40.0\n[shapes.s]\nkind = \"sphere\"\n\
                radius = 1.0\n[[objects]]\nshape = \"s\"\n";
    let Err(err) = Scene::parse(text, "bad", MeshFiles::Builtin) else { panic!("an unknown feature is refused") };
    let err = err.to_string();
    assert!(err.contains("no feature \"shading\"") && err.contains("area-lights"), "{err}");
}

/// Renders `scene` with `set_text` as it is, with every feature's code and without `drop`;
/// asserts the first two render alike, the third differently, and returns the third.
fn dropped(scene: &Scene, set_text: &str, drop: &str) -> twinray_host::RenderOutput {
    let ctx = validated_context();
    let all = features::names(features::ALL);
    let all: Vec<&str> = all.split(',').collect();
    let used = features::names(scene.build().plan.features);
    let without: Vec<&str> = used.split(',').filter(|f| *f != drop).collect();
    let [own, every, less] = [scene.clone(), with_features(scene, &all), with_features(scene, &without)]
        .map(|s| render_scene(&ctx, &s, set_text));
    let label = format!("{set_text} with every feature");
    assert_same_render(&label, &own, &every, scene);
    assert_eq!(own.rgba, every.rgba, "{}: specialising {set_text} on {used} changed pixels", scene.name());
    assert_ne!(own.rgba, less.rgba, "{}: {set_text} without {drop} renders as with it", scene.name());
    ctx.check_validation().expect("no validation errors");
    less
}

#[test]
fn each_feature_is_read_by_both_sets_and_specialising_changes_no_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let mut cutout = Scene::load(Some("cutout")).unwrap();
    // Pipelines decide cutouts in any-hit stages only cutout objects have; inline rays read the bit.
    cutout.file.renderer = Renderer::Compute;
    let cases = [
        (textured_scene(dir.path()), "textures"),
        (Scene::load(Some("lights")).unwrap(), "area-lights"),
        (Scene::load(Some("materials")).unwrap(), "emission"),
        (cutout, "alpha-masks"),
    ];
    for (scene, feature) in cases {
        let [rust, glsl] = ["rust", "glsl"].map(|set_text| dropped(&scene, set_text, feature));
        assert_same_render(&format!("without {feature}"), &rust, &glsl, &scene);
        eprintln!(
            "{}: without {feature}, {}x{} in both sets alike",
            scene.name(),
            SCENE_TEST_SIZE.0,
            SCENE_TEST_SIZE.1
        );
    }
}
