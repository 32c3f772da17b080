//! From a checked scene to what the GPU needs: buffers, one BLAS per shape that an object uses,
//! one TLAS instance per object, and the pipeline plan — only the hit groups, miss shaders and
//! specialisation the scene uses.

use super::file::{Formula, LightDesc, MaterialDesc, SceneFile, ShadowSampler, ShapeDesc};
use super::mesh::MeshData;
use glam::{EulerRot, Mat4, Quat, Vec3, Vec4};
use std::collections::BTreeMap;
use twinray_shared::bindings as b;
use twinray_shared::layout::{FrameUniform, Light, Material, ObjectData, Primitive, Vertex};
use twinray_shared::plane::DISK;

/// The hit groups twinray can build, in the order they take in the shader binding table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum HitGroup {
    Triangles,
    Sphere,
    Plane,
    Box,
    Cylinder,
    Cone,
    Torus,
    SphereNaive,
    CylinderNaive,
    TorusNaive,
}

impl HitGroup {
    pub fn name(self) -> &'static str {
        match self {
            HitGroup::Triangles => "triangles",
            HitGroup::Sphere => "sphere",
            HitGroup::Plane => "plane",
            HitGroup::Box => "box",
            HitGroup::Cylinder => "cylinder",
            HitGroup::Cone => "cone",
            HitGroup::Torus => "torus",
            HitGroup::SphereNaive => "sphere (naive)",
            HitGroup::CylinderNaive => "cylinder (naive)",
            HitGroup::TorusNaive => "torus (naive)",
        }
    }

    /// The intersection module, for procedural groups (triangles use the built-in test).
    pub fn intersection_module(self) -> Option<&'static str> {
        match self {
            HitGroup::Triangles => None,
            HitGroup::Sphere => Some("sphere_intersection"),
            HitGroup::Plane => Some("plane_intersection"),
            HitGroup::Box => Some("box_intersection"),
            HitGroup::Cylinder => Some("cylinder_intersection"),
            HitGroup::Cone => Some("cone_intersection"),
            HitGroup::Torus => Some("torus_intersection"),
            HitGroup::SphereNaive => Some("sphere_naive_intersection"),
            HitGroup::CylinderNaive => Some("cylinder_naive_intersection"),
            HitGroup::TorusNaive => Some("torus_naive_intersection"),
        }
    }

    pub fn closest_hit_module(self) -> &'static str {
        match self {
            HitGroup::Triangles => "triangle_closest_hit",
            HitGroup::Sphere
            | HitGroup::Plane
            | HitGroup::Box
            | HitGroup::Cylinder
            | HitGroup::Cone
            | HitGroup::Torus
            | HitGroup::SphereNaive
            | HitGroup::CylinderNaive
            | HitGroup::TorusNaive => "procedural_closest_hit",
        }
    }
}

/// What the ray tracing pipeline of a scene contains.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PipelinePlan {
    /// Distinct hit groups, in SBT order; an instance's SBT offset is its group's index here.
    pub hit_groups: Vec<HitGroup>,
    /// Whether any light casts shadows: the shadow miss shader and shadow rays.
    pub shadows: bool,
    /// M for M x M primary samples per pixel.
    pub samples_per_side: u32,
    /// `SHADOW_SAMPLER_STRATIFIED` or `SHADOW_SAMPLER_RANDOM`.
    pub shadow_sampler: u32,
}

/// Axis-aligned box of one procedural primitive, in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

/// One TLAS instance: an object placing a shape's BLAS in the world.
#[derive(Clone, Copy, Debug)]
pub struct InstanceDesc {
    pub blas: usize,
    pub object_to_world: Mat4,
    /// Index of the object (the instance's index in the TLAS).
    pub object: u32,
    /// The instance custom index: the object's first primitive (procedural shapes).
    pub custom_index: u32,
    pub mask: u32,
    /// Index of the hit group in `PipelinePlan::hit_groups` (the SBT record offset).
    pub hit_group: u32,
}

/// The geometry of one BLAS.
#[derive(Clone, Debug, PartialEq)]
pub enum BlasDesc {
    /// Procedural primitives: their boxes.
    Aabbs(Vec<Aabb>),
    /// A mesh: its range in the scene's vertex and index buffers.
    Triangles { vertex_base: u32, vertex_count: u32, index_base: u32, index_count: u32 },
}

/// Everything a render uploads for a scene.
pub struct SceneData {
    pub plan: PipelinePlan,
    pub blases: Vec<BlasDesc>,
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
    pub instances: Vec<InstanceDesc>,
    pub objects: Vec<ObjectData>,
    pub primitives: Vec<Primitive>,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
}

/// Where a shape's data lies: its BLAS, and the bases an object of it records.
#[derive(Clone, Copy)]
struct ShapeSlot {
    blas: usize,
    primitive_base: u32,
    vertex_base: u32,
    index_base: u32,
}

/// Buffers and BLAS descriptions, filled one shape at a time.
#[derive(Default)]
struct Geometry {
    blases: Vec<BlasDesc>,
    primitives: Vec<Primitive>,
    vertices: Vec<Vertex>,
    indices: Vec<u32>,
}

impl Geometry {
    fn add(&mut self, shape: &ShapeDesc, mesh: Option<&MeshData>) -> ShapeSlot {
        let slot = ShapeSlot {
            blas: self.blases.len(),
            primitive_base: self.primitives.len() as u32,
            vertex_base: self.vertices.len() as u32,
            index_base: self.indices.len() as u32,
        };
        match mesh {
            Some(m) => {
                self.vertices.extend_from_slice(&m.vertices);
                self.indices.extend_from_slice(&m.indices);
                self.blases.push(BlasDesc::Triangles {
                    vertex_base: slot.vertex_base,
                    vertex_count: m.vertices.len() as u32,
                    index_base: slot.index_base,
                    index_count: m.indices.len() as u32,
                });
            }
            None => {
                let (prims, boxes) = shape_primitives(shape);
                self.primitives.extend(prims);
                self.blases.push(BlasDesc::Aabbs(boxes));
            }
        }
        slot
    }
}

pub fn build(scene: &SceneFile, meshes: &BTreeMap<String, MeshData>) -> SceneData {
    let material_index: BTreeMap<&str, u32> =
        scene.materials.keys().enumerate().map(|(i, n)| (n.as_str(), i as u32)).collect();
    let mut slots: BTreeMap<&str, ShapeSlot> = BTreeMap::new();
    let mut geometry = Geometry::default();
    let mut groups: Vec<HitGroup> = scene.objects.iter().map(|o| hit_group(&scene.shapes[&o.shape])).collect();
    groups.sort();
    groups.dedup();
    let mut objects = Vec::new();
    let mut instances = Vec::new();
    for (i, object) in scene.objects.iter().enumerate() {
        let shape = &scene.shapes[&object.shape];
        let slot =
            *slots.entry(object.shape.as_str()).or_insert_with(|| geometry.add(shape, meshes.get(&object.shape)));
        let material_name = object.material.as_str();
        objects.push(ObjectData {
            material: material_index[material_name],
            vertex_base: slot.vertex_base,
            index_base: slot.index_base,
            _pad0: 0,
        });
        let emissive = matches!(scene.materials[material_name], MaterialDesc::Emissive { .. });
        instances.push(InstanceDesc {
            blas: slot.blas,
            object_to_world: object_transform(object.translate, object.rotate, object.scale.axes()),
            object: i as u32,
            custom_index: slot.primitive_base,
            mask: if emissive { b::MASK_EMITTER } else { b::MASK_OCCLUDER },
            hit_group: groups.iter().position(|g| *g == hit_group(shape)).unwrap_or(0) as u32,
        });
    }
    let lights: Vec<Light> = scene.lights.iter().map(|l| light(l, scene.shadow_samples)).collect();
    let plan = PipelinePlan {
        hit_groups: groups,
        shadows: lights.iter().any(|l| l.shadows != 0),
        samples_per_side: scene.image.samples,
        shadow_sampler: match scene.shadow_sampler {
            ShadowSampler::Stratified => b::SHADOW_SAMPLER_STRATIFIED,
            ShadowSampler::Random => b::SHADOW_SAMPLER_RANDOM,
        },
    };
    let materials = scene.materials.values().map(material).collect();
    let Geometry { blases, primitives, vertices, indices } = geometry;
    SceneData { plan, blases, vertices, indices, instances, objects, primitives, materials, lights }
}

/// Camera and frame constants for an image of `width` x `height`.
pub fn frame_uniform(scene: &SceneFile, width: u32, height: u32) -> FrameUniform {
    let c = &scene.camera;
    let view = glam::camera::rh::view::look_at_mat4(c.eye.into(), c.target.into(), c.up.into());
    let aspect = width as f32 / height as f32;
    let proj = glam::camera::rh::proj::vulkan::perspective(c.fov_y_degrees.to_radians(), aspect, 0.1, 1000.0);
    FrameUniform {
        view_inverse: view.inverse(),
        proj_inverse: proj.inverse(),
        background: Vec3::from(scene.background).extend(1.0),
        light_count: scene.lights.len() as u32,
        seed: scene.image.seed,
        _pad0: 0,
        _pad1: 0,
    }
}

fn hit_group(shape: &ShapeDesc) -> HitGroup {
    match shape {
        ShapeDesc::Sphere { formula: Formula::Naive, .. } | ShapeDesc::SphereField { formula: Formula::Naive, .. } => {
            HitGroup::SphereNaive
        }
        ShapeDesc::Cylinder { formula: Formula::Naive, .. } => HitGroup::CylinderNaive,
        ShapeDesc::Torus { formula: Formula::Naive, .. } => HitGroup::TorusNaive,
        ShapeDesc::Sphere { .. } | ShapeDesc::SphereField { .. } => HitGroup::Sphere,
        ShapeDesc::Rectangle { .. } | ShapeDesc::Disk { .. } => HitGroup::Plane,
        ShapeDesc::Box { .. } => HitGroup::Box,
        ShapeDesc::Cylinder { .. } => HitGroup::Cylinder,
        ShapeDesc::Cone { .. } => HitGroup::Cone,
        ShapeDesc::Torus { .. } => HitGroup::Torus,
        ShapeDesc::Mesh { .. } => HitGroup::Triangles,
    }
}

/// Scale, then rotation about x, y and z (degrees), then translation.
pub fn object_transform(translate: [f32; 3], rotate_degrees: [f32; 3], scale: [f32; 3]) -> Mat4 {
    let [x, y, z] = rotate_degrees.map(f32::to_radians);
    let rotation = Quat::from_euler(EulerRot::ZYX, z, y, x);
    Mat4::from_scale_rotation_translation(scale.into(), rotation, translate.into())
}

fn sphere(center: Vec3, radius: f32, tint: Vec3) -> (Primitive, Aabb) {
    let primitive = Primitive { a: center.extend(radius), b: Vec4::ZERO, tint: tint.extend(1.0) };
    (primitive, Aabb { min: center - Vec3::splat(radius), max: center + Vec3::splat(radius) })
}

/// One primitive with parameters `a` and a box of half extents `half` about the origin.
fn single(a: Vec3, half: Vec3) -> (Vec<Primitive>, Vec<Aabb>) {
    let primitive = Primitive { a: a.extend(0.0), b: Vec4::ZERO, tint: Vec4::ONE };
    (vec![primitive], vec![Aabb { min: -half, max: half }])
}

/// A rectangle (half extents in `a.xy`) or disk (`a.x` radius, `disk` = DISK) in y = 0. Its box
/// gets a thickness of a thousandth of its size: zero-thickness boxes are legal in Vulkan but
/// leave grazing rays to each implementation's slab test.
fn plane(a: Vec4, disk: f32) -> (Vec<Primitive>, Vec<Aabb>) {
    let half = Vec3::new(a.x, a.x.max(a.y) * 1e-3, a.y);
    let primitive = Primitive { a, b: Vec4::new(disk, 0.0, 0.0, 0.0), tint: Vec4::ONE };
    (vec![primitive], vec![Aabb { min: -half, max: half }])
}

/// The primitives of a shape and their boxes, in object space.
fn shape_primitives(shape: &ShapeDesc) -> (Vec<Primitive>, Vec<Aabb>) {
    match *shape {
        ShapeDesc::Sphere { radius, .. } => {
            let (p, b) = sphere(Vec3::ZERO, radius, Vec3::ONE);
            (vec![p], vec![b])
        }
        ShapeDesc::Rectangle { size } => plane(Vec4::new(size[0] / 2.0, size[1] / 2.0, 0.0, 0.0), 0.0),
        ShapeDesc::Disk { radius } => plane(Vec4::new(radius, radius, 0.0, 0.0), DISK),
        ShapeDesc::Box { size } => single(Vec3::from(size) / 2.0, Vec3::from(size) / 2.0),
        ShapeDesc::Cylinder { radius, height, .. } | ShapeDesc::Cone { radius, height } => {
            single(Vec3::new(radius, height / 2.0, 0.0), Vec3::new(radius, height / 2.0, radius))
        }
        ShapeDesc::Torus { major_radius, minor_radius, .. } => {
            let outer = major_radius + minor_radius;
            single(Vec3::new(major_radius, minor_radius, 0.0), Vec3::new(outer, minor_radius, outer))
        }
        ShapeDesc::Mesh { .. } => (Vec::new(), Vec::new()),
        ShapeDesc::SphereField { count, seed, center_min, center_max, radius_min, radius_max, .. } => {
            let mut rng = SplitMix64(seed);
            let (lo, hi) = (Vec3::from(center_min), Vec3::from(center_max));
            (0..count)
                .map(|_| {
                    let center = lo + (hi - lo) * Vec3::new(rng.unit(), rng.unit(), rng.unit());
                    let radius = radius_min + (radius_max - radius_min) * rng.unit();
                    let tint = Vec3::new(rng.unit(), rng.unit(), rng.unit()) * 0.8 + Vec3::splat(0.2);
                    sphere(center, radius, tint)
                })
                .unzip()
        }
    }
}

fn material(m: &MaterialDesc) -> Material {
    let (kind, a, b) = match *m {
        MaterialDesc::Diffuse { color } => (b::MATERIAL_DIFFUSE, Vec3::from(color).extend(1.0), Vec4::ZERO),
        MaterialDesc::Emissive { color, intensity } => {
            (b::MATERIAL_EMISSIVE, (Vec3::from(color) * intensity).extend(1.0), Vec4::ZERO)
        }
        MaterialDesc::Checker { colors, scale } => {
            (b::MATERIAL_CHECKER, Vec3::from(colors[0]).extend(1.0), Vec3::from(colors[1]).extend(scale))
        }
    };
    Material { kind, _pad0: 0, _pad1: 0, _pad2: 0, color_a: a, color_b: b }
}

fn light(l: &LightDesc, default_samples: u32) -> Light {
    let (kind, samples, shadows, position, color, intensity, u, v) = match *l {
        LightDesc::Directional { direction, color, intensity, shadows } => (
            b::LIGHT_DIRECTIONAL,
            1,
            shadows,
            Vec3::from(direction).normalize(),
            color,
            intensity,
            Vec3::ZERO,
            Vec3::ZERO,
        ),
        LightDesc::Point { position, color, intensity, shadows } => {
            (b::LIGHT_POINT, 1, shadows, position.into(), color, intensity, Vec3::ZERO, Vec3::ZERO)
        }
        LightDesc::Rect { center, u, v, color, intensity, samples, shadows } => (
            b::LIGHT_RECT,
            samples.unwrap_or(default_samples),
            shadows,
            center.into(),
            color,
            intensity,
            u.into(),
            v.into(),
        ),
    };
    Light {
        kind,
        samples,
        shadows: u32::from(shadows),
        _pad0: 0,
        position: position.extend(1.0),
        radiance: (Vec3::from(color) * intensity).extend(1.0),
        u: u.extend(0.0),
        v: v.extend(0.0),
    }
}

/// SplitMix64 (Steele, Lea, Flood 2014): small, fast, and fully specified.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 24 random bits: exact in f32.
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}
