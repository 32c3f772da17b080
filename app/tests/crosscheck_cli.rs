//! `twinray crosscheck`'s refusals: what Mitsuba cannot render, and missing Mitsuba renders,
//! each in one line with exit code 2 before any rendering, leaving nothing behind.

use twinray_tests::cli::assert_bad_input;

#[test]
fn scenes_mitsuba_cannot_render_are_refused_by_name() {
    // `materials` has checker floors; `spheres` has a light with shadows = false.
    assert_bad_input(&["crosscheck", "materials", "--python", "python3"], &["material", "checker"]);
    assert_bad_input(&["crosscheck", "spheres", "--python", "python3"], &["light 0", "shadows = false"]);
}

#[test]
fn missing_mitsuba_renders_and_bad_sample_counts_are_input_errors() {
    assert_bad_input(&["crosscheck", "sphere"], &["no Mitsuba renders here", "--python"]);
    assert_bad_input(
        &["crosscheck", "sphere", "--python", "python3", "--mitsuba-spp", "100"],
        &["twice a square", "100"],
    );
}

/// Mitsuba's shapes read other texture coordinates than twinray's parametrisations, so a
/// texture on a procedural shape is refused rather than compared against something else.
#[test]
fn textures_on_procedural_shapes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_fn(4, 4, |x, _| image::Rgb([(x * 60) as u8, 0, 0])).save(dir.path().join("t.png")).unwrap();
    let scene = dir.path().join("ball.toml");
    std::fs::write(
        &scene,
        "name = \"ball\"\n[image]\nwidth = 32\nheight = 32\n[camera]\neye = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n\
         fov_y_degrees = 40.0\n[shapes.ball]\nkind = \"sphere\"\nradius = 1.0\n[materials.m]\nkind = \"diffuse\"\n\
         color = [1.0, 1.0, 1.0]\ntexture = { file = \"t.png\" }\n[[objects]]\nshape = \"ball\"\nmaterial = \"m\"\n\
         [[lights]]\nkind = \"directional\"\ndirection = [0.0, 1.0, 1.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n",
    )
    .unwrap();
    let path = scene.to_string_lossy().into_owned();
    assert_bad_input(&["crosscheck", &path, "--python", "python3"], &["object 0", "procedural shape", "use a mesh"]);
}
