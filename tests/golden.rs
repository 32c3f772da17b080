//! Golden images: each shader set's render of the default scene at the test size, against the
//! committed PNG in tests/golden/. Refreshed only by `cargo xtask golden`, which sets
//! TWINRAY_REFRESH_GOLDEN=1; review the new images with git diff before committing them.
//!
//! Tolerance: the scene's parity tolerance on colour, which covers a different Mesa or LLVM
//! build rounding a few pixels differently; a changed shader fails it.

use twinray::compare::{color_diff, color_verdict};
use twinray::output::write_png;
use twinray_tests::{default_scene, render, repo_root, validated_context, TEST_SIZE};

fn check_golden(set: &str) {
    let ctx = validated_context();
    let scene = default_scene();
    let out = render(&ctx, &scene, set);
    let path = repo_root().join(format!("tests/golden/{}-{set}.png", scene.name()));
    if std::env::var_os("TWINRAY_REFRESH_GOLDEN").is_some() {
        write_png(&path, out.width, out.height, &out.rgba).expect("writing golden image");
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (create it with `cargo xtask golden`)", path.display()))
        .to_rgba8();
    assert_eq!(golden.dimensions(), (TEST_SIZE, TEST_SIZE), "{} has the wrong size", path.display());
    let parity = scene.file.parity;
    let d = color_diff(golden.as_raw(), &out.rgba, parity.pixel_threshold);
    let f = color_verdict(&d, &parity, u64::from(TEST_SIZE * TEST_SIZE));
    assert!(
        f.is_empty(),
        "{set} differs from {}: {f:?} ({d:?}); if intended, run `cargo xtask golden`",
        path.display()
    );
}

#[test]
fn rust_set_matches_golden_image() {
    check_golden("rust");
}

#[test]
fn glsl_set_matches_golden_image() {
    check_golden("glsl");
}
