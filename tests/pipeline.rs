//! The host builds only what a scene needs: the pipeline of the spheres-only scene has the
//! sphere hit group and no shadow miss shader; a scene whose light casts shadows adds it.

use twinray::render::pipeline::ScenePipeline;
use twinray_tests::{default_scene, set, validated_context};

#[test]
fn spheres_only_scene_builds_one_hit_group_and_no_shadow_miss() {
    let scene = default_scene();
    let plan = scene.build().plan;
    let groups: Vec<_> = plan.hit_groups.iter().map(|g| g.name()).collect();
    assert_eq!(groups, ["sphere"]);
    assert!(!plan.shadows, "the sphere scene's light casts no shadows");
    let ctx = validated_context();
    let pipeline =
        ScenePipeline::new(&ctx, &set("rust"), &plan, "raygen", Some(&Default::default())).expect("pipeline");
    assert_eq!(pipeline.modules, ["raygen", "miss", "sphere_intersection", "procedural_closest_hit"]);
    assert_eq!(pipeline.sbt_records, [vec![0], vec![1], vec![2], vec![]]);
    drop(pipeline);
    ctx.check_validation().expect("no validation errors");
}

#[test]
fn a_shadow_casting_light_adds_the_shadow_miss_shader() {
    let mut scene = default_scene();
    for light in &mut scene.file.lights {
        if let twinray::scene::file::LightDesc::Directional { shadows, .. } = light {
            *shadows = true;
        }
    }
    let plan = scene.build().plan;
    assert!(plan.shadows);
    let ctx = validated_context();
    let pipeline =
        ScenePipeline::new(&ctx, &set("glsl"), &plan, "raygen", Some(&Default::default())).expect("pipeline");
    assert!(pipeline.modules.contains(&"shadow_miss"));
    assert_eq!(pipeline.sbt_records, [vec![0], vec![1, 2], vec![3], vec![]]);
}

/// Callable materials add one callable group per callable the scene's material kinds use, and
/// a callable record for every material kind, each pointing at its kind's callable.
#[test]
fn callable_materials_get_a_record_per_material_kind() {
    let mut scene = twinray::scene::Scene::load(Some("showcase")).expect("showcase");
    scene.file.material_shading = twinray::scene::MaterialShading::Callable;
    let plan = scene.build().plan;
    assert_eq!(plan.callables(), ["flat_material", "checker_material"]);
    let ctx = validated_context();
    let pipeline =
        ScenePipeline::new(&ctx, &set("rust"), &plan, "raygen", Some(&Default::default())).expect("pipeline");
    let hits = plan.hit_groups.len() as u32;
    let (flat, checker) = (3 + hits, 4 + hits);
    // Kinds: diffuse, emissive, checker, cutout.
    assert_eq!(pipeline.sbt_records[3], [flat, flat, checker, flat]);
    assert_eq!(pipeline.group_count, checker + 1);
    assert!(pipeline.modules.contains(&"procedural_closest_hit_callable"));
    assert!(!pipeline.modules.contains(&"procedural_closest_hit"));
}
