//! From a checked scene to what the GPU needs: buffers, one BLAS per shape that an object uses,
//! one TLAS instance per object, and the pipeline plan — only the hit groups, miss shaders and
//! specialisation the scene uses.

use super::file::TextureLod;
use super::file::{
    CutoutPattern, EmissionDesc, HitGroups, LightDesc, MaterialDesc, MaterialShading, Renderer, SceneFile,
    ShadowMethod, ShadowSampler,
};
use super::mesh::MeshData;
use super::plan::{scene_features, Colour, HitGeometry, HitGroup, PipelinePlan};
use super::pool::Pooled;
use super::reach;
use super::shape::{Formula, OwnDesc, ShapeDesc};
use super::texture::{SamplerDesc, TextureDesc, TextureImage};
use glam::{Mat4, Vec3, Vec4};
use std::collections::BTreeMap;
use std::sync::Arc;
use twinray_shared::bindings as b;
use twinray_shared::features;
use twinray_shared::layout::{FrameUniform, Light, Material, ObjectData, Primitive, Vertex};
pub use twinray_shared::shapes::spec::Aabb;
use twinray_shared::shapes::SHAPES;

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
    /// Its triangles' back faces culled for primary rays (`ObjectDesc::single_sided`).
    pub single_sided: bool,
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
    /// The meshes' vertices and indices end to end, as the GPU's buffers hold them (shared
    /// with the scene's meshes, not copied).
    pub vertices: Pooled<Vertex>,
    pub indices: Pooled<u32>,
    pub instances: Vec<InstanceDesc>,
    pub objects: Vec<ObjectData>,
    pub primitives: Vec<Primitive>,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    /// The images and samplers of the texture array's slots from 1 (slot 0 is white): each
    /// distinct pair once.
    pub textures: Vec<(Arc<TextureImage>, SamplerDesc)>,
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
struct Geometry {
    blases: Vec<BlasDesc>,
    primitives: Vec<Primitive>,
    vertices: Pooled<Vertex>,
    indices: Pooled<u32>,
}

impl Geometry {
    fn new() -> Self {
        Geometry {
            blases: Vec::new(),
            primitives: Vec::new(),
            vertices: Pooled::new(|m| &m.vertices),
            indices: Pooled::new(|m| &m.indices),
        }
    }

    fn add(&mut self, shape: &ShapeDesc, mesh: Option<&Arc<MeshData>>) -> ShapeSlot {
        let slot = ShapeSlot {
            blas: self.blases.len(),
            primitive_base: self.primitives.len() as u32,
            vertex_base: self.vertices.len() as u32,
            index_base: self.indices.len() as u32,
        };
        match mesh {
            Some(m) => {
                self.vertices.push(m.clone());
                self.indices.push(m.clone());
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

pub fn build(
    scene: &SceneFile,
    meshes: &BTreeMap<String, Arc<MeshData>>,
    origin: Vec3,
    starts: Option<&Aabb>,
) -> SceneData {
    let material_index: BTreeMap<&str, u32> =
        scene.materials.keys().enumerate().map(|(i, n)| (n.as_str(), i as u32)).collect();
    let mut slots: BTreeMap<&str, ShapeSlot> = BTreeMap::new();
    let mut geometry = Geometry::new();
    let callable = scene.material_shading == MaterialShading::Callable;
    let group_of =
        |o: &super::file::ObjectDesc| hit_group(scene, &scene.shapes[&o.shape], &scene.materials[&o.material]);
    let mut groups: Vec<HitGroup> = scene.objects.iter().map(group_of).collect();
    groups.sort();
    groups.dedup();
    let mut objects = Vec::new();
    let mut instances = Vec::new();
    for (i, object) in scene.objects.iter().enumerate() {
        let shape = &scene.shapes[&object.shape];
        let mesh = meshes.get(&object.shape);
        // Loading gives every mesh shape its mesh; only a scene whose meshes were given up
        // (`render_owned`) lacks one, and building it would trace an empty structure.
        assert!(
            mesh.is_some() || !matches!(shape, ShapeDesc::Mesh(_) | ShapeDesc::Gltf(_)),
            "mesh shape {:?} has no mesh to build: the scene's meshes were given up",
            object.shape
        );
        let slot = *slots.entry(object.shape.as_str()).or_insert_with(|| geometry.add(shape, mesh));
        let material_name = object.material.as_str();
        objects.push(ObjectData {
            material: material_index[material_name],
            vertex_base: slot.vertex_base,
            index_base: slot.index_base,
            shape: group_of(object).shape_routine(),
        });
        let emissive = matches!(scene.materials[material_name], MaterialDesc::Emissive { .. });
        instances.push(InstanceDesc {
            blas: slot.blas,
            object_to_world: object.transform(),
            object: i as u32,
            custom_index: slot.primitive_base,
            mask: if emissive { b::MASK_EMITTER } else { b::MASK_OCCLUDER },
            hit_group: groups.iter().position(|g| *g == group_of(object)).unwrap_or(0) as u32,
            single_sided: object.single_sided,
        });
    }
    let lights = lights(scene);
    let mut textures = Vec::new();
    let own = scene.materials.values().filter_map(|m| if let MaterialDesc::Own(o) = m { Some(o) } else { None });
    let own_callables = super::material::own_callables(own);
    let materials: Vec<Material> =
        scene.materials.values().map(|m| material(m, &own_callables, &mut textures)).collect();
    let plan = PipelinePlan {
        hit_groups: groups,
        shadows: lights.iter().any(|l| l.shadows != 0),
        samples_per_side: scene.image.samples,
        shadow_sampler: match scene.shadow_sampler {
            ShadowSampler::Stratified => b::SHADOW_SAMPLER_STRATIFIED,
            ShadowSampler::Random => b::SHADOW_SAMPLER_RANDOM,
        },
        shadow_query: scene.shadow_method == ShadowMethod::Query,
        compute: scene.renderer == Renderer::Compute,
        callable_kinds: material_kinds(&materials, callable),
        own_callables,
        features: match &scene.features {
            Some(names) => names.iter().filter_map(|n| features::by_name(n)).fold(0, |bits, f| bits | f.bit),
            None => scene_features(&materials, &lights),
        },
    };
    let Geometry { blases, primitives, vertices, indices } = geometry;
    let mut data =
        SceneData { plan, blases, vertices, indices, instances, objects, primitives, materials, lights, textures };
    // A moving scene is taken to have far instances, as its objects may move anywhere.
    if scene.features.is_none() && (scene.animation.is_some() || data.far_at(origin, starts)) {
        data.plan.features |= features::FAR_INSTANCES;
    }
    data
}

/// `m` with its translation moved by `-origin` (`origin::to_local`).
fn local(mut m: Mat4, origin: Vec3) -> Mat4 {
    m.w_axis = super::origin::to_local(m.w_axis.truncate(), origin).extend(1.0);
    m
}

/// The kinds of `materials` that callables colour, each once, in kind order: all, where
/// `callable`, else those of a crate's own.
fn material_kinds(materials: &[Material], callable: bool) -> Vec<u32> {
    let called = materials.iter().map(|m| m.kind).filter(|&k| callable || k >= b::MATERIAL_KINDS);
    let mut kinds: Vec<u32> = called.collect();
    kinds.sort_unstable();
    kinds.dedup();
    kinds
}

/// What a frame of a moving scene rewrites on the GPU, from the scene posed at that frame.
pub struct FrameData {
    /// Each object's object-to-world transform, in object (TLAS instance) order.
    pub transforms: Vec<Mat4>,
    pub lights: Vec<Light>,
    pub uniform: FrameUniform,
}

/// The transforms, lights and frame constants of `scene` as it stands, its objects' own
/// bounds being `object_bounds` (see `reach::object_bounds`).
pub fn frame_data(scene: &SceneFile, width: u32, height: u32, object_bounds: &[Aabb]) -> FrameData {
    let transforms: Vec<Mat4> = scene.objects.iter().map(|o| o.transform()).collect();
    let boxes = reach::world_boxes(object_bounds, &transforms);
    FrameData { uniform: frame_uniform(scene, width, height, &boxes), transforms, lights: lights(scene) }
}

impl SceneData {
    /// Whether the scene has far instances with the GPU's coordinates centred at `origin`: an
    /// object lies far from it for its size, or, for a probe, from where its rays start
    /// (`starts`, in the scene's coordinates, moved there too) (`reach`).
    pub fn far_at(&self, origin: Vec3, starts: Option<&Aabb>) -> bool {
        let transforms: Vec<Mat4> = self.instances.iter().map(|i| local(i.object_to_world, origin)).collect();
        let bounds = self.object_bounds();
        let far_from_starts = |s: &Aabb| {
            let local =
                Aabb { min: super::origin::to_local(s.min, origin), max: super::origin::to_local(s.max, origin) };
            reach::far_from(&bounds, &transforms, &local)
        };
        reach::far_instances(&bounds, &transforms) || starts.is_some_and(far_from_starts)
    }

    /// The hit group of `object` (its TLAS instance's SBT record); none for an object the scene
    /// does not have.
    pub fn hit_group_of(&self, object: u32) -> Option<HitGroup> {
        self.instances.get(object as usize).map(|i| self.plan.hit_groups[i.hit_group as usize])
    }

    /// Each object's world-space bounds, as built.
    pub fn world_boxes(&self) -> Vec<Aabb> {
        self.placed_boxes(&self.object_bounds())
    }

    /// Each object's world-space bounds, its own being `object_bounds`.
    pub fn placed_boxes(&self, object_bounds: &[Aabb]) -> Vec<Aabb> {
        let transforms: Vec<Mat4> = self.instances.iter().map(|i| i.object_to_world).collect();
        reach::world_boxes(object_bounds, &transforms)
    }

    /// Each object's bounds in its own space, in object (TLAS instance) order.
    pub fn object_bounds(&self) -> Vec<Aabb> {
        let blas_bounds: Vec<Aabb> = self.blases.iter().map(|b| self.blas_bounds(b)).collect();
        self.instances.iter().map(|i| blas_bounds[i.blas]).collect()
    }

    fn blas_bounds(&self, blas: &BlasDesc) -> Aabb {
        let points: Vec<Vec3> = match blas {
            BlasDesc::Aabbs(boxes) => boxes.iter().flat_map(|b| [b.min, b.max]).collect(),
            BlasDesc::Triangles { vertex_base, vertex_count, .. } => {
                let range = self.vertices.range(*vertex_base as usize, *vertex_count as usize).unwrap_or_default();
                range.iter().map(|v| v.position.truncate()).collect()
            }
        };
        reach::enclose(points).unwrap_or(Aabb { min: Vec3::ZERO, max: Vec3::ZERO })
    }
}

fn lights(scene: &SceneFile) -> Vec<Light> {
    scene.lights.iter().map(|l| light(l, scene.shadow_samples)).collect()
}

/// Camera and frame constants for an image of `width` x `height`, the objects' world bounds
/// being `boxes` (they set the rays' reach).
pub fn frame_uniform(scene: &SceneFile, width: u32, height: u32, boxes: &[Aabb]) -> FrameUniform {
    let c = &scene.camera;
    let view = glam::camera::rh::view::look_at_mat4(c.eye.into(), c.target.into(), c.up.into());
    let aspect = width as f32 / height as f32;
    // Its near and far planes set no reach (`reach` does): rays take only their direction from it.
    let proj = glam::camera::rh::proj::vulkan::perspective(c.fov_y_degrees.to_radians(), aspect, 0.1, 1000.0);
    // An orthographic camera's maps the image (y down) onto its plane, `height` high.
    let ortho = |height: f32| Mat4::from_diagonal(Vec4::new(height / 2.0 * aspect, -height / 2.0, 1.0, 1.0));
    let mut uniform = FrameUniform {
        view_inverse: view.inverse(),
        proj_inverse: c.orthographic_height.map_or_else(|| proj.inverse(), ortho),
        background: Vec3::from(scene.background).extend(1.0),
        reach: reach::reach(boxes, c.eye.into()),
        light_count: scene.lights.len() as u32,
        seed: scene.image.seed,
        width,
        height,
        cone: match scene.image.texture_lod {
            TextureLod::Cones => {
                glam::Vec4::X
                    * twinray_shared::texture::spread_angle(c.fov_y_degrees.to_radians(), height, scene.image.samples)
            }
            TextureLod::Zero => glam::Vec4::ZERO,
        },
    };
    if c.orthographic_height.is_some() {
        // Parallel rays: no cone spreads (texture level 0), and the stages' camera told so.
        uniform.cone = Vec4::Y;
    }
    uniform
}

/// The hit group of an object of `shape` and `material` in `scene`.
fn hit_group(scene: &SceneFile, shape: &ShapeDesc, material: &MaterialDesc) -> HitGroup {
    let geometry = match shape {
        ShapeDesc::Procedural(p) => HitGeometry::Procedural {
            naive: p.formula == Formula::Naive && p.shape.naive_module.is_some(),
            shape: SHAPES.iter().position(|s| s.name == p.shape.name).unwrap_or(0),
        },
        ShapeDesc::Own(OwnDesc { resolved: Some((own, _)), .. }) => HitGeometry::Own(*own),
        // Resolved before the scene is built (`Scene::from_file`); never drawn otherwise.
        ShapeDesc::Own(_) => HitGeometry::Triangles,
        ShapeDesc::Mesh(_) | ShapeDesc::Gltf(_) => HitGeometry::Triangles,
    };
    let flat = !matches!(material, MaterialDesc::Checker { .. });
    let colour = match (scene.material_shading, scene.hit_groups) {
        _ if matches!(material, MaterialDesc::Own(_)) => Colour::Callable,
        (MaterialShading::Callable, _) => Colour::Callable,
        (MaterialShading::Inline, HitGroups::PerMaterial) if flat => Colour::Flat,
        (MaterialShading::Inline, _) => Colour::Inline,
    };
    HitGroup { geometry, cutout: matches!(material, MaterialDesc::Cutout { .. }), colour }
}

/// The primitives of a shape and their boxes, in object space (a mesh has none).
fn shape_primitives(shape: &ShapeDesc) -> (Vec<Primitive>, Vec<Aabb>) {
    match shape {
        ShapeDesc::Procedural(p) => (p.kind.primitives)(&p.values).into_iter().unzip(),
        // The crate's refusal was reported when the scene was checked (`check::check_shape`).
        ShapeDesc::Own(OwnDesc { resolved: Some((own, values)), .. }) => {
            own.primitives(values).unwrap_or_default().into_iter().unzip()
        }
        ShapeDesc::Own(_) => (Vec::new(), Vec::new()),
        ShapeDesc::Mesh(_) | ShapeDesc::Gltf(_) => (Vec::new(), Vec::new()),
    }
}

/// The GPU material of `m`, a crate's own kind being `MATERIAL_KINDS` plus its callable's place
/// in `own_callables`; each of its textures takes a slot of `textures` (shared with every
/// material of the same image and sampler).
fn material(
    m: &MaterialDesc,
    own_callables: &[&'static str],
    textures: &mut Vec<(Arc<TextureImage>, SamplerDesc)>,
) -> Material {
    let mut cutout = (b::CUTOUT_NONE, 0.0, 0.0);
    let mut gpu = Material::default();
    let (kind, a, b) = match *m {
        MaterialDesc::Diffuse { color, ref texture, ref emission } => {
            surface_textures(&mut gpu, texture.as_deref(), emission.as_deref(), textures);
            (b::MATERIAL_DIFFUSE, Vec3::from(color).extend(1.0), Vec4::ZERO)
        }
        MaterialDesc::Emissive { color, intensity } => {
            (b::MATERIAL_EMISSIVE, (Vec3::from(color) * intensity).extend(1.0), Vec4::ZERO)
        }
        MaterialDesc::Checker { colors, scale } => {
            (b::MATERIAL_CHECKER, Vec3::from(colors[0]).extend(1.0), Vec3::from(colors[1]).extend(scale))
        }
        MaterialDesc::Cutout { color, pattern, scale, threshold, opacity, ref texture, ref emission } => {
            let pattern = match pattern {
                CutoutPattern::Checker => b::CUTOUT_CHECKER,
                CutoutPattern::Discs => b::CUTOUT_DISCS,
                CutoutPattern::Alpha => b::CUTOUT_TEXTURE,
            };
            surface_textures(&mut gpu, texture.as_deref(), emission.as_deref(), textures);
            cutout = (pattern, scale, threshold);
            (b::MATERIAL_CUTOUT, Vec3::from(color).extend(opacity), Vec4::ZERO)
        }
        MaterialDesc::Own(ref own) => match own.resolved {
            Some((found, _, [a, b])) => {
                let module = found.material().module;
                let place = own_callables.iter().position(|c| *c == module).unwrap_or(0) as u32;
                (b::MATERIAL_KINDS + place, a, b)
            }
            // Resolved before the scene is built (`Scene::from_file`); never drawn otherwise.
            None => (b::MATERIAL_DIFFUSE, Vec4::ONE, Vec4::ZERO),
        },
    };
    let (cutout_pattern, cutout_scale, cutout_threshold) = cutout;
    Material { kind, cutout_pattern, cutout_scale, cutout_threshold, color_a: a, color_b: b, ..gpu }
}

/// Points `gpu` at its own `texture` (`texture.xy`) and its emission's (`texture.zw`), and
/// sets its emission and the one transform both read through (the scene check makes sure
/// they agree).
fn surface_textures(
    gpu: &mut Material,
    texture: Option<&TextureDesc>,
    emission: Option<&EmissionDesc>,
    textures: &mut Vec<(Arc<TextureImage>, SamplerDesc)>,
) {
    if let Some(e) = emission {
        gpu.emission = (Vec3::from(e.color) * e.intensity).extend(0.0);
    }
    let emission_texture = emission.and_then(|e| e.texture.as_deref());
    if let Some((slot, t)) = texture.and_then(|t| texture_slot(t, textures).map(|s| (s, t))) {
        (gpu.texture.x, gpu.texture.y) = (slot, t.uv);
        set_transform(gpu, t);
    }
    if let Some((slot, t)) = emission_texture.and_then(|t| texture_slot(t, textures).map(|s| (s, t))) {
        (gpu.texture.z, gpu.texture.w) = (slot, t.uv);
        set_transform(gpu, t);
    }
}

/// `t`'s slot, a new one for an image and sampler not seen yet (`None` before its image is
/// decoded).
fn texture_slot(t: &TextureDesc, textures: &mut Vec<(Arc<TextureImage>, SamplerDesc)>) -> Option<u32> {
    let image = t.image.as_ref()?;
    let known = textures.iter().position(|(i, s)| Arc::ptr_eq(i, image) && *s == t.sampler);
    let slot = known.unwrap_or_else(|| {
        textures.push((image.clone(), t.sampler));
        textures.len() - 1
    });
    Some(slot as u32 + 1)
}

fn set_transform(gpu: &mut Material, t: &TextureDesc) {
    let [u, v] = t.transform;
    gpu.uv_u = Vec3::from(u).extend(0.0);
    gpu.uv_v = Vec3::from(v).extend(0.0);
}

/// A point light's axis and the scale and offset that turn the cosine to it into its cone's
/// falloff (`twinray_shared::lighting::falloff`): no axis, 0 and 1 for a light without a cone.
fn spot_cone(spot: Option<&super::light::SpotDesc>) -> (Vec3, Vec3) {
    let Some(spot) = spot else { return (Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0)) };
    let (inner, outer) = (spot.inner_cone_degrees.to_radians().cos(), spot.outer_cone_degrees.to_radians().cos());
    // glTF's sample viewer divides by the difference, and its spec guards it so.
    let scale = 1.0 / (inner - outer).max(1e-3);
    (Vec3::from(spot.direction).normalize(), Vec3::new(scale, -outer * scale, 0.0))
}

fn light(l: &LightDesc, default_samples: u32) -> Light {
    let (kind, samples, shadows, position, color, intensity, u, v) = match *l {
        LightDesc::Directional { direction, color, intensity, shadows } => (
            b::LIGHT_DIRECTIONAL,
            1,
            shadows,
            Vec3::from(direction).normalize().extend(1.0),
            color,
            intensity,
            Vec3::ZERO,
            Vec3::ZERO,
        ),
        LightDesc::Point { position, color, intensity, shadows, range, spot } => {
            let (axis, cone) = spot_cone(spot.as_ref());
            let reach = range.map_or(0.0, |r| 1.0 / r);
            (b::LIGHT_POINT, 1, shadows, Vec3::from(position).extend(reach), color, intensity, axis, cone)
        }
        LightDesc::Rect { center, u, v, color, intensity, samples, shadows } => (
            b::LIGHT_RECT,
            samples.unwrap_or(default_samples),
            shadows,
            Vec3::from(center).extend(1.0),
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
        position,
        radiance: (Vec3::from(color) * intensity).extend(1.0),
        u: u.extend(0.0),
        v: v.extend(0.0),
    }
}
