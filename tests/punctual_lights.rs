//! Point lights' ranges and spot lights' cones (glTF's KHR_lights_punctual) on lavapipe, with
//! validation on: a floor seen from straight above by an orthographic camera, lit by one light
//! over its middle. Every pixel of both sets lies within what glTF's formulas give over the
//! floor under it (the light's inverse square times the range's window `1 - (d / range)^4`
//! and the cone's `((cos - cos outer) / (cos inner - cos outer))^2`, clamped, worked here in
//! f64): dark past the range and outside the cone, full inside the inner cone; and the sets
//! agree.

use twinray_host::compare::{scene_diff, verdict};
use twinray_host::render::RenderOutput;
use twinray_host::scene::MeshFiles;
use twinray_host::Scene;
use twinray_tests::{render_scene, validated_context, SCENE_TEST_SIZE};

/// The floor's albedo, the light's intensity and height, and the camera's view height.
const ALBEDO: f64 = 0.5;
const INTENSITY: f64 = 4.0;
const HEIGHT: f64 = 2.0;
const VIEW: f64 = 6.0;

fn scene(light: &str) -> Scene {
    let text = format!(
        "[image]\nwidth = 160\nheight = 120\n[camera]\neye = [0.0, 10.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n\
         up = [0.0, 0.0, -1.0]\northographic_height = {VIEW}\n[materials.floor]\nkind = \"diffuse\"\n\
         color = [{ALBEDO}, {ALBEDO}, {ALBEDO}]\n[shapes.floor]\nkind = \"rectangle\"\nsize = [40.0, 40.0]\n\
         [[objects]]\nshape = \"floor\"\nmaterial = \"floor\"\n[[lights]]\nkind = \"point\"\n\
         position = [0.0, {HEIGHT}, 0.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = {INTENSITY}\n{light}\n"
    );
    Scene::parse(&text, "lights.toml", MeshFiles::Builtin).unwrap_or_else(|e| panic!("{e}"))
}

/// Asserts every pixel of `out` within `shade(r)` (the floor's radiance at distance `r` from
/// the point under the light, falling with `r`) over the part of the floor the pixel sees,
/// give or take 0.1% and 1e-6, and returns the pixels lit and dark.
fn within(out: &RenderOutput, shade: impl Fn(f64) -> f64, label: &str) -> (usize, usize) {
    let (w, h) = (out.width as usize, out.height as usize);
    let size = VIEW / h as f64;
    let (mut lit, mut dark) = (0, 0);
    for (i, rgb) in out.linear.iter().enumerate() {
        let (px, py) = ((i % w) as f64 - w as f64 / 2.0, (i / w) as f64 - h as f64 / 2.0);
        // The pixel's nearest and farthest floor points from the middle (radially symmetric).
        let near = |a: f64| if a < 0.0 && a + 1.0 > 0.0 { 0.0 } else { a.abs().min((a + 1.0).abs()) };
        let far = |a: f64| a.abs().max((a + 1.0).abs());
        let r_near = size * near(px).hypot(near(py));
        let r_far = size * far(px).hypot(far(py));
        let (low, high) = (shade(r_far) * 0.999 - 1e-6, shade(r_near) * 1.001 + 1e-6);
        let value = f64::from(rgb[0]);
        assert!(low <= value && value <= high, "{label}: pixel {i} ({px}, {py}) is {value}, not in [{low}, {high}]");
        if value > 1e-3 {
            lit += 1
        } else {
            dark += 1
        }
    }
    (lit, dark)
}

/// Both sets within `shade` and each other; something lit and something dark.
fn check(scene: &Scene, shade: impl Fn(f64) -> f64 + Copy, label: &str) {
    let ctx = validated_context();
    let rust = render_scene(&ctx, scene, "rust");
    let glsl = render_scene(&ctx, scene, "glsl");
    let d = scene_diff(scene, &rust, &glsl);
    let (w, h) = SCENE_TEST_SIZE;
    assert!(verdict(&d, &scene.file.parity, u64::from(w * h)).is_empty(), "{label}: {d:?}");
    for (set, out) in [("rust", &rust), ("glsl", &glsl)] {
        let (lit, dark) = within(out, shade, &format!("{label}, {set}"));
        assert!(lit > 1000 && dark > 1000, "{label}, {set}: {lit} pixels lit, {dark} dark");
    }
}

/// The floor's radiance at `r` under a light of `falloff(d, cos)` (`cos` to the light's axis).
fn radiance(r: f64, falloff: impl Fn(f64, f64) -> f64) -> f64 {
    let d = r.hypot(HEIGHT);
    let cos = HEIGHT / d;
    ALBEDO * INTENSITY * falloff(d, cos) * cos / (d * d)
}

fn cone(cos: f64, inner: f64, outer: f64) -> f64 {
    let (ci, co) = (inner.to_radians().cos(), outer.to_radians().cos());
    ((cos - co) / (ci - co)).clamp(0.0, 1.0).powi(2)
}

#[test]
fn a_spot_light_lights_its_cone_and_nothing_outside_it() {
    let spot = "spot = { direction = [0.0, -1.0, 0.0], inner_cone_degrees = 20.0, outer_cone_degrees = 30.0 }";
    check(&scene(spot), |r| radiance(r, |_, cos| cone(cos, 20.0, 30.0)), "spot");
}

#[test]
fn a_light_with_a_range_goes_dark_at_it() {
    let range = 3.0;
    let window = |d: f64| (1.0 - (d / range).powi(4)).clamp(0.0, 1.0);
    check(&scene(&format!("range = {range}")), |r| radiance(r, |d, _| window(d)), "range");
}
