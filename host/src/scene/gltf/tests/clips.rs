//! A model's animation played over frames: frame k is the still picture of its time
//! (`--time` plus k / fps), objects, camera and posed meshes alike, up to the last key; a
//! node hidden (scaled to zero) in some frame is refused with its time named.

use crate::scene::gltf::{load_at, Playing, ASSIMP_TEST_MODELS};
use crate::scene::Scene;
use glam::{Mat4, Vec3};

/// The square in node 0, whose `path` two keys (0.5 s and 1.5 s, LINEAR) take from `from`
/// to `to`; node 1, its child, holds a perspective camera looking down -z from 5 up z.
fn keyed(path: &str, from: [f32; 3], to: [f32; 3]) -> String {
    let nodes = r#"{"mesh": 0, "children": [1]}, {"camera": 0, "translation": [0.5, 0.5, 5]}"#;
    let camera = r#", "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]"#;
    super::posed::keyed("LINEAR", path, [from, to], nodes, camera)
}

fn played(text: &str, playing: Playing) -> Result<Scene, String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.gltf");
    std::fs::write(&path, text).unwrap();
    let model = load_at(&path, None, playing)?;
    Scene::from_model(model, "model.gltf").map_err(|e| e.to_string())
}

fn placed(scene: &Scene) -> Mat4 {
    Mat4::from_cols_array(&scene.file.objects[0].matrix.unwrap())
}

#[test]
fn each_frame_is_the_still_picture_of_its_time() {
    let text = keyed("translation", [0.0; 3], [4.0, 0.0, 0.0]);
    for (start, frames) in [(0.0, 7), (1.0, 3)] {
        let scene = played(&text, Playing { time: start, fps: 4.0 }).unwrap();
        let animation = scene.animation.as_ref().expect("a clip");
        // Keys to 1.5 s at 4 frames a second.
        assert_eq!(scene.frame_count(), frames, "from {start} s");
        let moves = animation.moves();
        assert!(moves.objects && moves.camera && !moves.meshes && !moves.lights, "{moves:?}");
        for k in 0..frames {
            let time = start + k as f32 / 4.0;
            assert_eq!(animation.time(k), time);
            let still = played(&text, Playing { time, fps: 4.0 }).unwrap();
            let frame = scene.at_frame(k).unwrap();
            assert_eq!(placed(&frame), placed(&still), "frame {k} from {start} s");
            assert_eq!(frame.file.camera.eye, still.file.camera.eye, "frame {k} from {start} s");
            // Linear from x = 0 at 0.5 s to x = 4 at 1.5 s; the camera rides on its child.
            let x = 4.0 * (time - 0.5).clamp(0.0, 1.0);
            assert!((placed(&frame).w_axis.x - x).abs() < 1e-6, "frame {k} from {start} s");
            assert!((frame.file.camera.eye[0] - (x + 0.5)).abs() < 1e-6, "frame {k} from {start} s");
        }
    }
    // From the last key on, a still.
    assert!(played(&text, Playing { time: 1.5, fps: 4.0 }).unwrap().animation.is_none());
}

/// glTF hides a node by scaling it to zero; a moving scene draws its objects in every frame,
/// so a clip that hides one is refused, its node and time named; a still of a time it is
/// shown still loads.
#[test]
fn a_node_hidden_in_some_frame_is_refused_with_its_time() {
    let text = keyed("scale", [1.0; 3], [1.0, 0.0, 1.0]);
    let Err(e) = played(&text, Playing { time: 0.0, fps: 4.0 }) else { panic!("loaded") };
    assert!(e.contains("at 1.5 s (frame 6 at 4 fps)") && e.contains("node 0: matrix"), "{e}");
    assert!(played(&text, Playing { time: 1.5, fps: 4.0 }).is_err(), "a still of it hidden");
    let e = played(&text, Playing { time: 0.0, fps: 4.0 }).unwrap_err();
    assert_eq!(e.lines().count(), 1, "{e}");
}

/// AnimatedMorphCube (no one here made it): its weights change over 4.17 s; each frame's
/// posed mesh is, vertex for vertex, the still picture's of that time.
#[test]
fn a_clip_poses_its_meshes_at_every_frame() {
    let path = std::path::Path::new(ASSIMP_TEST_MODELS)
        .join("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
    let load = |time| {
        let model = load_at(&path, None, Playing { time, fps: 2.0 }).expect("the cube");
        Scene::from_model(model, "cube").expect("the cube")
    };
    let scene = load(0.0);
    let animation = scene.animation.as_ref().expect("a clip");
    assert!(animation.moves().meshes && !animation.moves().objects, "{:?}", animation.moves());
    assert_eq!(scene.frame_count(), 9);
    let shape = &scene.file.objects[0].shape;
    let corners = |s: &Scene| s.meshes[shape].vertices.iter().map(|v| v.position.truncate()).collect::<Vec<Vec3>>();
    let mut moved = false;
    for k in 0..scene.frame_count() {
        let frame = corners(&scene.at_frame(k).unwrap());
        assert_eq!(frame, corners(&load(k as f32 / 2.0)), "frame {k}");
        moved |= frame != corners(&scene);
    }
    assert!(moved, "no frame moved a vertex");
}
