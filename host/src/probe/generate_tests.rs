//! Tests of the ray generators, through probe case files as users write them.

use super::case::ProbeCase;
use glam::DVec3;

/// A case with one object of `shape` (a TOML table body) and the generator `generator`.
fn case(shape: &str, transform: &str, generator: &str) -> Result<ProbeCase, String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.toml");
    let text = format!(
        "name = \"t\"\n[scene.materials.m]\nkind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\n\
         [scene.shapes.s]\n{shape}\n[[scene.objects]]\nshape = \"s\"\nmaterial = \"m\"\n{transform}\n\
         [[generators]]\n{generator}\n"
    );
    std::fs::write(&path, text).unwrap();
    ProbeCase::load(&path).map_err(|e| e.to_string())
}

/// Each ray's origin and direction in the object's space.
fn object_rays(case: &ProbeCase) -> Vec<(DVec3, DVec3)> {
    let to_object = case.reference.objects[0].world_to_object;
    let rays = case.rays.iter();
    rays.map(|r| {
        let (o, d) = (r.origin.truncate().as_dvec3(), r.direction.truncate().as_dvec3());
        (to_object.transform_point3(o), to_object.transform_vector3(d))
    })
    .collect()
}

#[test]
fn face_plane_rays_lie_in_and_beside_the_faces_of_a_rotated_box() {
    let shape = "kind = \"box\"\nsize = [2.0, 4.0, 6.0]";
    let generator = "kind = \"face_plane\"\nobject = 0\ncount = 300\noffset = 1e-3";
    let case = case(shape, "translate = [5.0, 0.0, 0.0]\nrotate = [0.0, 30.0, 0.0]", generator).unwrap();
    let (half, size) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(1.0, 2.0, 3.0).length());
    for (k, (o, d)) in object_rays(&case).into_iter().enumerate() {
        // Parallel to one face: its axis has (nearly) no direction component.
        let axis = (0..3).min_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs())).unwrap();
        assert!(d[axis].abs() < 1e-6, "ray {k} is not parallel to a face: {d}");
        let beside = o[axis].abs() - half[axis];
        let expected = [0.0, 1.0, 1.0][k % 3] * 1e-3 * size;
        assert!((beside.abs() - expected).abs() < 1e-5, "ray {k}: {beside} from the face plane");
    }
}

#[test]
fn grazing_rays_arrive_within_the_angle_from_afar() {
    let generator = "kind = \"grazing\"\nobject = 0\ncount = 200\ndistance = 100.0\nangle = 2.0";
    let case = case("kind = \"sphere\"\nradius = 1.0", "", generator).unwrap();
    assert_eq!(case.rays.len(), 200);
    for (k, (o, d)) in object_rays(&case).into_iter().enumerate() {
        assert!((o.length() - 100.0).abs() < 2.0, "ray {k} starts {} away", o.length());
        // Closest approach to the centre: within the radius for aimed rays (arriving at
        // less than 2 degrees, so within 1 - cos 2deg of tangency), just above for lifted ones.
        let closest = (o - d * o.dot(d) / d.dot(d)).length();
        let bounds = if k % 2 == 0 { (1.0 - 7e-4, 1.0) } else { (1.0, 1.0 + 2.2e-3) };
        assert!(closest > bounds.0 - 1e-5 && closest < bounds.1 + 1e-5, "ray {k} passes {closest} from the centre");
    }
}

#[test]
fn face_plane_needs_flat_faces_and_an_existing_object() {
    let generator = "kind = \"face_plane\"\nobject = 0\ncount = 3";
    let err = case("kind = \"sphere\"\nradius = 1.0", "", generator).err().unwrap();
    assert!(err.contains("generators[0]: object 0 has no flat faces"), "{err}");
    let generator = "kind = \"grazing\"\nobject = 2\ncount = 3\ndistance = 10.0";
    let err = case("kind = \"sphere\"\nradius = 1.0", "", generator).err().unwrap();
    assert!(err.contains("no object 2 (the scene has 1)"), "{err}");
}

/// How many of the case's rays the reference says hit.
fn reference_hits(case: &ProbeCase) -> usize {
    let verdicts = case.rays.iter().map(|r| {
        let (o, d) = (r.origin.truncate().as_dvec3(), r.direction.truncate().as_dvec3());
        case.reference.trace(o, d, f64::from(r.origin.w), f64::from(r.direction.w))
    });
    verdicts.filter(|v| matches!(v, crate::reference::scene::SceneVerdict::Hit { .. })).count()
}

#[test]
fn surface_makes_every_ray_asked_for_on_thin_and_stretched_objects() {
    let cases = [
        ("kind = \"cylinder\"\nradius = 1e-3\nheight = 1e3", "", 400),
        ("kind = \"sphere\"\nradius = 1.0", "scale = [1e-3, 1.0, 1e3]\nrotate = [30.0, 40.0, 50.0]", 500),
        ("kind = \"torus\"\nmajor_radius = 1.0\nminor_radius = 1e-3", "translate = [0.0, 0.0, 1e3]", 600),
        ("kind = \"cone\"\nradius = 1e-3\nheight = 100.0", "", 300),
        ("kind = \"box\"\nsize = [1e-3, 1e3, 1.0]", "rotate = [10.0, 0.0, 80.0]", 300),
    ];
    for (shape, transform, count) in cases {
        let generator = format!("kind = \"surface\"\nobject = 0\ncount = {count}\nseed = 3");
        let made = case(shape, transform, &generator).unwrap_or_else(|e| panic!("{shape}: {e}"));
        assert_eq!(made.rays.len(), count, "{shape}");
        assert_eq!(made.generated[0].made, count, "{shape}");
        let grazing = format!("kind = \"grazing\"\nobject = 0\ncount = {count}\ndistance = 100.0");
        assert_eq!(case(shape, transform, &grazing).unwrap().rays.len(), count, "{shape}");
    }
}

#[test]
fn silhouette_grids_cover_elongated_and_scaled_objects() {
    let cases = [
        ("kind = \"cylinder\"\nradius = 1e-2\nheight = 1e2", "rotate = [0.0, 0.0, 45.0]"),
        ("kind = \"sphere\"\nradius = 1.0", "scale = [1e-2, 1.0, 1e2]\nrotate = [0.0, 30.0, 0.0]"),
        ("kind = \"box\"\nsize = [1e3, 1.0, 1.0]", "rotate = [0.0, 0.0, 30.0]"),
    ];
    for (shape, transform) in cases {
        let generator = "kind = \"silhouette\"\nobject = 0\nfrom = [0.0, 0.0, -50.0]\ncount = 32";
        let case = case(shape, transform, generator).unwrap();
        let hits = reference_hits(&case);
        // The grid spans 1.2 times the projection along its longest extent: at least a third
        // of the rays cross the object (a grid by bounding radius hits a few percent).
        assert!(hits * 3 >= case.rays.len(), "{shape} {transform}: {hits} of {} rays hit", case.rays.len());
    }
}

#[test]
fn generators_refuse_counts_they_cannot_make() {
    let sphere = "kind = \"sphere\"\nradius = 1.0";
    let err = case(sphere, "", "kind = \"surface\"\nobject = 0\ncount = 0").err().unwrap();
    assert!(err.contains("generators[0]: makes 0 rays; a generator makes 1..="), "{err}");
    let err =
        case(sphere, "", "kind = \"silhouette\"\nobject = 0\nfrom = [0.0, 0.0, 5.0]\ncount = 100000").err().unwrap();
    assert!(err.contains("makes 10000000000 rays"), "{err}");
    let err = case(sphere, "", "kind = \"silhouette\"\nobject = 0\nfrom = [0.0, 0.0, 0.0]\ncount = 4").err().unwrap();
    assert!(err.contains("is the object's centre"), "{err}");
}

/// Rays at the meeting points of a closed mesh's triangles (a rotated icosahedron, and the
/// builtin box, whose faces are split along a diagonal): each lies on an edge or vertex two
/// or more triangles share, arrives from outside across them, and the f64 reference, which
/// calls each triangle alone ambiguous there, decides a hit on the mesh.
#[test]
fn edge_rays_cross_where_triangles_meet_and_the_reference_decides_them() {
    for builtin in ["icosahedron", "box"] {
        let shape = format!("kind = \"mesh\"\nbuiltin = \"{builtin}\"");
        let generator = "kind = \"edges\"\nobject = 0\ncount = 200\nseed = 3";
        let case = case(&shape, "translate = [3.0, 1.0, -2.0]\nrotate = [10.0, 20.0, 30.0]", generator).unwrap();
        assert_eq!(case.rays.len(), 200);
        let mut hits = 0;
        for (k, r) in case.rays.iter().enumerate() {
            let (o, d) = (r.origin.truncate().as_dvec3(), r.direction.truncate().as_dvec3());
            match case.reference.trace(o, d, 0.0, 1e30) {
                crate::reference::scene::SceneVerdict::Hit { object: 0, .. } => hits += 1,
                other => panic!("{builtin}: ray {k} ({o} along {d}): {other:?}"),
            }
        }
        assert_eq!(hits, 200, "{builtin}");
    }
    let err = case("kind = \"sphere\"\nradius = 1.0", "", "kind = \"edges\"\nobject = 0\ncount = 4").err().unwrap();
    assert!(err.contains("generators[0]: object 0 is not a mesh"), "{err}");
}
