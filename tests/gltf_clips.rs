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
