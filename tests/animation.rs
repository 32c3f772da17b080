//! Moving scenes on lavapipe with validation on: a frame of an animated scene is the still
//! scene placed at that frame's values, the TLAS modes agree on every hit, and both sets agree
//! on every frame of the built-in moving scene.

use std::sync::Arc;
use twinray_host::compare::{diff, verdict};
use twinray_host::render::{render_frames, AsWork, TlasKind, TlasMode};
use twinray_host::scene::MeshFiles;
use twinray_host::{Context, RenderOptions, RenderOutput, Scene};
use twinray_tests::{set, validated_context};

pub(crate) const SIZE: (u32, u32) = (128, 96);

pub(crate) fn opts() -> RenderOptions {
    RenderOptions::once(SIZE.0, SIZE.1, 0, 1)
}

/// Every frame of `frames`, each as one output per set.
pub(crate) fn frames(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[&str],
    frames: std::ops::Range<u32>,
    mode: TlasMode,
) -> Vec<(AsWork, Vec<RenderOutput>)> {
    let sets: Vec<_> = sets.iter().map(|s| set(s)).collect();
    let mut out = Vec::new();
    render_frames(ctx, scene, &sets, &opts(), frames, mode, |f| {
        out.push((f.as_work, f.outputs));
        Ok(())
    })
    .unwrap_or_else(|e| panic!("rendering the frames of {}: {e}", scene.name()));
    out
}

pub(crate) fn same(a: &RenderOutput, b: &RenderOutput) -> bool {
    a.rgba == b.rgba && a.hit_ids == b.hit_ids
}

/// A still scene; `{MOVE}` is replaced with the animation or with frame 2's values.
const SCENE: &str = r#"
[image]
width = 128
height = 96
[camera]
eye = {EYE}
target = [0.0, 0.5, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 45.0
[materials.floor]
kind = "checker"
colors = [[0.9, 0.9, 0.9], [0.2, 0.2, 0.2]]
scale = 1.0
[materials.red]
kind = "diffuse"
color = [0.8, 0.2, 0.1]
[[lights]]
kind = "rect"
center = {LIGHT}
u = [1.0, 0.0, 0.0]
v = [0.0, 0.0, 1.0]
color = [1.0, 1.0, 1.0]
intensity = 20.0
samples = 2
[shapes.floor]
kind = "rectangle"
size = [20.0, 20.0]
[shapes.ball]
kind = "sphere"
radius = 0.6
[shapes.gem]
kind = "mesh"
builtin = "icosahedron"
[[objects]]
shape = "floor"
material = "floor"
[[objects]]
shape = "ball"
material = "red"
translate = {BALL}
[[objects]]
shape = "gem"
material = "red"
translate = [-1.5, 0.5, 0.0]
rotate = {GEM}
"#;

const ANIMATION: &str = r#"
[animation]
frames = 4
fps = 1
[[animation.tracks]]
target = "object 1"
property = "translate"
keys = [{ time = 0.0, value = [0.0, 0.6, 0.0] }, { time = 4.0, value = [2.0, 1.4, -1.0] }]
[[animation.tracks]]
target = "object 2"
property = "rotate"
keys = [{ time = 0.0, value = [0.0, 0.0, 0.0] }, { time = 1.0, value = [0.0, 30.0, 0.0] }]
[[animation.tracks]]
target = "light 0"
property = "center"
keys = [{ time = 0.0, value = [0.0, 4.0, 0.0] }, { time = 4.0, value = [4.0, 4.0, 2.0] }]
[[animation.tracks]]
target = "camera"
property = "eye"
keys = [{ time = 0.0, value = [0.0, 3.0, 8.0] }, { time = 4.0, value = [2.0, 4.0, 8.0] }]
"#;

fn filled(eye: &str, light: &str, ball: &str, gem: &str) -> String {
    SCENE.replace("{EYE}", eye).replace("{LIGHT}", light).replace("{BALL}", ball).replace("{GEM}", gem)
}

/// Frame 2 (t = 2 s, half way along every track but the gem's, which has ended) written out
/// by hand: the animation's interpolation is checked here too, not only the renderer.
#[test]
fn a_frame_renders_as_the_still_scene_of_its_values() {
    let ctx = validated_context();
    let at_rest = filled("[0.0, 3.0, 8.0]", "[0.0, 4.0, 0.0]", "[0.0, 0.6, 0.0]", "[0.0, 0.0, 0.0]");
    let moving = Scene::parse(&format!("{at_rest}{ANIMATION}"), "moving.toml", MeshFiles::Builtin).unwrap();
    let still_text = filled("[1.0, 3.5, 8.0]", "[2.0, 4.0, 1.0]", "[1.0, 1.0, -0.5]", "[0.0, 30.0, 0.0]");
    let still = Scene::parse(&still_text, "still.toml", MeshFiles::Builtin).unwrap();
    for kind in [TlasKind::Update, TlasKind::Rebuild] {
        let mode = TlasMode { kind, rebuild_every: 0 };
        for language in ["rust", "glsl"] {
            let rendered = frames(&ctx, &moving, &[language], 0..4, mode);
            let expected = twinray_host::render(&ctx, &still, &set(language), &opts()).unwrap();
            assert!(same(&rendered[2].1[0], &expected), "{language} {kind:?}: frame 2 differs from the still scene");
            assert!(!same(&rendered[1].1[0], &expected), "{language}: frame 1 should differ from frame 2");
            let expected_work = if kind == TlasKind::Update { AsWork::Update } else { AsWork::Build };
            assert_eq!(rendered[2].0, expected_work);
        }
    }
    ctx.close().unwrap();
}

/// Frames of `orbit` the TLAS modes are compared on: every motion of the scene moves from one
/// to the next, and an updated TLAS that falls a frame behind, or keeps its first frame's
/// transforms, differs from a rebuilt one at the second (`cargo xtask planted
/// tlas-update-stale`). All 48 frames cost 288 renders where these cost 48.
const ORBIT_FRAMES: u32 = 8;

/// The first frames of the built-in moving scene: updated (never rebuilt), rebuilt and
/// fast-built TLASes give the same hit ids in both sets; rust and glsl agree within the scene's
/// parity tolerance; and one frame matches the still scene `Scene::at_frame` makes.
#[test]
fn the_orbit_scene_agrees_across_tlas_modes_sets_and_its_still_frames() {
    let ctx = validated_context();
    let scene = Scene::load(Some("orbit")).unwrap();
    let count = ORBIT_FRAMES.min(scene.frame_count());
    let sets = ["rust", "glsl"];
    let run = |kind| frames(&ctx, &scene, &sets, 0..count, TlasMode { kind, rebuild_every: 0 });
    let updated = run(TlasKind::Update);
    let rebuilt = run(TlasKind::Rebuild);
    let fast = run(TlasKind::FastBuild);
    assert_eq!(updated.len(), count as usize);
    let parity = scene.file.parity;
    let pixels = u64::from(SIZE.0 * SIZE.1);
    let mut failures = Vec::new();
    for k in 0..count as usize {
        for (s, language) in sets.iter().enumerate() {
            for (name, other) in [("rebuilt", &rebuilt), ("fast-built", &fast)] {
                if updated[k].1[s].hit_ids != other[k].1[s].hit_ids {
                    failures.push(format!("frame {k} {language}: updated and {name} TLAS hit different ids"));
                }
            }
        }
        let d = diff(&updated[k].1[0], &updated[k].1[1], parity.pixel_threshold);
        let f = verdict(&d, &parity, pixels);
        if !f.is_empty() {
            failures.push(format!("frame {k} rust vs glsl: {f:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    let k = count - 3;
    let still = twinray_host::render(&ctx, &scene.at_frame(k).unwrap(), &set("rust"), &opts()).unwrap();
    assert!(same(&updated[k as usize].1[0], &still), "frame {k} differs from Scene::at_frame({k})");
    ctx.close().unwrap();
}

/// A glTF model no one here made (TextureTransformTest: twelve parts, each a node of its own)
/// placed by an object keyframed along x and by a grid of two that spin: every part of a
/// model takes its object's motion, so the model moves as one (its parts keep their places
/// relative to each other) while it moves; both sets agree on every frame, and a frame is
/// the still scene `Scene::at_frame` makes.
#[test]
fn placed_gltf_models_move_as_one() {
    twinray_tests::allow_installed_models();
    let model = "/usr/share/assimp/models/glTF2/textureTransform/TextureTransformTest.gltf";
    assert!(std::path::Path::new(model).exists(), "{model}: run `cargo xtask setup`");
    let text = placed_models(model, MODELS_MOVE);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("models.toml");
    std::fs::write(&path, text).unwrap();
    let scene = Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"));
    let parts = scene.file.objects.len() / 3;
    assert!(parts >= 12 && scene.file.objects.len() == 3 * parts, "{} objects", scene.file.objects.len());
    let (first, last) = (scene.at_frame(0).unwrap(), scene.at_frame(3).unwrap());
    for model in 0..3 {
        let at = |s: &Scene, k: usize| s.file.objects[model * parts + k].transform();
        let moved = (at(&first, 0).w_axis - at(&last, 0).w_axis).length();
        assert!(moved > 0.1, "model {model} did not move ({moved})");
        for k in 1..parts {
            let (before, after) = (at(&first, 0).inverse() * at(&first, k), at(&last, 0).inverse() * at(&last, k));
            assert!(before.abs_diff_eq(after, 1e-4), "model {model}, part {k} moved against part 0");
        }
    }
    let ctx = validated_context();
    let rendered = frames(&ctx, &scene, &["rust", "glsl"], 0..4, TlasMode { kind: TlasKind::Update, rebuild_every: 0 });
    for (k, (_, outputs)) in rendered.iter().enumerate() {
        let d = diff(&outputs[0], &outputs[1], scene.file.parity.pixel_threshold);
        assert!(verdict(&d, &scene.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty(), "frame {k}: {d:?}");
    }
    let still = twinray_host::render(&ctx, &last, &set("rust"), &opts()).unwrap();
    assert!(same(&rendered[3].1[0], &still), "frame 3 differs from Scene::at_frame(3)");
    assert!(!same(&rendered[0].1[0], &rendered[3].1[0]), "nothing moved on screen");
    ctx.close().unwrap();
}

/// A scene file placing the glTF model `model` as shape `test` by an object (scaled by 0.5, at
/// (-1.5, 1, 0)) and by a grid of two, seen from in front, with `animation` (TOML) after it.
pub(crate) fn placed_models(model: &str, animation: &str) -> String {
    format!(
        r#"
[image]
width = 128
height = 96
[camera]
eye = [0.0, 0.0, 9.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 50.0
[[lights]]
kind = "directional"
direction = [0.2, 0.5, 1.0]
color = [1.0, 1.0, 1.0]
intensity = 1.0
[shapes.test]
kind = "gltf"
file = "{model}"
[[objects]]
shape = "test"
translate = [-1.5, 1.0, 0.0]
scale = 0.5
[[grids]]
shape = "test"
materials = [""]
count = [2, 1, 1]
origin = [-1.0, -1.5, 0.0]
spacing = [2.5, 0.0, 0.0]
scale = 0.5
{animation}"#
    )
}

/// What moves the placed models in `placed_gltf_models_move_as_one`: object 0 along x, the grid
/// spinning.
pub(crate) const MODELS_MOVE: &str = r#"[animation]
frames = 4
fps = 1.0
[[animation.tracks]]
target = "object 0"
property = "translate"
keys = [{ time = 0.0, value = [-1.5, 1.0, 0.0] }, { time = 3.0, value = [1.5, 1.0, 0.0] }]
[[animation.motions]]
kind = "spin"
target = "grid 0"
degrees_per_second = [0.0, 0.0, 20.0]
"#;
