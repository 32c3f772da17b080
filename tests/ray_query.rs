//! Ray queries (`VK_KHR_ray_query`), on lavapipe with validation on: shadows traced inline
//! from ray generation (`shadow_method = "query"`) give the image `traceRay` shadows give, on
//! scenes with every shape, meshes, rect lights and cutouts, in both sets and mixed.

use twinray_host::scene::Scene;
use twinray_tests::{assert_same_render, render_scene, set, validated_context};

/// `scene` with its shadow rays traced by ray queries.
fn with_queries(scene: &Scene) -> Scene {
    let mut query = scene.clone();
    query.file.shadow_method = twinray_host::scene::ShadowMethod::Query;
    query
}

/// Query shadows against traced shadows, each set against itself, and the query renders of
/// both sets and a mix against each other.
#[test]
fn query_shadows_match_traced_shadows() {
    let ctx = validated_context();
    if !ctx.info.ray_query {
        panic!("{} has no VK_KHR_ray_query: these tests need lavapipe (run `cargo xtask setup`)", ctx.info.name);
    }
    for name in ["showcase", "cutout", "meshes", "lights"] {
        let scene = Scene::load(Some(name)).expect("built-in scene");
        let query = with_queries(&scene);
        assert!(query.build().plan.shadows, "{name} casts shadows");
        let mut queried = Vec::new();
        for set_text in ["rust", "glsl"] {
            let traced = render_scene(&ctx, &scene, set_text);
            let inline = render_scene(&ctx, &query, set_text);
            assert!(inline.rays.shadow > 0, "{name}: no shadow rays");
            assert_same_render(&format!("{set_text} query vs trace"), &inline, &traced, &scene);
            queried.push(inline);
        }
        assert_same_render("rust vs glsl query", &queried[0], &queried[1], &scene);
        let mixed = render_scene(&ctx, &query, "glsl,raygen=rust");
        assert_same_render("mix vs glsl query", &mixed, &queried[1], &scene);
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}

/// A query scene builds no shadow miss stage, and its pipeline's ray generation is
/// `raygen_query`.
#[test]
fn query_pipelines_have_no_shadow_miss_stage() {
    let scene = with_queries(&Scene::load(Some("showcase")).expect("showcase"));
    let plan = scene.build().plan;
    let modules = twinray_host::render::pipeline::plan_modules(&plan, plan.render_raygen());
    assert_eq!(&modules[..2], ["raygen_query", "miss"]);
    assert!(!modules.contains(&"shadow_miss"), "{modules:?}");
}

/// On a device without ray queries a query scene fails before any GPU work, with one line
/// naming the extension. Lavapipe has them, so the test hides them from twinray: the check
/// reads the context's record of what it enabled.
#[test]
fn a_device_without_ray_queries_refuses_query_scenes_by_name() {
    let mut ctx = validated_context();
    std::sync::Arc::get_mut(&mut ctx).expect("the only reference").info.ray_query = false;
    let scene = with_queries(&Scene::load(Some("lights")).expect("lights"));
    let err = twinray_host::render(&ctx, &scene, &set("rust"), &twinray_tests::small_render()).err().expect("an error");
    let message = err.to_string();
    assert!(message.contains("VK_KHR_ray_query") && message.contains("shadow_method"), "{message}");
    assert_eq!(message.lines().count(), 1, "{message}");
    // Scenes that trace their shadows still render.
    let traced = Scene::load(Some("lights")).expect("lights");
    twinray_host::render(&ctx, &traced, &set("rust"), &twinray_tests::small_render()).expect("traced shadows render");
}
