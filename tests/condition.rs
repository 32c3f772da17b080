//! The condition numbers every probe report carries beside the forward error
//! (`twinray_host::reference::condition`), checked against mpmath's: a handful of rays on turned,
//! scaled and far shapes of every kind the formula treats alike (quadrics, a torus, a box and a
//! mesh's triangle), written to a file that `condition/mpmath_condition.py` reads. There, t is
//! found again at 50 digits and κ by moving each input in turn, with no use of twinray's formula.
//! `cargo xtask setup` installs Debian's python3-mpmath.

use twinray_host::reference::condition::t_condition;
use twinray_host::reference::scene::{RefObject, SceneReference, SceneVerdict};
use twinray_host::reference::shapes::{RefRay, RefShape};
use twinray_host::scene::{MeshFiles, Scene};
use twinray_tests::SCENE_HEAD;

/// After `SCENE_HEAD`: one shape of each kind the check covers.
const SHAPES: &str = r#"
[shapes.ball]
kind = "sphere"
radius = 1.0

[shapes.ring]
kind = "torus"
major_radius = 2.0
minor_radius = 0.5

[shapes.slab]
kind = "box"
size = [2.0, 0.5, 3.0]

[shapes.can]
kind = "cylinder"
radius = 1.0
height = 4.0

[shapes.ico]
kind = "mesh"
builtin = "icosahedron"

[[objects]]
shape = "ball"
material = "m"
translate = [3000.0, -1200.5, 40.25]
rotate = [10.0, 20.0, 30.0]
scale = [3.0, 1.0, 0.5]

[[objects]]
shape = "ring"
material = "m"
translate = [-50.0, 20.0, 10.0]
rotate = [35.0, -10.0, 60.0]

[[objects]]
shape = "slab"
material = "m"
translate = [0.0, 400.0, -250.0]
rotate = [15.0, 40.0, -20.0]
scale = [1.0, 2.0, 0.25]

[[objects]]
shape = "can"
material = "m"
translate = [100.0, 100.0, 100.0]
rotate = [70.0, 0.0, 20.0]
scale = [1.0, 5.0, 0.2]

[[objects]]
shape = "ico"
material = "m"
translate = [-2000.0, 5.0, 3000.0]
rotate = [5.0, 50.0, 5.0]
scale = 2.0
"#;

/// One ray's line of the file: its inputs, the shape it hits and twinray's t and κ.
fn line(
    name: &str,
    (o, d): ([f32; 3], [f32; 3]),
    object: &RefObject,
    shape: &RefShape,
    (t, kappa): (f64, f64),
) -> String {
    let m = object.object_to_world;
    let rows: Vec<f64> = (0..3).flat_map(|r| [m.x_axis[r], m.y_axis[r], m.z_axis[r]]).collect();
    let (kind, params): (&str, Vec<f64>) = match *shape {
        RefShape::Sphere { center, radius } => ("sphere", vec![center.x, center.y, center.z, radius]),
        RefShape::Torus { major, minor } => ("torus", vec![major, minor]),
        RefShape::Box { half } => ("box", half.to_array().to_vec()),
        RefShape::Cylinder { radius, .. } => ("cylinder", vec![radius]),
        RefShape::Triangle { p } => ("triangle", p.iter().flat_map(|v| v.to_array()).collect()),
        ref other => panic!("no implicit function for {other:?}"),
    };
    let list = |v: &[f64]| v.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ");
    let floats = |v: [f32; 3]| list(&v.map(f64::from));
    format!(
        "{{\"name\": \"{name}\", \"origin\": [{}], \"direction\": [{}], \"matrix\": [{}], \"translation\": [{}], \
         \"shape\": {{\"kind\": \"{kind}\", \"params\": [{}]}}, \"t\": {t:?}, \"kappa\": {kappa:?}}}",
        floats(o),
        floats(d),
        list(&rows),
        list(&m.w_axis.truncate().to_array()),
        list(&params)
    )
}

#[test]
fn condition_numbers_agree_with_mpmath() {
    let scene = Scene::parse(&format!("{SCENE_HEAD}{SHAPES}"), "condition.toml", MeshFiles::Builtin).expect("scene");
    let reference = SceneReference::new(&scene).expect("reference");
    let mut lines = Vec::new();
    // From 20 to 200 units away, aimed at points about each object, some nearly grazing it.
    let aims = [
        [0.1f32, 0.2, 0.0],
        [0.6, -0.3, 0.4],
        [0.9, 0.45, -0.2],
        [1.8, 0.1, 0.3],
        [-1.1, 0.9, 0.5],
        [-2.0, 0.1, 0.2],
        [0.2, -1.9, -0.6],
    ];
    for (index, object) in reference.objects.iter().enumerate() {
        let centre = object.object_to_world.w_axis.truncate().as_vec3();
        let mut found = 0;
        for (k, aim) in aims.iter().enumerate() {
            let from = glam::Vec3::new(20.0, 7.5, -13.0) * (1.0 + 4.5 * k as f32);
            let o = centre + from;
            let d = (centre + glam::Vec3::from(*aim) - o).normalize();
            let (od, dd) = (o.as_dvec3(), d.as_dvec3());
            let SceneVerdict::Hit { object: hit, t, normal } = reference.trace(od, dd, 0.0, 1e30) else { continue };
            if hit != index {
                continue;
            }
            let local = RefRay {
                origin: object.world_to_object.transform_point3(od),
                direction: object.world_to_object.transform_vector3(dd),
                t_min: 0.0,
                t_max: 1e30,
                noise_floor: 0.0,
            };
            let Some(Some((shape, _, _))) = object.first_shape(&local, twinray_host::reference::scene::Faces::Front)
            else {
                continue;
            };
            let kappa = t_condition(object, od, dd, t, normal);
            let name = format!("object {index} ray {k}");
            lines.push(line(&name, (o.to_array(), d.to_array()), object, &object.shapes[shape], (t, kappa)));
            found += 1;
        }
        assert!(found >= 2, "object {index}: only {found} of the aimed rays hit it");
    }
    let dir = tempfile::tempdir().expect("temp");
    let file = dir.path().join("rays.json");
    std::fs::write(&file, format!("[\n{}\n]\n", lines.join(",\n"))).expect("write");
    let script = twinray_tests::repo_root().join("tests/condition/mpmath_condition.py");
    // Debian's python3, which `cargo xtask setup` gives mpmath, before any other on the path.
    let python =
        ["/usr/bin/python3", "python3"].into_iter().find(|p| !p.starts_with('/') || std::path::Path::new(p).exists());
    let out =
        std::process::Command::new(python.unwrap_or("python3")).arg(&script).arg(&file).output().unwrap_or_else(|e| {
            panic!("python3 did not run ({e}): `cargo xtask setup` installs it with python3-mpmath")
        });
    let text = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    eprintln!("{text}");
    assert!(
        !text.contains("No module named 'mpmath'"),
        "mpmath is missing: `cargo xtask setup` installs python3-mpmath"
    );
    assert!(out.status.success(), "mpmath disagrees:\n{text}");
    assert_eq!(text.matches("kappa").count(), lines.len(), "every ray checked:\n{text}");
}
