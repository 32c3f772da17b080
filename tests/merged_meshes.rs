//! Meshes that share a BLAS, on lavapipe with validation on: a glTF mesh of four primitives,
//! each a quad of a material of its own, placed by two nodes, is one BLAS of four geometries
//! traced as two instances (`scene::merge`); every quad's hit names its own object in both sets,
//! through the pipeline's stages and through ray queries, as the f64 reference does, and every
//! quad shows its own material's colour.

use glam::Vec4;
use twinray_host::probe::{probe, ProbeRay};
use twinray_host::reference::scene::{SceneReference, SceneVerdict};
use twinray_host::render::NO_HIT_ID;
use twinray_host::scene::{Renderer, Scene};
use twinray_tests::gltf::strip;
use twinray_tests::{render_scene, set, validated_context};

const COLORS: [[f32; 3]; 4] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
const NODES: [[f32; 3]; 2] = [[0.0, 0.0, 0.0], [0.0, 1.5, 0.0]];

fn model(dir: &std::path::Path) -> Scene {
    let path = strip(dir, &COLORS, &NODES);
    Scene::load(Some(path.to_str().unwrap())).expect("the model")
}

/// A ray down -z through the middle of each quad of each node, node by node.
fn rays() -> Vec<ProbeRay> {
    let through = |node: [f32; 3], p: usize| {
        let origin = Vec4::new(node[0] + 1.2 * p as f32 + 0.5, node[1] + 0.5, 5.0, 0.0);
        ProbeRay { origin, direction: Vec4::new(0.0, 0.0, -1.0, 100.0) }
    };
    NODES.iter().flat_map(|&n| (0..COLORS.len()).map(move |p| through(n, p))).collect()
}

#[test]
fn each_primitive_of_a_shared_blas_is_hit_as_its_own_object() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let mut scene = model(dir.path());
    assert_eq!(scene.file.objects.len(), COLORS.len() * NODES.len());
    let rays = rays();
    let reference = SceneReference::new(&scene).expect("reference");
    let expected: Vec<usize> = rays
        .iter()
        .map(|r| match reference.trace(r.origin.truncate().as_dvec3(), r.direction.truncate().as_dvec3(), 0.0, 100.0) {
            SceneVerdict::Hit { object, t, .. } if (t - 5.0).abs() < 1e-9 => object,
            other => panic!("the reference says {other:?} for {r:?}"),
        })
        .collect();
    let mut distinct = expected.clone();
    distinct.sort();
    distinct.dedup();
    assert_eq!(distinct.len(), rays.len(), "the reference's objects {expected:?}");
    for renderer in [Renderer::Pipeline, Renderer::Compute] {
        scene.file.renderer = renderer;
        for set_text in ["rust", "glsl"] {
            let out = probe(&ctx, &scene, &set(set_text), &rays, 0, 1).expect("probe");
            let objects: Vec<usize> = out.results.iter().map(|r| r.ids.x as usize).collect();
            assert_eq!(objects, expected, "{set_text}, {renderer:?}: the objects hit");
        }
    }
}

#[test]
fn a_shared_blas_shows_each_primitive_in_its_own_colour_in_both_sets() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let scene = model(dir.path());
    let objects = scene.file.objects.len();
    let rust = render_scene(&ctx, &scene, "rust");
    let glsl = render_scene(&ctx, &scene, "glsl");
    assert_eq!((rust.accel.blases, rust.accel.instances), (1, NODES.len()), "{}", rust.accel);
    let differing = rust.hit_ids.iter().zip(&glsl.hit_ids).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "pixels whose hit ids differ between the sets");
    // Every object is seen, and the mean colour of its pixels leans to its material's.
    for out in [&rust, &glsl] {
        let mut sums = vec![([0.0f64; 3], 0u32); objects];
        for (id, rgb) in out.hit_ids.iter().zip(&out.linear).filter(|(id, _)| **id != NO_HIT_ID) {
            let (sum, n) = &mut sums[(id >> 32) as usize];
            (0..3).for_each(|c| sum[c] += f64::from(rgb[c]));
            *n += 1;
        }
        for (object, (sum, n)) in sums.iter().enumerate() {
            assert!(*n > 20, "object {object} covers {n} pixels");
            let color = COLORS[object % COLORS.len()];
            let (lit, dark) = (0..3).partition::<Vec<_>, _>(|&c| color[c] > 0.5);
            let least_lit = lit.iter().map(|&c| sum[c]).fold(f64::MAX, f64::min);
            let most_dark = dark.iter().map(|&c| sum[c]).fold(0.0, f64::max);
            assert!(least_lit > 4.0 * most_dark, "object {object}: colour sums {sum:?} for material {color:?}");
        }
    }
}
