//! glTF animations played over frames on lavapipe, validation on, with models no one here made
//! (assimp's test models): a morph target clip and a skinned clip, their meshes posed on the
//! host every frame and their BLASes refitted in place, show at each frame what a still
//! picture of that time shows (the BLAS built afresh); both sets agree on every frame, and
//! refitting hits what rebuilding hits. A node the clip moves keeps its mesh's primitives in
//! one BLAS, one instance, frame after frame.

use super::animation::{frames, opts, same, SIZE};
use std::sync::Arc;
use twinray_host::compare::{diff, verdict};
use twinray_host::render::{AsWork, TlasKind, TlasMode};
use twinray_host::scene::gltf::{load_at, Playing};
use twinray_host::{Context, Scene};
use twinray_tests::{set, validated_context};

const MODELS: &str = "/usr/share/assimp/models/glTF2";

/// The model at `path` played from 0 s at `fps`.
fn clip(path: &str, fps: f32) -> Scene {
    twinray_tests::allow_installed_models();
    let path = std::path::Path::new(MODELS).join(path);
    assert!(path.exists(), "{}: run `cargo xtask setup`", path.display());
    let model = load_at(&path, None, Playing { time: 0.0, fps }).unwrap_or_else(|e| panic!("{e}"));
    Scene::from_model(model, &path.display().to_string()).unwrap_or_else(|e| panic!("{e}"))
}

fn check_clip(ctx: &Arc<Context>, scene: &Scene) {
    let name = scene.name().to_string();
    let animation = scene.animation.as_ref().unwrap_or_else(|| panic!("{name}: no clip"));
    assert!(animation.moves().meshes, "{name}: its meshes do not move");
    let all = 0..scene.frame_count();
    let run = |kind| frames(ctx, scene, &["rust", "glsl"], all.clone(), TlasMode { kind, rebuild_every: 0 });
    let (updated, rebuilt) = (run(TlasKind::Update), run(TlasKind::Rebuild));
    let pixels = u64::from(SIZE.0 * SIZE.1);
    let mut failures = Vec::new();
    for (k, ((work, outputs), (_, again))) in updated.iter().zip(&rebuilt).enumerate() {
        assert_eq!(*work, if k == 0 { AsWork::Build } else { AsWork::Update }, "{name}: frame {k}");
        for s in 0..2 {
            if outputs[s].hit_ids != again[s].hit_ids {
                failures.push(format!("{name} frame {k} set {s}: refitted and rebuilt BLASes hit different ids"));
            }
        }
        let d = diff(&outputs[0], &outputs[1], scene.file.parity.pixel_threshold);
        let f = verdict(&d, &scene.file.parity, pixels);
        if !f.is_empty() {
            failures.push(format!("{name} frame {k} rust vs glsl: {f:?}"));
        }
    }
    let last = updated.len() - 1;
    for k in [2, last] {
        let still = twinray_host::render(ctx, &scene.at_frame(k as u32).unwrap(), &set("rust"), &opts()).unwrap();
        if !same(&updated[k].1[0], &still) {
            failures.push(format!("{name}: frame {k} (refitted) differs from a still picture of its time"));
        }
    }
    if same(&updated[0].1[0], &updated[2].1[0]) {
        failures.push(format!("{name}: nothing moved on screen"));
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn morphed_and_skinned_clips_refit_to_what_a_still_picture_shows() {
    let ctx = validated_context();
    // 4.17 s of morph target weights, and 5.5 s of a joint turning a strip: 9 and 12 frames;
    // frame 2 (1 s) is the cube thinned and the strip bent a quarter turn.
    check_clip(&ctx, &clip("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", 2.0));
    check_clip(&ctx, &clip("simple_skin/simple_skin.gltf", 2.0));
    ctx.close().unwrap();
}

#[test]
fn a_moving_nodes_primitives_share_one_blas_on_every_frame() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let colors = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let path = twinray_tests::gltf::moving_strip(dir.path(), &colors, [0.0, 1.5, 0.0], 2.0);
    let model = load_at(&path, None, Playing { time: 0.0, fps: 2.0 }).unwrap_or_else(|e| panic!("{e}"));
    let scene = Scene::from_model(model, &path.display().to_string()).unwrap_or_else(|e| panic!("{e}"));
    let animation = scene.animation.as_ref().expect("a clip");
    assert!(animation.moves().objects && !animation.moves().meshes);
    let mode = TlasMode { kind: TlasKind::Update, rebuild_every: 0 };
    let out = frames(&ctx, &scene, &["rust", "glsl"], 0..scene.frame_count(), mode);
    assert_eq!(out.len(), 5, "0 to 2 s at 2 fps");
    for (k, (_, outputs)) in out.iter().enumerate() {
        let a = outputs[0].accel;
        assert_eq!((a.blases, a.instances), (1, 1), "frame {k}: {a}");
        assert_eq!(outputs[0].hit_ids, outputs[1].hit_ids, "frame {k}: the sets hit different ids");
        let objects: std::collections::BTreeSet<u64> =
            outputs[0].hit_ids.iter().filter(|id| **id != twinray_host::render::NO_HIT_ID).map(|id| id >> 32).collect();
        assert_eq!(objects.len(), colors.len(), "frame {k}: the objects seen");
    }
    for k in [2, 4] {
        let still = twinray_host::render(&ctx, &scene.at_frame(k).unwrap(), &set("rust"), &opts()).unwrap();
        assert!(same(&out[k as usize].1[0], &still), "frame {k} differs from a still picture of its time");
    }
    assert!(!same(&out[0].1[0], &out[4].1[0]), "nothing moved on screen");
}

/// A scene file that places `model` (its file name in `dir`) by an object and by a grid of
/// two (`animation::placed_models`), with no `[animation]`.
fn placing(dir: &std::path::Path, model: &str) -> Scene {
    let path = dir.join("placing.toml");
    std::fs::write(&path, super::animation::placed_models(model, "")).unwrap();
    Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"))
}

/// A scene file that places an animated model by an object and a grid plays the model's clip
/// where each places it: at every frame each part is its placing object's transform after the
/// part's pose in the model alone (the placing the same on every frame, the pose not), and
/// frames render in both sets alike and as the still pictures of their times.
#[test]
fn a_placed_models_clip_plays_where_the_scene_places_it() {
    let dir = tempfile::tempdir().unwrap();
    let colors = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let path = twinray_tests::gltf::moving_strip(dir.path(), &colors, [0.0, 1.5, 0.0], 2.0);
    let scene = placing(dir.path(), "strip.gltf");
    let fps = twinray_host::scene::gltf::playing().fps;
    let alone = load_at(&path, None, Playing { time: 0.0, fps }).unwrap_or_else(|e| panic!("{e}"));
    let alone = Scene::from_model(alone, "strip").unwrap_or_else(|e| panic!("{e}"));
    let animation = scene.animation.as_ref().expect("the model's clip, played");
    assert!(animation.moves().objects && !animation.moves().camera && !animation.moves().lights);
    assert_eq!(scene.frame_count(), alone.frame_count());
    let parts = alone.file.objects.len();
    assert_eq!(scene.file.objects.len(), 3 * parts);
    let last = scene.frame_count() - 1;
    let placings = |k: u32| {
        let (placed, posed) = (scene.at_frame(k).unwrap(), alone.at_frame(k).unwrap());
        let of = |i: usize| placed.file.objects[i].transform() * posed.file.objects[i % parts].transform().inverse();
        (0..3 * parts).map(of).collect::<Vec<_>>()
    };
    let (first, end) = (placings(0), placings(last));
    for (i, (a, b)) in first.iter().zip(&end).enumerate() {
        assert!(a.abs_diff_eq(*b, 1e-5), "object {i}: placed otherwise at frame {last}: {a} against {b}");
        assert!(a.abs_diff_eq(first[i - i % parts], 1e-5), "object {i}: its model's parts placed apart");
    }
    let moved = |s: &Scene| s.file.objects[0].transform().w_axis;
    assert!((moved(&scene.at_frame(0).unwrap()) - moved(&scene.at_frame(last).unwrap())).length() > 0.5);
    let ctx = validated_context();
    let mode = TlasMode { kind: TlasKind::Update, rebuild_every: 0 };
    let out = frames(&ctx, &scene, &["rust", "glsl"], last - 2..last + 1, mode);
    for (k, (_, outputs)) in out.iter().enumerate() {
        assert_eq!(outputs[0].hit_ids, outputs[1].hit_ids, "frame {}: the sets hit different ids", last - 2 + k as u32);
    }
    let still = twinray_host::render(&ctx, &scene.at_frame(last).unwrap(), &set("rust"), &opts()).unwrap();
    assert!(same(&out[2].1[0], &still), "the last frame differs from a still picture of its time");
}

/// A placed skinned model (assimp's simple_skin) poses its mesh under the scene's name for it:
/// frame k's mesh is the model's own at frame k.
#[test]
fn a_placed_skinned_model_poses_its_mesh_on_every_frame() {
    twinray_tests::allow_installed_models();
    let dir = tempfile::tempdir().unwrap();
    let model = std::path::Path::new(MODELS).join("simple_skin/simple_skin.gltf");
    assert!(model.exists(), "{}: run `cargo xtask setup`", model.display());
    std::fs::copy(&model, dir.path().join("skin.gltf")).unwrap();
    let scene = placing(dir.path(), "skin.gltf");
    let animation = scene.animation.as_ref().expect("the model's clip, played");
    assert!(animation.moves().meshes);
    let alone = clip("simple_skin/simple_skin.gltf", twinray_host::scene::gltf::playing().fps);
    let k = scene.frame_count() / 2;
    let (placed, posed) = (scene.at_frame(k).unwrap(), alone.at_frame(k).unwrap());
    let mut matched = 0;
    for (shape, mesh) in &posed.meshes {
        let theirs = placed.meshes.get(&format!("test/{shape}")).unwrap_or_else(|| panic!("no test/{shape}"));
        assert_eq!(theirs.vertices, mesh.vertices, "{shape} at frame {k}");
        matched += usize::from(!Arc::ptr_eq(&alone.meshes[shape], mesh));
    }
    assert!(matched > 0, "no mesh posed at frame {k}");
}

/// A scene file that places two animated models plays both clips together, as long as the
/// longer (a strip moving for 2 s, another for 4 s): at every frame each part is its placing
/// object's transform after the part's pose in its model alone at that time, the shorter
/// looping over its own 2 s as glTF-Sample-Viewer loops an animation (frame 49 is its frame
/// 1 again, 72 its 24, 96 its last); frames render in both sets alike and as the still picture of
/// their time.
#[test]
fn two_placed_models_play_their_clips_together() {
    let dir = tempfile::tempdir().unwrap();
    let colors = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let fps = twinray_host::scene::gltf::playing().fps;
    let mut alone = Vec::new();
    for (name, seconds) in [("short", 2.0), ("long", 4.0)] {
        let folder = dir.path().join(name);
        std::fs::create_dir(&folder).unwrap();
        let path = twinray_tests::gltf::moving_strip(&folder, &colors, [0.0, 1.5, 0.0], seconds);
        let model = load_at(&path, None, Playing { time: 0.0, fps }).unwrap_or_else(|e| panic!("{e}"));
        alone.push(Scene::from_model(model, name).unwrap_or_else(|e| panic!("{e}")));
    }
    let other = "[shapes.other]\nkind = \"gltf\"\nfile = \"long/strip.gltf\"\n[[objects]]\nshape = \"other\"\ntranslate = [1.5, 1.0, 0.0]\nscale = 0.5\n";
    let path = dir.path().join("placing.toml");
    std::fs::write(&path, super::animation::placed_models("short/strip.gltf", other)).unwrap();
    let scene = Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"));
    let ends = [alone[0].frame_count() - 1, alone[1].frame_count() - 1];
    assert!(ends[0] < ends[1], "clip lengths {ends:?}");
    assert_eq!(scene.frame_count(), ends[1] + 1, "the scene plays as long as the longer clip");
    let parts = alone[0].file.objects.len();
    // Each object's model (0: short, placed as `test`; 1: long, as `other`) and part.
    let mut of = Vec::new();
    for (i, object) in scene.file.objects.iter().enumerate() {
        let model = usize::from(object.shape.starts_with("other/"));
        let run = of.iter().rev().take_while(|&&(m, _): &&(usize, usize)| m == model).count();
        assert!(i == 0 || run > 0 || of.last().is_some_and(|&(_, p)| p == parts - 1), "object {i}");
        of.push((model, run % parts));
    }
    assert_eq!(of.iter().filter(|o| o.0 == 1).count(), parts, "one placing of the long model");
    let placings = |k: u32| {
        let placed = scene.at_frame(k).unwrap();
        let of = of.iter().enumerate().map(|(i, &(model, part))| {
            // Both clips' lengths are whole frames: the frame of the cycle is k modulo the end.
            let end = ends[model];
            let frame = match k % end {
                _ if k <= end => k,
                0 => end,
                into => into,
            };
            let posed = alone[model].at_frame(frame).unwrap();
            placed.file.objects[i].transform() * posed.file.objects[part].transform().inverse()
        });
        of.collect::<Vec<_>>()
    };
    let first = placings(0);
    for k in [ends[0], ends[0] + 1, ends[0] + ends[0] / 2, ends[1]] {
        for (i, (a, b)) in first.iter().zip(placings(k)).enumerate() {
            assert!(a.abs_diff_eq(b, 1e-5), "object {i}: placed otherwise at frame {k}: {a} against {b}");
        }
    }
    let ctx = validated_context();
    let mode = TlasMode { kind: TlasKind::Update, rebuild_every: 0 };
    let last = ends[1];
    let out = frames(&ctx, &scene, &["rust", "glsl"], last - 2..last + 1, mode);
    for (k, (_, outputs)) in out.iter().enumerate() {
        assert_eq!(outputs[0].hit_ids, outputs[1].hit_ids, "frame {}: the sets hit different ids", last - 2 + k as u32);
    }
    let still = |k: u32| twinray_host::render(&ctx, &scene.at_frame(k).unwrap(), &set("rust"), &opts()).unwrap();
    assert!(same(&out[2].1[0], &still(last)), "the last frame differs from a still picture of its time");
    assert!(!same(&still(0), &still(last)), "nothing moved on screen");
}

/// A placed model's clip plays under the scene's `[animation]` (object 0 keyframed along x,
/// the grid spinning, 4 frames at 1 fps): at every frame each part is where the same scene
/// with the model still puts it, after the part's own pose in the model alone at the frame's
/// time; frames render in both sets alike and as the still picture of their time.
#[test]
fn a_placed_models_clip_plays_under_the_scenes_animation() {
    let dir = tempfile::tempdir().unwrap();
    let colors = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let fps = twinray_host::scene::gltf::playing().fps;
    for folder in ["moving", "still"] {
        std::fs::create_dir(dir.path().join(folder)).unwrap();
    }
    let moving = twinray_tests::gltf::moving_strip(&dir.path().join("moving"), &colors, [0.0, 1.5, 0.0], 2.0);
    twinray_tests::gltf::strip(&dir.path().join("still"), &colors, &[[0.0; 3]]);
    let load = |model: &str| {
        let path = dir.path().join(format!("{}.toml", &model[..5]));
        std::fs::write(&path, super::animation::placed_models(model, super::animation::MODELS_MOVE)).unwrap();
        Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"))
    };
    let (scene, held) = (load("moving/strip.gltf"), load("still/strip.gltf"));
    assert_eq!(scene.frame_count(), 4, "the scene's [animation] sets the frames");
    assert!(scene.animation.as_ref().is_some_and(|a| a.moves().objects));
    let parts = colors.len();
    for k in 0..4 {
        let alone = load_at(&moving, None, Playing { time: k as f32, fps }).unwrap_or_else(|e| panic!("{e}"));
        let alone = Scene::from_model(alone, "strip").unwrap_or_else(|e| panic!("{e}"));
        let (placed, held) = (scene.at_frame(k).unwrap(), held.at_frame(k).unwrap());
        assert_eq!(placed.file.objects.len(), 3 * parts);
        for (i, object) in placed.file.objects.iter().enumerate() {
            let want = held.file.objects[i].transform() * alone.file.objects[i % parts].transform();
            assert!(
                object.transform().abs_diff_eq(want, 1e-5),
                "frame {k}, object {i}: {} against {want}",
                object.transform()
            );
        }
    }
    let ctx = validated_context();
    let mode = TlasMode { kind: TlasKind::Update, rebuild_every: 0 };
    let out = frames(&ctx, &scene, &["rust", "glsl"], 0..4, mode);
    for (k, (_, outputs)) in out.iter().enumerate() {
        assert_eq!(outputs[0].hit_ids, outputs[1].hit_ids, "frame {k}: the sets hit different ids");
    }
    let still = twinray_host::render(&ctx, &scene.at_frame(3).unwrap(), &set("rust"), &opts()).unwrap();
    assert!(same(&out[3].1[0], &still), "frame 3 differs from a still picture of its time");
}
