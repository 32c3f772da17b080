//! Shared BLASes against one BLAS per mesh, on random glTF models (lavapipe, validation on).
//! A model is a few meshes of a few primitives, each primitive random triangles of a material
//! of its own (a random colour; double-sided or not; alpha-tested by its vertex colours' alpha
//! or not), placed by nodes of random translation, rotation and scale, mirrored among them,
//! two nodes sometimes placing the same mesh. Rendered with consecutive primitives placed alike
//! sharing one structure (`scene::merge`, the default) and with every primitive alone
//! (`Context::share_blases(false)`), the image and the hit ids are the same bit for bit,
//! through the pipeline's stages and through ray queries, with either set: a structure's
//! content changes the order of traversal, never what a ray hits or how its hit is shaded.
//! The counts follow the rule: a mesh's primitives share a structure while their facing and
//! alpha mode stay alike, and each mesh's structures are built once, whichever nodes place it.

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use twinray_host::scene::Renderer;
use twinray_host::{Context, ContextOptions, RenderOptions, RenderOutput, Scene, Validation};
use twinray_tests::set;

#[derive(Clone, Debug)]
struct Primitive {
    /// Each triangle's corners and each corner's alpha.
    triangles: Vec<([[f32; 3]; 3], [f32; 3])>,
    color: [f32; 3],
    double_sided: bool,
    /// Alpha-tested at 0.5 (glTF's MASK), its alpha its vertex colours'.
    masked: bool,
}

#[derive(Clone, Debug)]
struct Node {
    mesh: prop::sample::Index,
    translation: [f32; 3],
    /// A unit quaternion, x, y, z, w.
    rotation: [f32; 4],
    scale: [f32; 3],
}

#[derive(Clone, Debug)]
struct Model {
    meshes: Vec<Vec<Primitive>>,
    nodes: Vec<Node>,
    renderer: Renderer,
    set: &'static str,
}

fn primitive() -> impl Strategy<Value = Primitive> {
    let corner = [-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0];
    let triangle = ([corner.clone(), corner.clone(), corner], [0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0]);
    (
        prop::collection::vec(triangle, 1..5),
        [0.1f32..1.0, 0.1f32..1.0, 0.1f32..1.0],
        prop::bool::weighted(6.0 / 7.0),
        prop::bool::weighted(1.0 / 7.0),
    )
        .prop_map(|(triangles, color, double_sided, masked)| Primitive { triangles, color, double_sided, masked })
}

fn node() -> impl Strategy<Value = Node> {
    let scale = (0.5f32..1.5, prop::bool::weighted(0.2)).prop_map(|(s, mirrored)| if mirrored { -s } else { s });
    let axis = [-1.0f32..1.0, -1.0f32..1.0, 0.2f32..1.0];
    (
        any::<prop::sample::Index>(),
        [-1.5f32..1.5, -1.5f32..1.5, -1.5f32..1.5],
        axis,
        -3.0f32..3.0,
        [scale.clone(), scale.clone(), scale],
    )
        .prop_map(|(mesh, translation, axis, angle, scale)| {
            let axis = glam::Vec3::from(axis).normalize();
            Node { mesh, translation, rotation: glam::Quat::from_axis_angle(axis, angle).to_array(), scale }
        })
}

fn model() -> impl Strategy<Value = Model> {
    let meshes = prop::collection::vec(prop::collection::vec(primitive(), 1..6), 1..4);
    (meshes, prop::collection::vec(node(), 1..4), prop_oneof![Just("rust"), Just("glsl")])
        .prop_map(|(meshes, nodes, set)| Model { meshes, nodes, renderer: Renderer::Pipeline, set })
}

impl Model {
    fn mesh_of(&self, node: &Node) -> usize {
        node.mesh.index(self.meshes.len())
    }

    /// The meshes some node places, each once.
    fn placed(&self) -> Vec<usize> {
        let mut used: Vec<usize> = self.nodes.iter().map(|n| self.mesh_of(n)).collect();
        used.sort();
        used.dedup();
        used
    }

    /// Structures with sharing: a mesh's runs of consecutive primitives of one facing and alpha
    /// mode, each mesh's once.
    fn shared_blases(&self) -> usize {
        let runs = |mesh: &[Primitive]| {
            1 + mesh.windows(2).filter(|w| (w[0].double_sided, w[0].masked) != (w[1].double_sided, w[1].masked)).count()
        };
        self.placed().iter().map(|&m| runs(&self.meshes[m])).sum()
    }

    /// Writes `model.gltf` and `model.bin` into `dir`; the file's path.
    fn write(&self, dir: &Path) -> PathBuf {
        let (mut bytes, mut views, mut accessors) = (Vec::<u8>::new(), Vec::new(), Vec::new());
        let mut view = |bytes: &mut Vec<u8>, data: Vec<u8>| {
            views.push(format!(r#"{{"buffer": 0, "byteOffset": {}, "byteLength": {}}}"#, bytes.len(), data.len()));
            bytes.extend(data);
            views.len() - 1
        };
        let (mut materials, mut meshes) = (Vec::new(), Vec::new());
        for mesh in &self.meshes {
            let mut primitives = Vec::new();
            for p in mesh {
                let corners: Vec<[f32; 3]> = p.triangles.iter().flat_map(|(c, _)| *c).collect();
                let count = corners.len();
                let (lo, hi) = corners.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), c| {
                    (std::array::from_fn(|i| lo[i].min(c[i])), std::array::from_fn(|i| hi[i].max(c[i])))
                });
                let v = view(&mut bytes, corners.iter().flatten().flat_map(|x| x.to_le_bytes()).collect());
                accessors.push(format!(
                    r#"{{"bufferView": {v}, "componentType": 5126, "count": {count}, "type": "VEC3", "min": {lo:?}, "max": {hi:?}}}"#
                ));
                let mut attributes = format!(r#""POSITION": {}"#, accessors.len() - 1);
                if p.masked {
                    let colors = p.triangles.iter().flat_map(|(_, a)| a.map(|a| [1.0, 1.0, 1.0, a])).flatten();
                    let v = view(&mut bytes, colors.flat_map(|x: f32| x.to_le_bytes()).collect());
                    accessors.push(format!(
                        r#"{{"bufferView": {v}, "componentType": 5126, "count": {count}, "type": "VEC4"}}"#
                    ));
                    attributes += &format!(r#", "COLOR_0": {}"#, accessors.len() - 1);
                }
                let v = view(&mut bytes, (0..count as u32).flat_map(u32::to_le_bytes).collect());
                accessors.push(format!(
                    r#"{{"bufferView": {v}, "componentType": 5125, "count": {count}, "type": "SCALAR"}}"#
                ));
                let [r, g, b] = p.color;
                let alpha = if p.masked { r#", "alphaMode": "MASK", "alphaCutoff": 0.5"# } else { "" };
                materials.push(format!(
                    r#"{{"doubleSided": {}, "pbrMetallicRoughness": {{"baseColorFactor": [{r}, {g}, {b}, 1]}}{alpha}}}"#,
                    p.double_sided
                ));
                primitives.push(format!(
                    r#"{{"attributes": {{{attributes}}}, "indices": {}, "material": {}}}"#,
                    accessors.len() - 1,
                    materials.len() - 1
                ));
            }
            meshes.push(format!(r#"{{"primitives": [{}]}}"#, primitives.join(", ")));
        }
        let nodes: Vec<String> = self
            .nodes
            .iter()
            .map(|n| {
                format!(
                    r#"{{"mesh": {}, "translation": {:?}, "rotation": {:?}, "scale": {:?}}}"#,
                    self.mesh_of(n),
                    n.translation,
                    n.rotation,
                    n.scale
                )
            })
            .collect();
        std::fs::write(dir.join("model.bin"), &bytes).unwrap();
        let gltf = format!(
            r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {}, "uri": "model.bin"}}],
            "bufferViews": [{}], "accessors": [{}], "materials": [{}], "meshes": [{}],
            "nodes": [{}], "scenes": [{{"nodes": [{}]}}], "scene": 0}}"#,
            bytes.len(),
            views.join(", "),
            accessors.join(", "),
            materials.join(", "),
            meshes.join(", "),
            nodes.join(", "),
            (0..nodes.len()).map(|i| i.to_string()).collect::<Vec<_>>().join(", ")
        );
        let path = dir.join("model.gltf");
        std::fs::write(&path, gltf).unwrap();
        path
    }
}

fn render(ctx: &Arc<Context>, scene: &Scene, set_text: &str) -> RenderOutput {
    twinray_host::render(ctx, scene, &set(set_text), &RenderOptions::once(64, 48, 0, 1)).expect("the render")
}

/// What one case showed: pixels that hit something, and structures saved by sharing.
fn check(model: &Model, ctx: &Arc<Context>) -> Result<(usize, usize), TestCaseError> {
    let dir = tempfile::tempdir().unwrap();
    // A shrunk model may be one the loader refuses (a triangle of no width): not a case.
    let loaded = Scene::load(Some(model.write(dir.path()).to_str().unwrap()));
    let mut scene = loaded.map_err(|e| TestCaseError::reject(e.to_string()))?;
    scene.file.renderer = model.renderer;
    ctx.share_blases(true);
    let shared = render(ctx, &scene, model.set);
    ctx.share_blases(false);
    let alone = render(ctx, &scene, model.set);
    let objects = scene.file.objects.len();
    let primitives: usize = model.placed().iter().map(|&m| model.meshes[m].len()).sum();
    prop_assert_eq!((alone.accel.blases, alone.accel.instances), (primitives, objects));
    prop_assert_eq!(shared.accel.blases, model.shared_blases());
    prop_assert_eq!(shared.accel.triangles, alone.accel.triangles);
    let differing = shared.hit_ids.iter().zip(&alone.hit_ids).filter(|(a, b)| a != b).count();
    prop_assert_eq!(differing, 0, "pixels whose hit ids differ");
    let bits = |out: &RenderOutput| out.linear.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>();
    prop_assert!(bits(&shared) == bits(&alone), "the radiance differs");
    let hit = shared.hit_ids.iter().filter(|&&id| id != twinray_host::render::NO_HIT_ID).count();
    Ok((hit, alone.accel.blases - shared.accel.blases))
}

/// `cases` random models on `renderer`, each checked (a failure panics naming its shrunk
/// model): how many hit something, and how many shared a structure.
fn property(ctx: &Arc<Context>, renderer: Renderer, cases: u32) -> (u32, u32) {
    // Each case renders twice; shrinking renders more.
    let config = ProptestConfig { cases, max_shrink_iters: 64, failure_persistence: None, ..ProptestConfig::default() };
    let mut runner = proptest::test_runner::TestRunner::new(config);
    let seen = std::cell::Cell::new((0, 0));
    let result = runner.run(&model(), |mut model| {
        model.renderer = renderer;
        let (hit, saved) = check(&model, ctx)?;
        let (hits, sharing) = seen.get();
        seen.set((hits + u32::from(hit > 0), sharing + u32::from(saved > 0)));
        Ok(())
    });
    if let Err(e) = result {
        panic!("{renderer:?}: {e}");
    }
    seen.get()
}

#[test]
fn shared_blases_trace_and_shade_as_one_blas_per_mesh() {
    // One context: its pipelines are made once for both renders of every case.
    let ctx = Context::new(&ContextOptions { validation: Validation::Required, ..ContextOptions::default() })
        .expect("a validated Vulkan context (run `cargo xtask setup`)");
    // Fewer cases by ray queries: lavapipe compiles the compute pipeline for each render (1 to
    // 2 s a case, against 0.1 s through the ray tracing pipeline's kept libraries).
    let (pipeline, queries) = (property(&ctx, Renderer::Pipeline, 10), property(&ctx, Renderer::Compute, 2));
    // The property means little if the cases hit nothing or shared nothing. Double-sided
    // materials are 6 in 7 and masked ones 1 in 7, so that a mesh's primitives often share:
    // with both a toss-up and 1 to 4 primitives a mesh, 72 cases of 150 shared a structure.
    let (hits, sharing) = (pipeline.0 + queries.0, pipeline.1 + queries.1);
    assert!(hits > 0 && sharing > 0, "of 12 cases {hits} hit something, {sharing} shared a BLAS");
}
