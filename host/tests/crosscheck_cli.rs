//! `twinray crosscheck`'s refusals: what Mitsuba cannot render, and missing Mitsuba renders,
//! each in one line with exit code 2 before any rendering, leaving nothing behind.

mod common;

use common::assert_bad_input;

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
