//! The probe end to end on lavapipe (validation on): rays across the silhouettes of a sphere
//! and of a torus instance scaled by 2 go through the ordinary pipeline of each shader set,
//! and every ray the f64 reference decides must agree in hit or miss, t and normal.

use glam::{DVec3, Vec4};
use twinray_host::probe::{probe, ProbeRay};
use twinray_host::reference::shapes::{intersect, RefRay, RefShape, Verdict};
use twinray_host::scene::{MeshFiles, Scene};
use twinray_shared::bindings::NO_HIT;
use twinray_tests::{set, validated_context, SCENE_HEAD};

/// After `SCENE_HEAD`: a sphere and a torus instance scaled by 2.
const SHAPES: &str = r#"
[shapes.ball]
kind = "sphere"
radius = 1.0
[shapes.ring]
kind = "torus"
major_radius = 1.0
minor_radius = 0.25
[[objects]]
shape = "ball"
material = "m"
[[objects]]
shape = "ring"
material = "m"
translate = [6.0, 0.0, 0.0]
rotate = [90.0, 0.0, 0.0]
scale = 2.0
[parity]
max_rmse = 0.01
pixel_threshold = 2
max_pixels_over_threshold = 0.002
max_hit_mismatches = 0.002
"#;

/// Rays from z = -20 towards +z across [x0 - w, x0 + w] x [-w, w].
fn grid(x0: f32, w: f32, n: u32) -> Vec<ProbeRay> {
    let mut rays = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let x = x0 - w + 2.0 * w * (i as f32 + 0.5) / n as f32;
            let y = -w + 2.0 * w * (j as f32 + 0.5) / n as f32;
            rays.push(ProbeRay { origin: Vec4::new(x, y, -20.0, 0.0), direction: Vec4::new(0.0, 0.0, 1.0, 100.0) });
        }
    }
    rays
}

#[test]
fn probe_agrees_with_the_f64_reference_in_both_sets() {
    let text = format!("name = \"probe-test\"\n{SCENE_HEAD}{SHAPES}");
    let scene = Scene::parse(&text, "probe-test", MeshFiles::Folder(".".into())).expect("scene");
    let ctx = validated_context();
    let sphere_rays = grid(0.0, 1.2, 40);
    let torus_rays = grid(6.0, 3.0, 40);
    let rays: Vec<ProbeRay> = sphere_rays.iter().chain(&torus_rays).copied().collect();
    // Object 1 is the torus, rotated 90 degrees about x (its axis along z) and scaled by 2.
    let to_torus = |p: DVec3| DVec3::new((p.x - 6.0) / 2.0, p.z / 2.0, -p.y / 2.0);
    for set_text in ["rust", "glsl"] {
        let out = probe(&ctx, &scene, &set(set_text), &rays, 0, 1).expect("probe");
        let (mut decided, mut hits) = (0, 0);
        for (k, (ray, result)) in rays.iter().zip(&out.results).enumerate() {
            let o = ray.origin.truncate().as_dvec3();
            let d = ray.direction.truncate().as_dvec3();
            let torus = k >= sphere_rays.len();
            let (shape, local) = if torus {
                let origin = to_torus(o);
                let direction = to_torus(o + d) - origin;
                (
                    RefShape::Torus { major: 1.0, minor: 0.25 },
                    RefRay { origin, direction, t_min: 0.0, t_max: 100.0, noise_floor: 0.0 },
                )
            } else {
                (
                    RefShape::Sphere { center: DVec3::ZERO, radius: 1.0 },
                    RefRay { origin: o, direction: d, t_min: 0.0, t_max: 100.0, noise_floor: 0.0 },
                )
            };
            let got_hit = result.ids.w != NO_HIT;
            match intersect(&shape, &local) {
                Verdict::Ambiguous => continue,
                Verdict::Miss => assert!(!got_hit, "{set_text}: false hit on ray {k} {ray:?}"),
                Verdict::Hit { t, .. } => {
                    assert!(got_hit, "{set_text}: false miss on ray {k} {ray:?} (true t {t})");
                    let rel = (f64::from(result.normal_t.w) - t).abs() / t;
                    assert!(rel < 1e-5, "{set_text}: ray {k}: t {} vs {t} (relative {rel:.2e})", result.normal_t.w);
                    assert_eq!(result.ids.x, u32::from(torus), "{set_text}: ray {k} hit the wrong object");
                    let n = result.normal_t.truncate();
                    assert!(
                        (n.length() - 1.0).abs() < 1e-4 && n.z < 0.0,
                        "{set_text}: ray {k}: normal {n} should face the ray"
                    );
                    hits += 1;
                }
            }
            decided += 1;
        }
        assert!(decided > 3000 && hits > 1000, "{set_text}: only {decided} decided rays, {hits} hits");
    }
}

/// Every case that ships in probes/, and the example of docs/probe-format.md (a case file
/// written by someone else, in the documented format), run in both sets with no false hit,
/// false miss or wrong object.
#[test]
fn shipped_and_documented_probe_cases_run_clean_in_both_sets() {
    twinray_tests::allow_installed_models();
    let root = twinray_tests::repo_root();
    let doc = std::fs::read_to_string(root.join("docs/probe-format.md")).expect("docs/probe-format.md");
    let start = doc.find("```toml\n").expect("an example") + "```toml\n".len();
    let end = start + doc[start..].find("```").expect("the example's end");
    let dir = tempfile::tempdir().unwrap();
    let example = dir.path().join("example.toml");
    std::fs::write(&example, &doc[start..end]).unwrap();
    let mut cases = twinray_host::probe::stability::case_files(&root.join("probes")).expect("probe cases");
    cases.push(example);
    let ctx = validated_context();
    for path in cases {
        let case =
            twinray_host::probe::case::ProbeCase::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for set_text in ["rust", "glsl"] {
            let out = probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
            let r = twinray_host::probe::report::evaluate(&case, out.records(), set_text, "test", None);
            eprintln!("{}", r.summary());
            assert_eq!((r.false_hits, r.false_misses, r.wrong_object), (0, 0, 0), "{} with {set_text}", path.display());
            assert!(r.decided > 0, "{}: nothing decided", path.display());
            // Rays gone through a first surface: none, but for the watertight case, where
            // lavapipe's triangle test lets a few of its 8000 rays through between triangles,
            // a different number each run (docs/probe-format.md): over 120 runs (60 per set)
            // 1 to 6, mean 2.4, variance 1.0. The bound was 4 until a CI run met 5. Counted
            // as Poisson with that mean (the spread is narrower than Poisson's, so this is
            // cautious), more than 10 comes once in 25,000 runs. A leak of twinray's own
            // beyond that bound (0.125% of the rays) still fails.
            let allowed = if path.ends_with("mesh-edges.toml") { 10 } else { 0 };
            assert!(r.through <= allowed, "{} with {set_text}: {} rays went through", path.display(), r.through);
        }
    }
}

/// The textbook variants kept on purpose fail where docs/numerics.md says they do, in both sets,
/// while the robust forms do not: the sphere 1e4 away gets false hits and a relative t error
/// above 1e-5 with the naive discriminant.
#[test]
fn naive_sphere_fails_where_the_robust_one_holds() {
    let path = twinray_tests::repo_root().join("probes/far-sphere.toml");
    let ctx = validated_context();
    for set_text in ["rust", "glsl"] {
        let mut case = twinray_host::probe::case::ProbeCase::load(&path).expect("case");
        let robust = probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
        let robust = twinray_host::probe::report::evaluate(&case, robust.records(), set_text, "test", None);
        case.set_formula(twinray_host::scene::shape::Formula::Naive);
        let naive = probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
        let naive = twinray_host::probe::report::evaluate(&case, naive.records(), set_text, "test", None);
        assert_eq!(robust.false_hits + robust.false_misses, 0, "{set_text} robust");
        assert!(robust.relative_t_error.p99 < 1e-6, "{set_text} robust p99 {}", robust.relative_t_error.p99);
        assert!(naive.false_hits + naive.false_misses > 50, "{set_text} naive: {}", naive.summary());
        assert!(naive.relative_t_error.p99 > 1e-5, "{set_text} naive p99 {}", naive.relative_t_error.p99);
        // The witness pass puts the naive formula's error on the stage, where it is. The naive
        // routine keeps the textbook transform (the ray transformed where it starts, 10 units
        // away); the robust one's ray is brought near the sphere first, so its transform is
        // no worse.
        let (robust, naive) = (robust.t_error_by_source.expect("split"), naive.t_error_by_source.expect("split"));
        assert!(naive.stage.p99 > 1e-5 && robust.stage.p99 < 1e-6, "{set_text}: {robust:?} {naive:?}");
        assert_eq!(robust.rays, naive.rays, "{set_text}");
        assert!(robust.transform.p99 <= naive.transform.p99, "{set_text}: {robust:?} {naive:?}");
    }
}

/// An instance far from the origin, seen from close by. The driver's world-to-object transform
/// rounds at the magnitude of 1e4 (lavapipe: relative t error p99 about 4e-4 on the ray it hands
/// a hit group); the intersection stages compute their own object-space ray, the translation
/// taken off first, so the totals stay within f32 noise, and the split still reports what the
/// driver's transform would have cost. Fails if a set's stages read the driver's ray again.
#[test]
fn the_stages_own_transform_keeps_a_far_instance_precise_and_the_drivers_is_reported() {
    let path = twinray_tests::repo_root().join("probes/far-instances.toml");
    let case = twinray_host::probe::case::ProbeCase::load(&path).expect("case");
    let ctx = validated_context();
    let mut witnesses = Vec::new();
    for set_text in ["rust", "glsl"] {
        let out = probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
        witnesses.push(out.witness.clone().expect("a witness pass"));
        let r = twinray_host::probe::report::evaluate(&case, out.records(), set_text, "test", None);
        let split = r.t_error_by_source.clone().expect("a witness pass");
        let agreed = r.decided - r.false_hits - r.false_misses - r.wrong_object;
        let hits = out.results.iter().filter(|h| h.ids.w != NO_HIT).count();
        assert_eq!(split.unrepeated, 0, "{set_text}: the witness pass repeats the probe's answers");
        assert!(split.rays * 100 >= hits.min(agreed) * 95, "{set_text}: {} of {hits} hits judged", split.rays);
        assert!(split.stage.p99 < 1e-6, "{set_text}: {}", split.summary());
        // The totals: what a user sees, with no ray wrong.
        let total = r.relative_t_error.p99;
        assert!(total < 1e-6, "{set_text}: total p99 {total}, {}", split.summary());
        assert_eq!(r.false_hits + r.false_misses + r.wrong_object + r.through, 0, "{set_text}");
        assert!(total <= split.stage.max + split.transform.max + 1e-12, "{set_text}: {total} vs {split:?}");
        // The case is hard for the driver's transform, and the split says so.
        let driver = split.driver.expect("the driver's witness pass");
        assert!(driver.p99 > 1e-5, "{set_text}: the driver's transform gave only {:e}", driver.p99);
    }
    // The host chose the stages' transform for this scene: its instances are far for their size.
    let features = case.scene.build().plan.features;
    assert_ne!(features & twinray_shared::features::FAR_INSTANCES, 0, "far-instances not set: {features:#b}");
    // The twins' witnesses hand back the same object-space rays, from the same place along the
    // world ray, bit for bit: one formula in both languages (twinray_shared::transform and
    // transform.glsl).
    let ray = |r: &twinray_host::probe::ProbeResult| {
        twinray_host::probe::split::witness(r).map(|w| (w.origin, w.direction, w.shift.to_bits()))
    };
    let (rust, glsl) = (&witnesses[0], &witnesses[1]);
    let same = rust.iter().zip(glsl).filter(|(r, g)| ray(r) == ray(g)).count();
    assert_eq!(same, rust.len(), "rays whose witnessed object-space ray (or miss) differs between the twins");
    assert!(rust.iter().filter_map(ray).count() > 1000, "the witness saw the hits");
}

/// A shape at the world origin grazed from 1,000 units: nothing stands far from the GPU's
/// origin, but the rays start 100 of the shape's sizes away, so the probe judges the scene to
/// have far instances from where its rays start (`reach::far_from`), while a render of the same
/// scene, from its camera, does not. Fails if the probe judges by the objects' places alone
/// (the driver's transform, about 2e-6 here on lavapipe, would be the stages').
#[test]
fn a_probe_judges_far_instances_from_where_its_rays_start() {
    for (set_text, total, _, driver) in near_rays("cylinder-at-origin-grazing-1e3") {
        assert!(driver > 1e-6, "{set_text}: the driver's transform gave only {driver:e}: the case is not hard");
        assert!(total < 1e-6, "{set_text}: relative t error p99 {total:e}");
    }
}

/// A torus 1,000 units across grazed from 2,000 units: its rays start 4 of its bounds away,
/// where the stages once transformed them where they started (they were brought near only from
/// 16 bounds), and its relative t error p99 was 1.4e-5 on the H200. Now every ray that starts
/// farther than 3 of its primitive's bounds is brought onto twice the bound
/// (`transform::FAR_BOUNDS`), and the probe turns the stages' own transform on for rays that
/// start that many of an object's sizes away (`reach::START_FACTOR`). Fails if either rule goes
/// back to 16: the transform's part is then the driver's (on lavapipe 1.1e-5) or the stages'
/// plain one (8.7e-6), not at most 0.6 of the driver's (0.4 to 0.5 measured: moving from 4
/// bounds to 2 can win at most 2).
#[test]
fn a_ray_a_few_bounds_away_is_brought_near() {
    for (set_text, total, transform, driver) in near_rays("torus-wide-turned") {
        assert!(
            transform <= 0.6 * driver,
            "{set_text}: transform's part {transform:e} against the driver's {driver:e}"
        );
        assert!(total < 1e-5, "{set_text}: relative t error p99 {total:e}");
    }
}

/// Probes the stability case `name` in both sets and checks what every such case must show:
/// the far-instances feature on although a render of it would not have it, no ray wrong.
/// Returns, per set, the relative t error p99 in all, of the stages' transform and of the
/// driver's transform.
fn near_rays(name: &str) -> Vec<(&'static str, f64, f64, f64)> {
    let path = twinray_tests::repo_root().join(format!("probes/stability/{name}.toml"));
    let case = twinray_host::probe::case::ProbeCase::load(&path).expect("case");
    assert_eq!(case.scene.build().plan.features & twinray_shared::features::FAR_INSTANCES, 0, "a render's rule");
    let ctx = validated_context();
    ["rust", "glsl"]
        .into_iter()
        .map(|set_text| {
            let out = probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
            let r = twinray_host::probe::report::evaluate(&case, out.records(), set_text, "test", None);
            assert!(r.features.contains("far-instances"), "{set_text}: {}", r.summary());
            assert_eq!(r.false_hits + r.false_misses + r.wrong_object + r.through, 0, "{set_text}: {}", r.summary());
            let split = r.t_error_by_source.clone().expect("a witness pass");
            let driver = split.driver.expect("the driver's witness").p99;
            (set_text, r.relative_t_error.p99, split.transform.p99, driver)
        })
        .collect()
}

/// The switch works in both sets: the same far case with its `features` forced to none takes
/// the driver's object-space ray, and its totals show the driver's error again (lavapipe: about
/// 4e-4), with no ray wrong.
#[test]
fn without_far_instances_the_stages_take_the_drivers_ray() {
    let text = std::fs::read_to_string(twinray_tests::repo_root().join("probes/far-instances.toml")).unwrap();
    let text = text.replacen("[scene]\n", "[scene]\nfeatures = []\n", 1);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("far-driver.toml");
    std::fs::write(&path, text).unwrap();
    let case = twinray_host::probe::case::ProbeCase::load(&path).expect("case");
    assert_eq!(case.scene.build().plan.features, 0);
    let ctx = validated_context();
    for set_text in ["rust", "glsl"] {
        let out = probe(&ctx, &case.scene, &set(set_text), &case.rays, 0, 1).expect("probe");
        let r = twinray_host::probe::report::evaluate(&case, out.records(), set_text, "test", None);
        let split = r.t_error_by_source.clone().expect("a witness pass");
        let driver = split.driver.expect("the driver's witness").p99;
        assert_eq!((r.false_hits, r.false_misses, r.wrong_object), (0, 0, 0), "{set_text}");
        // The stages used the driver's ray, so their transform is the driver's.
        assert_eq!(split.transform.p99, driver, "{set_text}: {}", split.summary());
        assert!(r.relative_t_error.p99 > 1e-5, "{set_text}: {}", r.summary());
    }
}

/// A folder of modules built before the witness existed still probes, with the same answers,
/// and says the split is not available rather than failing.
#[test]
fn a_folder_set_without_the_witness_probes_without_the_split() {
    let root = twinray_tests::repo_root();
    let case = twinray_host::probe::case::ProbeCase::load(&root.join("probes/far-instances.toml")).expect("case");
    let dir = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(root.join("spirv/rust")).unwrap() {
        let path = entry.unwrap().path();
        if path.file_stem().is_some_and(|s| s != "probe_witness") {
            std::fs::copy(&path, dir.path().join(path.file_name().unwrap())).unwrap();
        }
    }
    let ctx = validated_context();
    let with = probe(&ctx, &case.scene, &set("rust"), &case.rays, 0, 1).expect("probe");
    let without = probe(&ctx, &case.scene, &set(dir.path().to_str().unwrap()), &case.rays, 0, 1).expect("probe");
    assert!(with.witness.is_some() && without.witness.is_none());
    // A miss's t and normal are whatever the payload held: compare hits, and which rays hit.
    let answers = |out: &twinray_host::probe::ProbeOutput| -> Vec<_> {
        out.results.iter().map(|r| (r.ids, if r.ids.w == NO_HIT { Vec4::ZERO } else { r.normal_t })).collect()
    };
    assert_eq!(answers(&with), answers(&without));
    let r = twinray_host::probe::report::evaluate(&case, without.records(), "old", "test", None);
    assert!(r.t_error_by_source.is_none() && r.summary().contains("by source: n/a"), "{}", r.summary());
    // A folder from before the driver's witness: the split, without the driver's figure.
    let older = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(root.join("spirv/rust")).unwrap() {
        let path = entry.unwrap().path();
        if path.file_stem().is_some_and(|s| s != "probe_witness_driver") {
            std::fs::copy(&path, older.path().join(path.file_name().unwrap())).unwrap();
        }
    }
    let out = probe(&ctx, &case.scene, &set(older.path().to_str().unwrap()), &case.rays, 0, 1).expect("probe");
    assert!(out.witness.is_some() && out.driver_witness.is_none());
    let r = twinray_host::probe::report::evaluate(&case, out.records(), "older", "test", None);
    let split = r.t_error_by_source.expect("the stages' witness");
    assert!(split.driver.is_none() && !split.summary().contains("driver"), "{}", split.summary());
}

/// Five turned shapes near the origin, and the same scene (camera, light and objects) moved by
/// `offset`, the GPU centred as `gpu_origin` says.
fn shapes_at(offset: [f64; 3], gpu_origin: &str) -> Scene {
    let at = |p: [f64; 3]| format!("[{:.1}, {:.1}, {:.1}]", p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]);
    let mut text = format!(
        "gpu_origin = \"{gpu_origin}\"\n[image]\nwidth = 96\nheight = 72\n\
         [camera]\neye = {}\ntarget = {}\nup = [0.0, 1.0, 0.0]\nfov_y_degrees = 40.0\n\
         [materials.m]\nkind = \"diffuse\"\ncolor = [0.8, 0.8, 0.8]\n\
         [[lights]]\nkind = \"point\"\nposition = {}\ncolor = [1.0, 1.0, 1.0]\nintensity = 20.0\n\
         [shapes.ball]\nkind = \"sphere\"\nradius = 0.8\n\
         [shapes.can]\nkind = \"cylinder\"\nradius = 0.6\nheight = 1.5\n\
         [shapes.slab]\nkind = \"box\"\nsize = [1.4, 0.5, 1.0]\n\
         [shapes.cone]\nkind = \"cone\"\nradius = 0.7\nheight = 1.4\n\
         [shapes.ring]\nkind = \"torus\"\nmajor_radius = 0.7\nminor_radius = 0.2\n",
        at([0.0, 1.5, 8.0]),
        at([0.0, 0.0, 0.0]),
        at([-3.0, 5.0, 4.0])
    );
    let placed = [
        ("ball", [-2.4, 0.0, 0.0], [0.0, 0.0, 0.0]),
        ("can", [-1.2, 0.0, -0.5], [35.0, 20.0, 50.0]),
        ("slab", [0.0, 0.0, 0.3], [10.0, 40.0, 25.0]),
        ("cone", [1.2, 0.0, -0.5], [60.0, 0.0, 30.0]),
        ("ring", [2.4, 0.0, 0.0], [70.0, 15.0, 0.0]),
    ];
    for (shape, p, r) in placed {
        text += &format!(
            "[[objects]]\nshape = \"{shape}\"\nmaterial = \"m\"\ntranslate = {}\nrotate = [{:.1}, {:.1}, {:.1}]\n",
            at(p),
            r[0],
            r[1],
            r[2]
        );
    }
    Scene::parse(&text, "far-scene.toml", MeshFiles::Builtin).expect("scene")
}

/// A scene moved 1.7e4 from the origin renders the same hit ids as at the origin, in both sets,
/// but where a pixel's ray passes within f32 rounding of a silhouette: every pixel that differs
/// has a 4-neighbour of another id in the render at the origin (the band where the camera's
/// own position, rounded to f32 at 1e4, may move an edge by a fraction of a pixel). Both ways
/// of working far out: centred on the camera (the default), and at world coordinates with the
/// stages' own transform.
#[test]
fn a_scene_far_from_the_origin_hits_what_it_hits_at_the_origin() {
    let near = shapes_at([0.0; 3], "local");
    assert_eq!(near.origin, None, "a scene near the world origin is not moved");
    let far = [10000.0, -10000.0, 10000.0];
    let (local, world) = (shapes_at(far, "local"), shapes_at(far, "world"));
    // Centred on its camera, the scene's objects are near for their size; at world coordinates
    // they are far, and the stages compute their own object-space ray.
    assert_eq!(local.origin, Some(glam::Vec3::from(local.file.camera.eye)));
    assert_eq!(local.build().plan.features & twinray_shared::features::FAR_INSTANCES, 0);
    assert_ne!(world.build().plan.features & twinray_shared::features::FAR_INSTANCES, 0);
    let ctx = validated_context();
    for (set_text, far) in [("rust", &local), ("glsl", &local), ("rust", &world), ("glsl", &world)] {
        let label = format!("{set_text} ({:?})", far.file.gpu_origin);
        let a = twinray_tests::render(&ctx, &near, set_text);
        let b = twinray_tests::render(&ctx, far, set_text);
        let (w, h) = (a.width as usize, a.height as usize);
        let id = |x: usize, y: usize| a.hit_ids[y * w + x];
        let edge = |x: usize, y: usize| {
            let n = [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)];
            n.iter().any(|&(nx, ny)| nx < w && ny < h && id(nx, ny) != id(x, y))
        };
        let hits = a.hit_ids.iter().filter(|&&i| i != twinray_host::render::NO_HIT_ID).count();
        assert!(hits > w * h / 10, "{label}: the shapes fill the view ({hits} pixels)");
        let (mut differ, mut off_edge) = (0, Vec::new());
        for (i, (x, y)) in (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).enumerate() {
            if a.hit_ids[i] != b.hit_ids[i] {
                differ += 1;
                if !edge(x, y) {
                    off_edge.push((x, y));
                }
            }
        }
        eprintln!("{label}: {differ} of {} pixels differ, all on edges: {}", w * h, off_edge.is_empty());
        assert!(off_edge.is_empty(), "{label}: pixels away from any edge hit something else: {off_edge:?}");
    }
}
