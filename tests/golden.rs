//! Golden images: every built-in scene rendered by each shader set at the test size, against
//! the committed PNGs in tests/golden/ (linear 8-bit values, the steps parity counts; written
//! tagged gAMA 1.0, not sRGB). Refreshed only by `cargo xtask golden [SCENES]`, which
//! sets TWINRAY_REFRESH_GOLDEN=1 (and TWINRAY_GOLDEN_SCENES to the scenes named, comma-separated;
//! empty is all); review the new images with git diff before committing them.
//!
//! Tolerance: the scene's parity tolerance on colour, which covers a different Mesa or LLVM
//! build rounding a few pixels differently; a changed shader fails it.

use twinray_host::compare::{color_diff, color_verdict};
use twinray_host::util::output::write_linear_png;
use twinray_tests::{builtin_scenes, render_scene, repo_root, validated_context, SCENE_TEST_SIZE};

fn check_goldens(set: &str) {
    let ctx = validated_context();
    let refresh = std::env::var_os("TWINRAY_REFRESH_GOLDEN").is_some();
    let only = std::env::var("TWINRAY_GOLDEN_SCENES").unwrap_or_default();
    let only: Vec<&str> = only.split(',').filter(|s| !s.is_empty()).collect();
    let scenes = builtin_scenes();
    for name in &only {
        assert!(scenes.iter().any(|s| s.name() == *name), "TWINRAY_GOLDEN_SCENES names no built-in scene {name:?}");
    }
    let mut failures = Vec::new();
    for scene in scenes.into_iter().filter(|s| only.is_empty() || only.contains(&s.name())) {
        let out = render_scene(&ctx, &scene, set);
        let path = repo_root().join(format!("tests/golden/{}-{set}.png", scene.name()));
        if refresh {
            write_linear_png(&path, out.width, out.height, &out.rgba).expect("writing golden image");
            continue;
        }
        let golden = match image::open(&path) {
            Ok(image) => image.to_rgba8(),
            Err(e) => {
                failures.push(format!("{}: {e} (create it with `cargo xtask golden`)", path.display()));
                continue;
            }
        };
        if golden.dimensions() != SCENE_TEST_SIZE {
            failures.push(format!("{} is {:?}, not {SCENE_TEST_SIZE:?}", path.display(), golden.dimensions()));
            continue;
        }
        let parity = scene.file.parity;
        let d = color_diff(golden.as_raw(), &out.rgba, parity.pixel_threshold);
        let f = color_verdict(&d, &parity, u64::from(SCENE_TEST_SIZE.0 * SCENE_TEST_SIZE.1));
        if !f.is_empty() {
            failures.push(format!("{} differs from {}: {f:?}", scene.name(), path.display()));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}\nif the change is intended, run `cargo xtask golden` and review");
}

#[test]
fn rust_set_matches_golden_images() {
    check_goldens("rust");
}

#[test]
fn glsl_set_matches_golden_images() {
    check_goldens("glsl");
}
