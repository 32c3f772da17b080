//! Orthographic cameras on lavapipe, validation on: a sphere of radius 1 seen by a camera 4
//! units high spans half the image's height whatever the camera's distance (a perspective
//! camera's view of it shrinks with distance), in both sets, which agree; a glTF model no one
//! here made (assimp's Cameras.gltf, its node made to hold its orthographic camera) opens
//! with that camera.

use twinray_host::compare::{diff, verdict};
use twinray_host::render::NO_HIT_ID as NO_HIT;
use twinray_host::scene::MeshFiles;
use twinray_host::Scene;
use twinray_tests::{render_scene, validated_context};

/// A unit sphere at the origin and a camera on +z at `eye_z`, with `lens` (its camera key).
fn sphere(eye_z: f32, lens: &str) -> Scene {
    let text = format!(
        r#"
[image]
width = 160
height = 120
[camera]
eye = [0.0, 0.0, {eye_z}]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
{lens}
[materials.white]
kind = "diffuse"
color = [0.8, 0.8, 0.8]
[[lights]]
kind = "directional"
direction = [0.3, 0.5, 1.0]
color = [1.0, 1.0, 1.0]
intensity = 1.0
[shapes.ball]
kind = "sphere"
radius = 1.0
[[objects]]
shape = "ball"
material = "white"
"#
    );
    Scene::parse(&text, "sphere.toml", MeshFiles::Builtin).unwrap_or_else(|e| panic!("{e}"))
}

/// Pixels of the middle row and middle column that hit something.
fn spans(ids: &[u64], (w, h): (usize, usize)) -> (usize, usize) {
    let hit = |i: usize| ids[i] != NO_HIT;
    ((0..w).filter(|&x| hit((h / 2) * w + x)).count(), (0..h).filter(|&y| hit(y * w + w / 2)).count())
}

#[test]
fn an_orthographic_view_keeps_its_size_at_any_distance() {
    let ctx = validated_context();
    let size = (160, 120);
    for eye_z in [3.0, 30.0] {
        let scene = sphere(eye_z, "orthographic_height = 4.0");
        let rust = render_scene(&ctx, &scene, "rust");
        let glsl = render_scene(&ctx, &scene, "glsl");
        let d = diff(&rust, &glsl, scene.file.parity.pixel_threshold);
        assert!(verdict(&d, &scene.file.parity, 160 * 120).is_empty(), "eye at {eye_z}: {d:?}");
        assert_eq!(rust.hit_ids, glsl.hit_ids, "eye at {eye_z}");
        // 2 of 4 units high over 120 pixels is 60; across, 4 x 160 / 120 units over 160.
        let (across, down) = spans(&rust.hit_ids, size);
        assert!((59..=61).contains(&down) && (59..=61).contains(&across), "eye at {eye_z}: {across} x {down}");
    }
    // A perspective camera's view of it shrinks with distance.
    let near = spans(&render_scene(&ctx, &sphere(3.0, "fov_y_degrees = 60.0"), "rust").hit_ids, size);
    let far = spans(&render_scene(&ctx, &sphere(30.0, "fov_y_degrees = 60.0"), "rust").hit_ids, size);
    assert!(far.1 * 4 < near.1, "perspective: {near:?} near, {far:?} far");
    ctx.close().unwrap();
}

#[test]
fn a_gltf_orthographic_camera_is_the_view() {
    twinray_tests::allow_installed_models();
    let original = std::path::Path::new("/usr/share/assimp/models/glTF2/cameras");
    assert!(original.exists(), "{}: run `cargo xtask setup`", original.display());
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(original.join("simpleSquare.bin"), dir.path().join("simpleSquare.bin")).unwrap();
    let text = std::fs::read_to_string(original.join("Cameras.gltf")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    // Node 1 holds camera 0 (perspective), the first found; node 2 camera 1 (orthographic,
    // xmag = ymag = 1): swapped, the orthographic one is the view.
    assert_eq!(json["cameras"][1]["type"], "orthographic");
    json["nodes"][1]["camera"] = 1.into();
    json["nodes"][2]["camera"] = 0.into();
    let path = dir.path().join("Cameras.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.file.camera.orthographic_height, Some(2.0));
    assert_eq!((scene.file.image.width, scene.file.image.height), (480, 480));
    assert_eq!(scene.file.camera.eye, [0.5, 0.5, 3.0]);
    let ctx = validated_context();
    let rust = render_scene(&ctx, &scene, "rust");
    let glsl = render_scene(&ctx, &scene, "glsl");
    assert_eq!(rust.hit_ids, glsl.hit_ids);
    assert!(rust.hit_ids.iter().any(|&id| id != NO_HIT), "the square is not in view");
    ctx.close().unwrap();
}
