//! The compute renderer (`renderer = "compute"`), on lavapipe with validation on: one compute
//! stage that traces primary and shadow rays with ray queries, deciding procedural candidates
//! and cutouts with the shared code, sees what the ray tracing pipeline sees: the same hit ids
//! in every pixel and the same image, on scenes with every shape (robust and naive formulas),
//! meshes, instances, rect lights and cutouts, in both sets and mixed (bit-identical on
//! lavapipe for every built-in scene; each scene but showcase in one set here).

use twinray_host::scene::{MeshFiles, Renderer, Scene};
use twinray_tests::{alternate_set, assert_same_render, render_scene, repo_root, set, validated_context};

/// `scene` rendered by the compute renderer.
fn with_compute(scene: &Scene) -> Scene {
    let mut compute = scene.clone();
    compute.file.renderer = Renderer::Compute;
    compute
}

/// The torus scene with the textbook quartic (`formula = "naive"`): the naive variants'
/// routines are chosen through `ObjectData::shape` as the robust ones are.
fn naive_torus() -> Scene {
    let text = std::fs::read_to_string(repo_root().join("scenes/torus.toml")).expect("torus.toml");
    let text = text.replacen("kind = \"torus\"", "kind = \"torus\"\nformula = \"naive\"", 1);
    Scene::parse(&text, "torus-naive", MeshFiles::Builtin).expect("naive torus")
}

#[test]
fn the_compute_renderer_sees_what_the_pipeline_sees() {
    let ctx = validated_context();
    if !ctx.info.ray_query {
        panic!("{} has no VK_KHR_ray_query: these tests need lavapipe (run `cargo xtask setup`)", ctx.info.name);
    }
    // Showcase (every procedural shape, a mesh, a rect light) in both sets and a mix; each other
    // scene in one set, alternating: a compute stage with ray queries takes lavapipe about 6 s
    // to compile from nothing, once per scene's specialisation and set. That set's compute
    // image is held to its own pipeline's, which tests/scenes.rs holds to the other set's.
    let scenes = ["showcase", "cutout", "meshes", "lights", "instances", "cylinder", "cone", "box"]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let sets = if k == 0 { vec!["rust", "glsl"] } else { vec![alternate_set(k)] };
            (Scene::load(Some(name)).expect("built-in scene"), sets)
        });
    // The naive quartic rounds differently in the two languages (what it is kept to show), so
    // each set is held to its own pipeline only.
    for (scene, sets) in scenes.chain([(naive_torus(), vec!["rust", "glsl"])]) {
        let scene = &scene;
        let name = scene.name();
        let compute = with_compute(scene);
        let mut computed = Vec::new();
        for set_text in sets {
            let pipeline = render_scene(&ctx, scene, set_text);
            let queried = render_scene(&ctx, &compute, set_text);
            assert_eq!(queried.raygen_stack_bytes, 0, "{name}: a compute pipeline has no ray generation stack");
            assert_same_render(&format!("{set_text} compute vs pipeline"), &queried, &pipeline, scene);
            computed.push(queried);
        }
        if name == "showcase" {
            let mixed = render_scene(&ctx, &compute, "rust,compute=glsl");
            assert_same_render("mix vs glsl compute", &mixed, &computed[1], scene);
            assert_same_render("rust vs glsl compute", &computed[0], &computed[1], scene);
        }
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}

/// A compute scene's pipeline is its one compute stage: no miss, hit or callable stages.
#[test]
fn a_compute_scene_has_one_stage() {
    let scene = with_compute(&Scene::load(Some("cutout")).expect("cutout"));
    let plan = scene.build().plan;
    let modules = twinray_host::render::pipeline::plan_modules(&plan, plan.render_raygen());
    assert_eq!(modules, ["render_compute"]);
    let stages = twinray_host::render::pipeline::used_stages(&plan, plan.render_raygen());
    assert_eq!(stages, [twinray_host::sets::Stage::Compute]);
    // The probe still traces through the pipeline's stages.
    assert!(twinray_host::render::pipeline::plan_modules(&plan, "probe").contains(&"cutout_any_hit"));
}

/// On a device without ray queries a compute scene fails before any GPU work, in one line
/// naming the extension and the key.
#[test]
fn a_device_without_ray_queries_refuses_compute_scenes_by_name() {
    let mut ctx = validated_context();
    std::sync::Arc::get_mut(&mut ctx).expect("the only reference").info.ray_query = false;
    let scene = with_compute(&Scene::load(Some("meshes")).expect("meshes"));
    let err = twinray_host::render(&ctx, &scene, &set("glsl"), &twinray_tests::small_render()).err().expect("an error");
    let message = err.to_string();
    assert!(message.contains("VK_KHR_ray_query") && message.contains("renderer"), "{message}");
    assert_eq!(message.lines().count(), 1, "{message}");
}

/// A compute scene is probed by `probe_query`, which traces each ray as the compute renderer
/// traces primary rays: on every shipped probe case (every shape, meshes, cutouts, far and
/// grazing rays, each ray's own t range), in both sets, it reports exactly what the pipeline's
/// probe reports, ray by ray.
#[test]
fn compute_scenes_are_probed_as_the_compute_renderer_traces() {
    twinray_tests::allow_installed_models();
    let ctx = validated_context();
    let cases = twinray_host::probe::stability::case_files(&repo_root().join("probes")).expect("probe cases");
    for path in cases {
        let case =
            twinray_host::probe::case::ProbeCase::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for set_text in ["rust", "glsl"] {
            let pipeline =
                twinray_host::probe::probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
            let compute = with_compute(&case.scene);
            let queried = twinray_host::probe::probe(&ctx, &compute, &set(set_text), &case.rays, 0, 1).expect("probe");
            assert_eq!(queried.raygen_stack_bytes, 0, "{}: the compute probe ran", path.display());
            let differ = pipeline.results.iter().zip(&queried.results).filter(|(p, q)| p.ids != q.ids).count();
            assert_eq!(differ, 0, "{} with {set_text}: {differ} rays hit something else", path.display());
            for (p, q) in pipeline.results.iter().zip(&queried.results) {
                if p.ids.w != twinray_shared::bindings::NO_HIT {
                    assert_eq!(p.normal_t, q.normal_t, "{} with {set_text}", path.display());
                }
            }
        }
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}
