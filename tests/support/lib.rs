//! The one support library of every integration test (`tests/`, `app/tests/`, `xtask/tests/`):
//! a validated Vulkan context per test, small renders and the repository's root here; running
//! the `twinray` binary and planting stages in `cli`; the docs' fenced blocks in `docs`; small
//! glTF models in `gltf`; scratch
//! copies of the repository in `scratch`, what `new-shape` promises in `scaffold`, and following
//! a tutorial's blocks in `tutorial`.

pub mod cli;
pub mod docs;
pub mod gltf;
pub mod scaffold;
pub mod scratch;
pub mod tutorial;

use std::path::PathBuf;
use std::sync::Arc;
use twinray_host::{Context, ContextOptions, RenderOptions, RenderOutput, Scene, ShaderSet, Validation};

/// Test renders stay small: lavapipe traces the 1024-sphere scene at about 0.4 Mrays/s.
pub const TEST_SIZE: u32 = 256;

/// Scene files and probe cases here name models Debian installs (assimp-testmodels) by
/// absolute path, outside their own folders: the whole disk is their asset root, as
/// `--asset-root /` gives a command (what confinement refuses is tested in host/tests).
pub fn allow_installed_models() {
    twinray_host::util::input::set_asset_root(std::path::Path::new("/")).expect("the asset root");
}

/// The repository root.
pub fn repo_root() -> PathBuf {
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    here.parent().map(PathBuf::from).unwrap_or(here)
}

/// A context on the default device with the validation layer required: a test fails if the
/// layer is missing, and any validation error fails the render that caused it. Each test gets
/// its own device, so tests running in parallel never share a queue.
pub fn validated_context() -> Arc<Context> {
    validated_context_making(None)
}

/// As [`validated_context`], making pipelines as `pipelines` says (`None`: the default,
/// libraries where the device has them).
pub fn validated_context_making(pipelines: Option<twinray_host::vk::context::PipelineKind>) -> Arc<Context> {
    let options = ContextOptions {
        validation: Validation::Required,
        device_filter: None,
        pipeline_cache: None,
        pipelines,
        ..ContextOptions::default()
    };
    match Context::new(&options) {
        Ok(ctx) => ctx,
        Err(e) => panic!("creating a validated Vulkan context: {e} (run `cargo xtask setup`)"),
    }
}

/// Options for one untimed-warm-up, one-trace render of `TEST_SIZE` squared.
pub fn small_render() -> RenderOptions {
    RenderOptions::once(TEST_SIZE, TEST_SIZE, 0, 1)
}

/// Built-in scenes are tested at this size: small enough for lavapipe, large enough that
/// each shape covers hundreds of pixels.
pub const SCENE_TEST_SIZE: (u32, u32) = (160, 120);

/// Renders a built-in scene at `SCENE_TEST_SIZE` with one trace.
pub fn render_scene(ctx: &Arc<Context>, scene: &Scene, set_text: &str) -> RenderOutput {
    let (width, height) = SCENE_TEST_SIZE;
    let opts = RenderOptions::once(width, height, 0, 1);
    match twinray_host::render(ctx, scene, &set(set_text), &opts) {
        Ok(out) => out,
        Err(e) => panic!("rendering {} with {set_text}: {e}", scene.name()),
    }
}

/// Asserts that two renders of `scene` at `SCENE_TEST_SIZE` (`label` says which) hit the same
/// object and primitive in every pixel (but where either answer is right, as `compare` judges:
/// `twinray_host::compare::edges`), trace the same shadow rays, and give images within the scene's
/// parity.
pub fn assert_same_render(label: &str, a: &RenderOutput, b: &RenderOutput, scene: &Scene) {
    let name = scene.name();
    let parity = scene.file.parity;
    let d = twinray_host::compare::scene_diff(scene, a, b);
    let f = twinray_host::compare::verdict(&d, &parity, u64::from(SCENE_TEST_SIZE.0 * SCENE_TEST_SIZE.1));
    eprintln!(
        "{name} {label}: rmse {:.6}, {} over, {} hit mismatches ({} + {} set apart), shadow rays {} / {}",
        d.color.rmse,
        d.color.pixels_over_threshold,
        d.hit_mismatches,
        d.internal_edges,
        d.alpha_edges,
        a.rays.shadow,
        b.rays.shadow
    );
    assert_eq!(d.hit_mismatches, 0, "{name} {label}: different objects or primitives hit");
    assert!(f.is_empty(), "{name} {label}: {f:?}");
    assert_eq!(a.rays.shadow, b.rays.shadow, "{name} {label}: the same shadow rays are traced");
}

/// Every built-in scene, loaded.
pub fn builtin_scenes() -> Vec<Scene> {
    twinray_host::scene::BUILTIN
        .iter()
        .map(|(name, _)| Scene::load(Some(name)).unwrap_or_else(|e| panic!("built-in scene {name}: {e}")))
        .collect()
}

pub fn default_scene() -> Scene {
    match Scene::load(None) {
        Ok(scene) => scene,
        Err(e) => panic!("loading the default scene: {e}"),
    }
}

/// A scene file's first lines for tests that add their own shapes and objects: an 8 x 8
/// image, a camera at z = 10 looking at the origin, and a white diffuse material `m`.
pub const SCENE_HEAD: &str = r#"
[image]
width = 8
height = 8
[camera]
eye = [0.0, 0.0, 10.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 45.0
[materials.m]
kind = "diffuse"
color = [1.0, 1.0, 1.0]
"#;

/// The built-in set a test renders case `k` with where one set per case is enough (the check
/// is the host's, the same for both): Rust for even `k`, GLSL for odd, so both languages meet
/// the cases and each case compiles one set's pipelines, not two.
pub fn alternate_set(k: usize) -> &'static str {
    ["rust", "glsl"][k % 2]
}

/// The set `text` names, loaded (folders of sources built with the default deadline).
pub fn set(text: &str) -> ShaderSet {
    match text.parse().and_then(|spec| twinray_host::sets::Loader::default().load(&spec)) {
        Ok(set) => set,
        Err(e) => panic!("shader set {text:?}: {e}"),
    }
}

/// Renders `scene` with `set` at the test size, failing the test on any error.
pub fn render(ctx: &Arc<Context>, scene: &Scene, set_text: &str) -> RenderOutput {
    match twinray_host::render(ctx, scene, &set(set_text), &small_render()) {
        Ok(out) => out,
        Err(e) => panic!("rendering {} with {set_text}: {e}", scene.name()),
    }
}
