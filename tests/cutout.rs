//! Cutouts (the any-hit stage), on lavapipe with validation on: light falls through a cutout's
//! holes exactly where its pattern says, for a procedural sheet and a mesh slab, in both sets
//! and with the any-hit stage from the other language; the camera's rays pass through the
//! same holes; and only cutout objects get a hit group with an any-hit stage.

use glam::{UVec2, Vec2, Vec3};
use twinray_host::render::pipeline::plan_modules;
use twinray_host::scene::{MeshFiles, Scene};
use twinray_host::RenderOptions;
use twinray_tests::{set, validated_context};

/// A floor under two cutouts 1 unit above it, lit only by a directional light from
/// (0.5, 1, 0), seen from straight above: a procedural rectangle with checker holes (cells of
/// 0.5) left of x = 0 and a flat mesh box with disc holes (cells of 1, its pattern scaled by
/// the object's 4x4 footprint) right of it.
const SCENE: &str = r#"
name = "cutout-test"
[image]
width = 240
height = 240
[camera]
eye = [0.0, 30.0, 0.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov_y_degrees = 19.0
[materials.floor]
kind = "diffuse"
color = [0.8, 0.8, 0.8]
[materials.checker]
kind = "cutout"
color = [0.5, 0.5, 0.5]
pattern = "checker"
scale = 2.0
threshold = 0.5
[materials.discs]
kind = "cutout"
color = [0.5, 0.5, 0.5]
pattern = "discs"
scale = 1.0
threshold = 0.8
[[lights]]
kind = "directional"
direction = [0.5, 1.0, 0.0]
color = [1.0, 1.0, 1.0]
intensity = 1.0
[shapes.floor]
kind = "rectangle"
size = [30.0, 30.0]
[shapes.sheet]
kind = "rectangle"
size = [4.0, 4.0]
[shapes.slab]
kind = "mesh"
builtin = "box"
[[objects]]
shape = "floor"
material = "floor"
[[objects]]
shape = "sheet"
material = "checker"
translate = [-2.5, 1.0, 0.0]
[[objects]]
shape = "slab"
material = "discs"
translate = [2.5, 1.0, 0.0]
scale = [4.0, 0.02, 4.0]
"#;

const FLOOR: u32 = 0;
/// World distance from a hole's edge within which a pixel is not judged: rounding of the
/// f32 hit point, the slab's two faces 0.02 apart (0.01 apart along x for the slanted light).
const MARGIN: f32 = 0.02;

/// Whether the cutouts are solid at world point `p` (on their plane y = 1): `Some(true)` on
/// solid parts, `Some(false)` in holes or beside the cutouts, `None` within `MARGIN` of an
/// edge.
fn covered(p: Vec3) -> Option<bool> {
    let solid_at = |q: Vec3| -> bool {
        let sheet = (q.x + 2.5).abs() <= 2.0 && q.z.abs() <= 2.0;
        let slab = (q.x - 2.5).abs() <= 2.0 && q.z.abs() <= 2.0;
        if sheet {
            // Checker cells of 0.5 in the sheet's space (x - (-2.5), z).
            let cell = ((Vec2::new(q.x + 2.5, q.z)) * 2.0).floor();
            (cell.x + cell.y).rem_euclid(2.0) == 0.0
        } else if slab {
            // Disc holes of radius 0.8 half-cells in the slab's space ((x - 2.5) / 4, z / 4).
            let o = Vec2::new((q.x - 2.5) / 4.0, q.z / 4.0);
            ((o - o.floor() - Vec2::splat(0.5)) * 2.0).length().min(1.0) >= 0.8
        } else {
            false
        }
    };
    let here = solid_at(p);
    let nudges = [Vec3::X, -Vec3::X, Vec3::Z, -Vec3::Z];
    nudges.iter().all(|d| solid_at(p + *d * MARGIN) == here).then_some(here)
}

#[test]
fn light_falls_through_the_holes_exactly_where_the_pattern_says() {
    let scene = Scene::parse(SCENE, "cutout-test", MeshFiles::Builtin).expect("scene");
    let ctx = validated_context();
    let (w, h) = (scene.file.image.width, scene.file.image.height);
    let frame = scene.frame_uniform(w, h);
    let light = Vec3::new(0.5, 1.0, 0.0).normalize();
    for set_text in ["rust", "glsl", "rust,any_hit=glsl", "glsl,any_hit=rust"] {
        let out = twinray_host::render(&ctx, &scene, &set(set_text), &RenderOptions::once(w, h, 0, 1))
            .unwrap_or_else(|e| panic!("{set_text}: {e}"));
        let (mut lit, mut shadowed, mut through, mut stopped) = (0, 0, 0, 0);
        let mut wrong = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                let ray =
                    twinray_shared::camera::primary_ray(&frame, UVec2::new(x, y), UVec2::new(w, h), Vec2::splat(0.5));
                // Where the camera's ray crosses the cutouts' plane, and then the floor.
                let at_cutouts = ray.origin + ray.direction * ((1.0 - ray.origin.y) / ray.direction.y);
                let on_floor = ray.origin + ray.direction * (-ray.origin.y / ray.direction.y);
                let object = (out.hit_ids[i] >> 32) as u32;
                match covered(at_cutouts) {
                    None => continue,
                    Some(true) => {
                        stopped += 1;
                        if object == FLOOR {
                            wrong
                                .push(format!("pixel ({x}, {y}): the camera saw through solid cutout at {at_cutouts}"));
                        }
                        continue;
                    }
                    Some(false) => {
                        through += 1;
                        if object != FLOOR {
                            wrong.push(format!("pixel ({x}, {y}): the camera's ray stopped in a hole at {at_cutouts}"));
                            continue;
                        }
                    }
                }
                // The floor point's shadow ray crosses y = 1 one unit along the light.
                let Some(in_shadow) = covered(on_floor + light / light.y) else { continue };
                let luminance = out.linear[i].iter().sum::<f32>() / 3.0;
                // Lit: 0.8 * cos(light, up) = 0.72; in shadow: nothing (no other light).
                let looks_lit = luminance > 0.36;
                if in_shadow {
                    shadowed += 1;
                } else {
                    lit += 1;
                }
                if looks_lit == in_shadow {
                    wrong.push(format!(
                        "pixel ({x}, {y}) floor {on_floor}: luminance {luminance}, shadow expected {in_shadow}"
                    ));
                }
            }
        }
        eprintln!(
            "{set_text}: {lit} lit, {shadowed} shadowed floor pixels; {through} rays through holes, {stopped} stopped"
        );
        assert!(
            wrong.is_empty(),
            "{set_text}: {} wrong pixels, first: {:#?}",
            wrong.len(),
            &wrong[..wrong.len().min(5)]
        );
        assert!(lit > 2000 && shadowed > 2000 && stopped > 5000, "{set_text}: too few pixels judged");
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}

/// Only cutout objects pay for the any-hit stage: the opaque floor keeps a hit group without
/// one, and a scene without cutouts has no any-hit module at all.
#[test]
fn only_cutouts_get_an_any_hit_stage() {
    let scene = Scene::parse(SCENE, "cutout-test", MeshFiles::Builtin).expect("scene");
    let data = scene.build();
    let names: Vec<String> = data.plan.hit_groups.iter().map(|g| g.name()).collect();
    assert_eq!(names, ["triangles (cutout)", "plane", "plane (cutout)"]);
    let floor = data.instances[0].hit_group as usize;
    assert!(!data.plan.hit_groups[floor].cutout);
    assert!(plan_modules(&data.plan, "raygen").contains(&"cutout_any_hit"));
    // Triangles read their own alpha too: a stage of their own.
    assert!(plan_modules(&data.plan, "raygen").contains(&"triangle_cutout_any_hit"));
    let opaque = SCENE
        .replace("material = \"checker\"", "material = \"floor\"")
        .replace("material = \"discs\"", "material = \"floor\"");
    let plain = Scene::parse(&opaque, "opaque", MeshFiles::Builtin).expect("scene").build();
    assert!(plain.plan.hit_groups.iter().all(|g| g.any_hit_module().is_none()));
    assert!(!plan_modules(&plain.plan, "raygen").contains(&"cutout_any_hit"));
}

/// The probe case of cutouts runs clean in both sets with normals as accurate as without
/// holes: lavapipe hands closest-hit the hit attribute of the last intersection stage run,
/// so without the intersection stages putting back the attribute of a hit a cutout ignored,
/// rays through a sphere's holes got the sphere's normal on the wall behind it (p99 1.4 rad).
#[test]
fn probes_through_holes_keep_their_normals() {
    let path = twinray_tests::repo_root().join("probes/cutout-holes.toml");
    let case = twinray_host::probe::case::ProbeCase::load(&path).expect("case");
    let ctx = validated_context();
    for set_text in ["rust", "glsl", "glsl,any_hit=rust"] {
        let out = twinray_host::probe::probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
        let r = twinray_host::probe::report::evaluate(&case, out.records(), set_text, "test", None);
        eprintln!("{}", r.summary());
        assert_eq!((r.false_hits, r.false_misses, r.wrong_object), (0, 0, 0), "{set_text}");
        assert!(r.decided > 8000, "{set_text}: {} decided", r.decided);
        assert!(r.normal_angle_error_p99 < 1e-3, "{set_text}: normal p99 {}", r.normal_angle_error_p99);
    }
}
