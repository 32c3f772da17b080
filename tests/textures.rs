//! Textures in both sets: a floor textured with a fine checker, seen from just above it, so
//! that its texels shrink from many pixels each near the camera to many texels per pixel far
//! away. Against a converged render of level 0 (64 jittered samples per pixel, each at level
//! 0: the box-filtered truth), one sample per pixel with ray-cone level of detail must be far
//! nearer than one sample at level 0 in the distance (no aliasing) and no farther near by (no
//! blur); the Rust and GLSL sets must agree on it; a material's texture is read through its
//! coordinate transform.

use std::path::Path;
use twinray_host::render::{RenderOptions, RenderOutput};
use twinray_host::scene::Scene;
use twinray_tests::{set, validated_context};

const SIZE: (u32, u32) = (128, 96);

/// A 64x64 checker of 8-texel cells, black and white.
fn write_checker(path: &Path) {
    let image = image::RgbaImage::from_fn(64, 64, |x, y| {
        let v = if ((x / 8) + (y / 8)) % 2 == 0 { 255 } else { 0 };
        image::Rgba([v, v, v, 255])
    });
    image.save(path).unwrap();
}

/// A floor quad from z = 2 to z = -200, its texture coordinates a quarter of x and z.
fn write_floor(path: &Path) {
    let (x, near, far) = (60.0, 2.0, -200.0);
    let corners = [(-x, near), (x, near), (x, far), (-x, far)];
    let mut obj = String::new();
    for (cx, cz) in corners {
        obj += &format!("v {cx} 0 {cz}\n");
    }
    for (cx, cz) in corners {
        // OBJ's v runs up the image; twinray turns it to run down, as glTF's does.
        obj += &format!("vt {} {}\n", cx / 4.0, 1.0 - cz / 4.0);
    }
    obj += "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    std::fs::write(path, obj).unwrap();
}

/// The floor of material `material` (a TOML table's body), lit from above, seen from just above
/// it with `samples` per pixel and level of detail `lod`; `extra` adds to the scene file.
fn floor_scene(dir: &Path, name: &str, (samples, lod): (u32, &str), material: &str, extra: &str) -> Scene {
    write_floor(&dir.join("floor.obj"));
    let floor = "kind = \"mesh\"\nfile = \"floor.obj\"\nnormals = \"flat\"";
    floor_of(dir, name, (samples, lod), (floor, ""), (material, extra))
}

/// `floor_scene` with the floor's shape `floor` (a TOML table's body) placed by `placed` (keys
/// of its object).
fn floor_of(
    dir: &Path,
    name: &str,
    (samples, lod): (u32, &str),
    (floor, placed): (&str, &str),
    (material, extra): (&str, &str),
) -> Scene {
    write_checker(&dir.join("checker.png"));
    let text = format!(
        r#"
name = "{name}"
background = [0.0, 0.0, 0.0]
[image]
width = {w}
height = {h}
samples = {samples}
texture_lod = "{lod}"
[camera]
eye = [0.0, 0.6, 2.0]
target = [0.0, 0.0, -6.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 60.0
[shapes.floor]
{floor}
[materials.m]
{material}
[[objects]]
shape = "floor"
material = "m"
{placed}
[[lights]]
kind = "directional"
direction = [0.0, 1.0, 0.0]
color = [1.0, 1.0, 1.0]
intensity = 1.0
shadows = false
{extra}
"#,
        w = SIZE.0,
        h = SIZE.1
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"))
}

/// The floor textured with the checker, read through `transform` (`, transform = ...` or "").
fn scene(dir: &Path, samples: u32, lod: &str, transform: &str) -> Scene {
    let material =
        format!("kind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\ntexture = {{ file = \"checker.png\"{transform} }}");
    floor_scene(dir, &format!("floor-{samples}-{lod}"), (samples, lod), &material, "")
}

fn render(scene: &Scene, shaders: &str) -> RenderOutput {
    let opts = RenderOptions::once(SIZE.0, SIZE.1, 0, 1);
    twinray_host::render(&validated_context(), scene, &set(shaders), &opts).unwrap_or_else(|e| panic!("{e}"))
}

/// RMSE of `a` against `b` over rows `rows` (luminance-free: the mean of the channels).
fn rmse(a: &RenderOutput, b: &RenderOutput, rows: std::ops::Range<u32>) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for y in rows {
        for x in 0..SIZE.0 {
            let i = (y * SIZE.0 + x) as usize;
            let (p, q) = (a.linear[i], b.linear[i]);
            sum += (0..3).map(|c| f64::from(p[c] - q[c]).powi(2)).sum::<f64>() / 3.0;
            n += 1.0;
        }
    }
    (sum / n).sqrt()
}

#[test]
fn ray_cones_neither_alias_in_the_distance_nor_blur_near_by() {
    let dir = tempfile::tempdir().unwrap();
    let truth = render(&scene(dir.path(), 16, "zero", ""), "glsl");
    let cones = scene(dir.path(), 1, "cones", "");
    let (rust, glsl) = (render(&cones, "rust"), render(&cones, "glsl"));
    let zero = render(&scene(dir.path(), 1, "zero", ""), "rust");
    // The first row that sees the floor: its horizon. Far: the 12 rows under it, where a pixel
    // spans from 30 down to 2 checker cells along the view; near: the bottom quarter, where a
    // cell spans many pixels.
    let horizon =
        (0..SIZE.1).find(|&y| rust.hit_ids[(y * SIZE.0) as usize] != twinray_host::render::NO_HIT_ID).unwrap();
    let (far, near) = (horizon..horizon + 12, SIZE.1 - SIZE.1 / 4..SIZE.1);
    let (cones_far, zero_far) = (rmse(&rust, &truth, far.clone()), rmse(&zero, &truth, far));
    let (cones_near, zero_near) = (rmse(&rust, &truth, near.clone()), rmse(&zero, &truth, near));
    eprintln!(
        "rmse against 256 samples at level 0, horizon at row {horizon}: far cones {cones_far:.4}, level 0 \
         {zero_far:.4}; near cones {cones_near:.4}, level 0 {zero_near:.4}"
    );
    // Measured on lavapipe 22.3: far 0.053 against 0.412, near 0.005 against 0.016.
    assert!(cones_far < 0.3 * zero_far, "level 0 aliases in the distance; the cones should not");
    assert!(cones_near <= 1.1 * zero_near + 0.005, "the cones blur what level 0 shows sharp");
    // Both sets alike.
    let d = twinray_host::compare::diff(&rust, &glsl, cones.file.parity.pixel_threshold);
    eprintln!("rust against glsl: rmse {:.6}, {} hit mismatches", d.color.rmse, d.hit_mismatches);
    assert_eq!(d.hit_mismatches, 0);
    assert!(twinray_host::compare::verdict(&d, &cones.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty());
}

/// The material's transform moves the texture: half a checker cell along u turns black cells
/// white where the floor is sharp, in both sets alike.
#[test]
fn a_texture_transform_moves_the_texture() {
    let dir = tempfile::tempdir().unwrap();
    let plain = render(&scene(dir.path(), 1, "zero", ""), "rust");
    let moved_scene = scene(dir.path(), 1, "zero", ", transform = [[1.0, 0.0, 0.125], [0.0, 1.0, 0.0]]");
    let (moved, glsl) = (render(&moved_scene, "rust"), render(&moved_scene, "glsl"));
    let near = SIZE.1 - SIZE.1 / 8..SIZE.1;
    assert!(rmse(&plain, &moved, near) > 0.3, "the transform changed nothing");
    let d = twinray_host::compare::diff(&moved, &glsl, moved_scene.file.parity.pixel_threshold);
    assert_eq!(d.hit_mismatches, 0);
    assert!(twinray_host::compare::verdict(&d, &moved_scene.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty());
}

/// A checker of alpha: opaque white cells and transparent ones.
fn write_alpha_checker(path: &Path) {
    let image = image::RgbaImage::from_fn(64, 64, |x, y| {
        let solid = ((x / 8) + (y / 8)) % 2 == 0;
        image::Rgba([255, 255, 255, if solid { 255 } else { 0 }])
    });
    image.save(path).unwrap();
}

/// A floor alpha-tested by its texture (glTF's alpha mode MASK: `pattern = "alpha"`) above a
/// plain one, seen from above, lit from above with shadows.
/// `top` adds top-level keys (how rays are traced).
fn masked_scene(dir: &Path, opacity: f32, top: &str) -> Scene {
    write_alpha_checker(&dir.join("alpha.png"));
    write_floor(&dir.join("floor.obj"));
    let text = format!(
        r#"
name = "masked-floor"
{top}
[image]
width = {w}
height = {h}
[camera]
eye = [0.0, 3.0, -5.0]
target = [0.0, 0.0, -5.0]
up = [0.0, 0.0, -1.0]
fov_y_degrees = 60.0
[shapes.floor]
kind = "mesh"
file = "floor.obj"
normals = "flat"
[materials.mask]
kind = "cutout"
color = [1.0, 0.2, 0.2]
pattern = "alpha"
scale = 1.0
threshold = 0.5
opacity = {opacity}
texture = {{ file = "alpha.png" }}
[materials.under]
kind = "diffuse"
color = [0.2, 0.2, 1.0]
[[objects]]
shape = "floor"
material = "mask"
[[objects]]
shape = "floor"
material = "under"
translate = [0.0, -1.0, 0.0]
[[lights]]
kind = "directional"
direction = [0.3, 1.0, 0.2]
color = [1.0, 1.0, 1.0]
intensity = 1.0
"#,
        w = SIZE.0,
        h = SIZE.1
    );
    let path = dir.join(format!("masked-{opacity}-{}.toml", top.len()));
    std::fs::write(&path, text).unwrap();
    Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"))
}

/// What share of the pixels see object `object` first.
fn share(out: &RenderOutput, object: u64) -> f64 {
    out.hit_ids.iter().filter(|&&id| id != twinray_host::render::NO_HIT_ID && id >> 32 == object).count() as f64
        / out.hit_ids.len() as f64
}

/// Through the transparent half of the texture, rays (primary and shadow alike) reach the
/// floor below; both sets agree; an opacity under the threshold makes the floor all hole.
#[test]
fn a_texture_s_alpha_cuts_holes_for_every_ray() {
    let dir = tempfile::tempdir().unwrap();
    let scene = masked_scene(dir.path(), 1.0, "");
    let (rust, glsl) = (render(&scene, "rust"), render(&scene, "glsl"));
    let (upper, lower) = (share(&rust, 0), share(&rust, 1));
    eprintln!("upper floor {upper:.3}, lower {lower:.3}");
    assert!((0.4..0.6).contains(&upper) && (upper + lower - 1.0).abs() < 1e-9, "{upper} {lower}");
    // Light reaches the lower floor through the holes only: lit and shadowed pixels both.
    let lower_pixels: Vec<f32> =
        (0..rust.hit_ids.len()).filter(|&i| rust.hit_ids[i] >> 32 == 1).map(|i| rust.linear[i][2]).collect();
    let lit = lower_pixels.iter().filter(|&&b| b > 0.1).count() as f64 / lower_pixels.len() as f64;
    assert!((0.2..0.8).contains(&lit), "share of the lower floor lit through the holes: {lit}");
    let d = twinray_host::compare::diff(&rust, &glsl, scene.file.parity.pixel_threshold);
    assert_eq!(d.hit_mismatches, 0);
    assert!(twinray_host::compare::verdict(&d, &scene.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty());
    let clear = render(&masked_scene(dir.path(), 0.4, ""), "glsl");
    assert_eq!(share(&clear, 0), 0.0, "opacity 0.4 under a threshold of 0.5: no surface");
}

/// Rays traced inline by ray queries test the same alpha with the same code: shadow rays
/// (`shadow_method = "query"`) and the compute renderer's primary rays give the pipeline's
/// image and hits, in both sets.
#[test]
fn rays_traced_inline_test_the_same_alpha() {
    let dir = tempfile::tempdir().unwrap();
    let pipeline = render(&masked_scene(dir.path(), 1.0, ""), "glsl");
    for top in ["shadow_method = \"query\"", "renderer = \"compute\""] {
        let scene = masked_scene(dir.path(), 1.0, top);
        for language in ["rust", "glsl"] {
            let inline = render(&scene, language);
            let d = twinray_host::compare::diff(&pipeline, &inline, scene.file.parity.pixel_threshold);
            eprintln!("{top}, {language}: rmse {:.6}, {} hit mismatches", d.color.rmse, d.hit_mismatches);
            assert_eq!(d.hit_mismatches, 0, "{top}, {language}");
            assert!(twinray_host::compare::verdict(&d, &scene.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty());
        }
    }
}

/// The floor and a ball, lit from above, both of material `material` (a TOML table body).
fn emissive_scene(dir: &Path, name: &str, material: &str) -> Scene {
    let ball = "[shapes.ball]\nkind = \"sphere\"\nradius = 0.3\n[[objects]]\nshape = \"ball\"\nmaterial = \"m\"\n\
                translate = [0.0, 0.5, -3.0]\n";
    floor_scene(dir, name, (1, "zero"), material, ball)
}

/// The same floor as a procedural rectangle, from z = 2 to -200, its parametrisation turned by
/// the material's transform into the mesh's coordinates (x / 4, z / 4): with ray cones the
/// two render alike, so a shape's footprint reaches texture space as a triangle's does.
#[test]
fn a_procedural_floor_filters_as_the_mesh_does() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = scene(dir.path(), 1, "cones", "");
    let material = "kind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\n\
                    texture = { file = \"checker.png\", transform = [[30.0, 0.0, -15.0], [0.0, 50.5, -50.0]] }";
    let rectangle = ("kind = \"rectangle\"\nsize = [120.0, 202.0]", "translate = [0.0, 0.0, -99.0]");
    let flat = floor_of(dir.path(), "rectangle", (1, "cones"), rectangle, (material, ""));
    let (mesh_image, rust, glsl) = (render(&mesh, "glsl"), render(&flat, "rust"), render(&flat, "glsl"));
    let all = 0..SIZE.1;
    let (against_mesh, sets) = (rmse(&rust, &mesh_image, all.clone()), rmse(&rust, &glsl, all));
    eprintln!("rectangle against mesh: rmse {against_mesh:.5}; rust against glsl {sets:.6}");
    assert!(against_mesh < 0.01, "the rectangle filters otherwise than the mesh: rmse {against_mesh}");
    let level_zero = render(&floor_of(dir.path(), "zero", (1, "zero"), rectangle, (material, "")), "rust");
    assert!(rmse(&level_zero, &mesh_image, 0..SIZE.1) > 5.0 * against_mesh.max(0.002), "filtering changed nothing");
    let d = twinray_host::compare::diff(&rust, &glsl, flat.file.parity.pixel_threshold);
    assert_eq!(d.hit_mismatches, 0);
    assert!(twinray_host::compare::verdict(&d, &flat.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty());
}

/// A material's emission adds to the light it reflects: the factor times its texture (black
/// cells emit nothing, white ones the factor), on the floor's coordinates and on the ball's
/// parametrisation alike; both sets alike.
#[test]
fn emission_adds_its_factor_times_its_texture() {
    let dir = tempfile::tempdir().unwrap();
    let base = "kind = \"diffuse\"\ncolor = [0.5, 0.5, 0.5]";
    let plain = render(&emissive_scene(dir.path(), "plain", base), "glsl");
    let e = [0.2f32, 0.3, 0.1];
    let emission = format!(
        "{base}\nemission = {{ color = [0.1, 0.15, 0.05], intensity = 2.0, texture = {{ file = \"checker.png\" }} }}"
    );
    let glowing = emissive_scene(dir.path(), "glowing", &emission);
    let (rust, glsl) = (render(&glowing, "rust"), render(&glowing, "glsl"));
    // What the emission added at each pixel, as a share of the factor (the same in every
    // channel, or the wrong channel went somewhere).
    let added = |i: usize| {
        let s: Vec<f32> = (0..3).map(|c| (rust.linear[i][c] - plain.linear[i][c]) / e[c]).collect();
        assert!((s[0] - s[1]).abs() < 0.02 && (s[1] - s[2]).abs() < 0.02, "pixel {i}: {s:?}");
        s[0]
    };
    let object = |i: usize, o: u64| rust.hit_ids[i] != twinray_host::render::NO_HIT_ID && rust.hit_ids[i] >> 32 == o;
    let ball: Vec<f32> = (0..rust.hit_ids.len()).filter(|&i| object(i, 1)).map(added).collect();
    let (low, high) = ball.iter().fold((f32::MAX, f32::MIN), |(l, h), &s| (l.min(s), h.max(s)));
    eprintln!("ball: {} pixels emit {low:.3} to {high:.3} of the factor", ball.len());
    assert!(!ball.is_empty() && low > -0.01 && high < 1.01, "the ball emits beyond its factor: {ball:?}");
    assert!(high - low > 0.5, "the checker does not shape the ball's emission: {low} to {high}");
    // The near rows of the floor, where a checker cell spans pixels: many see a cell whole (the
    // rest, bilinearly filtered across a cell's edge, between the two).
    let near = (SIZE.1 - SIZE.1 / 4) * SIZE.0..SIZE.1 * SIZE.0;
    let floor: Vec<f32> = near.map(|i| i as usize).filter(|&i| object(i, 0)).map(added).collect();
    let (dark, bright) = (
        floor.iter().filter(|s| s.abs() < 0.01).count() as f64 / floor.len() as f64,
        floor.iter().filter(|s| (*s - 1.0).abs() < 0.01).count() as f64 / floor.len() as f64,
    );
    eprintln!("near floor: {dark:.3} emit nothing, {bright:.3} the factor");
    assert!(dark > 0.3 && bright > 0.3, "the texture does not shape the emission");
    assert!(floor.iter().all(|s| (-0.01..=1.01).contains(s)), "emission beyond the factor times [0, 1]");
    let d = twinray_host::compare::diff(&rust, &glsl, glowing.file.parity.pixel_threshold);
    assert_eq!(d.hit_mismatches, 0);
    assert!(twinray_host::compare::verdict(&d, &glowing.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty());
}

/// A 64x64 image whose red grows with u and green with v: texel (i, j) holds 8-bit sRGB
/// `i * 255 / 63`, `j * 255 / 63`.
fn write_uv_image(path: &Path) {
    let code = |i: u32| (i * 255 / 63) as u8;
    image::RgbImage::from_fn(64, 64, |x, y| image::Rgb([code(x), code(y), 0])).save(path).unwrap();
}

/// What `write_uv_image`'s image gives at coordinate `c` along one axis, filtered bilinearly at
/// level 0 in linear light (sRGB decoded before filtering, as Vulkan's sRGB formats are).
fn uv_image_at(c: f64) -> f64 {
    let decode = |i: f64| {
        let e = (i * 255.0 / 63.0).floor() / 255.0;
        if e <= 0.04045 {
            e / 12.92
        } else {
            ((e + 0.055) / 1.055).powf(2.4)
        }
    };
    let x = c * 64.0 - 0.5;
    let (k, f) = (x.floor(), x - x.floor());
    decode(k) * (1.0 - f) + decode(k + 1.0) * f
}

/// Every procedural shape wears a texture through its documented parametrisation, in both
/// sets: each pixel that sees a shape emits what the image holds at the coordinates the f64
/// reference finds for its ray (`twinray_host::reference::uv`), the shapes emitting their texture
/// and reflecting nothing. Pixels within a texel of the image's edges (seams, where repeat
/// wrapping blends both ends) are left out.
#[test]
fn every_shape_reads_its_texture_where_the_reference_puts_the_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    write_uv_image(&dir.path().join("uv.png"));
    let text = std::fs::read_to_string(twinray_tests::repo_root().join("tests/textures/shapes.toml")).unwrap();
    let path = dir.path().join("shapes.toml");
    std::fs::write(&path, text).unwrap();
    let scene = Scene::load(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{e}"));
    let (rust, glsl) = (render(&scene, "rust"), render(&scene, "glsl"));
    let d = twinray_host::compare::diff(&rust, &glsl, scene.file.parity.pixel_threshold);
    assert_eq!(d.hit_mismatches, 0);
    assert!(twinray_host::compare::verdict(&d, &scene.file.parity, u64::from(SIZE.0 * SIZE.1)).is_empty());
    let reference = twinray_host::reference::scene::SceneReference::new(&scene).unwrap();
    let rays = twinray_host::explain::rays::Camera::new(&scene, SIZE).first_samples();
    let mut checked = vec![0usize; reference.objects.len()];
    let mut first = std::collections::BTreeMap::new();
    let mut wrong = Vec::new();
    for (i, ray) in rays.iter().enumerate() {
        let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
        let reach = (f64::from(ray.origin.w), f64::from(ray.direction.w));
        let twinray_host::reference::scene::SceneVerdict::Hit { object, .. } = reference.trace(o, d, reach.0, reach.1)
        else {
            continue;
        };
        let Some((k, p)) = reference.shape_hit(object, o, d, reach) else { continue };
        let (uv, _) = twinray_host::reference::uv::uv(&reference.objects[object].shapes[k], p).unwrap();
        if uv.min_element() < 1.0 / 64.0 || uv.max_element() > 63.0 / 64.0 {
            continue;
        }
        checked[object] += 1;
        first.entry(object).or_insert(i as u32);
        let want = [uv_image_at(uv.x), uv_image_at(uv.y)];
        for (label, out) in [("rust", &rust), ("glsl", &glsl)] {
            let got = out.linear[i];
            if (0..2).any(|c| (f64::from(got[c]) - want[c]).abs() > 0.01) || got[2] != 0.0 {
                wrong.push(format!("{label} pixel {i} on object {object} at uv {uv}: {got:?}, not {want:?}"));
            }
        }
    }
    eprintln!("pixels checked per object: {checked:?}; {} wrong", wrong.len());
    assert!(checked.iter().all(|&n| n >= 100), "too few pixels on some object: {checked:?}");
    // Box edges, where the shaders pick the face by the reported normal and the reference by
    // the point, may differ by a pixel's worth.
    let total: usize = checked.iter().sum();
    assert!(wrong.len() * 200 <= total, "{} of {total} wrong, first: {:?}", wrong.len(), &wrong[..wrong.len().min(5)]);
    // explain names the texture and coordinates of a hit on a shape, per set as the reference.
    let sets = [("rust".to_string(), set("rust")), ("glsl".to_string(), set("glsl"))];
    for object in [0, 4] {
        let i = first[&object];
        let px = twinray_host::explain::pixel::explain_pixel(
            &validated_context(),
            &scene,
            &sets,
            SIZE,
            (i % SIZE.0, i / SIZE.0),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let truth = px.reference_surfaces[0].as_ref().expect("the reference's surface");
        for s in &px.sets {
            let on = s.samples[0].surface.as_ref().expect("the set's surface");
            let (a, b) = (&on.textures[0], &truth.textures[0]);
            assert_eq!((a.role, a.file.as_str()), ("emission", "uv.png"));
            assert!((a.uv[0] - b.uv[0]).abs() < 1e-4 && (a.uv[1] - b.uv[1]).abs() < 1e-4, "{a:?} against {b:?}");
            assert_eq!(a.level, 0.0, "texture_lod = \"zero\"");
        }
    }
}
