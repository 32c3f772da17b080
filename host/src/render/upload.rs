//! Uploading a scene: its acceleration structures (BLASes and the TLAS) and the buffers its
//! stages read, shared by every pipeline that traces it.

use super::textures::upload_textures;
use crate::error::Result;
use crate::scene::merge::{self, BlasLimits, Run};
use crate::scene::{frame_data, Aabb, BlasDesc, InstanceDesc, Scene, SceneData};
use crate::vk::accel::{build_tlas, AccelStruct, InstanceRecord, Tlas, TlasFlags};
use crate::vk::blas::{build_blases, BlasInput, MeshGeometry};
use crate::vk::buffer::Buffer;
use crate::vk::commands::OneShot;
use crate::vk::context::Context;
use crate::vk::refit::MovingBlas;
use crate::vk::texture::Texture;
use ash::vk;
use glam::Mat4;
use gpu_allocator::MemoryLocation;
use std::cell::RefCell;
use std::rc::Rc;
use std::sync::Arc;
use twinray_shared::bindings as b;
use twinray_shared::layout::Light;

const VERTEX_BYTES: u64 = size_of::<twinray_shared::layout::Vertex>() as u64;

/// The scene's GPU data; kept alive until the trace has completed. The TLAS and the buffers
/// can be rewritten between submissions (moving scenes), never during one.
pub(crate) struct SceneResources {
    _blases: Vec<AccelStruct>,
    /// The BLASes of meshes whose vertices move: shape name, first vertex, BLAS index among
    /// the scene's, and the structure.
    pub moving: Vec<(String, u32, usize, MovingBlas)>,
    /// The texture array's slots, slot 0 first (`textures::upload_textures`).
    pub textures: Vec<Texture>,
    pub tlas: RefCell<Tlas>,
    /// (binding, buffer) of every storage and uniform buffer the scene provides.
    pub buffers: RefCell<Vec<(u32, vk::DescriptorType, Buffer)>>,
}

impl SceneResources {
    /// Rewrites the host-visible buffer at `binding` (the frame constants, the lights).
    pub fn write(&self, binding: u32, bytes: &[u8]) -> Result<()> {
        let mut buffers = self.buffers.borrow_mut();
        match buffers.iter_mut().find(|(b, ..)| *b == binding) {
            Some((.., buffer)) => buffer.write(bytes),
            None => Err(crate::error::Error::Unsupported(format!("the scene has no buffer at binding {binding}"))),
        }
    }
}

impl SceneResources {
    /// Rewrites the vertices from vertex `base` on (a posed mesh's), for its BLAS to be
    /// refitted or rebuilt (`MovingBlas::record`).
    pub fn write_vertices(&self, base: u32, vertices: &[twinray_shared::layout::Vertex]) -> Result<()> {
        let mut buffers = self.buffers.borrow_mut();
        let Some((.., buffer)) = buffers.iter_mut().find(|(b, ..)| *b == b::BINDING_VERTICES) else {
            return Err(crate::error::Error::Unsupported("the scene has no vertex buffer".into()));
        };
        buffer.write_at(base as usize * VERTEX_BYTES as usize, bytemuck::cast_slice(vertices))
    }

    /// Writes each instance's transform, `transforms[object]` for its object, into `records` and
    /// the TLAS's instances, for the caller to rebuild or update (`Tlas::record`).
    pub fn place(&self, records: &mut [InstanceRecord], instances: &[InstanceDesc], transforms: &[Mat4]) -> Result<()> {
        for (record, instance) in records.iter_mut().zip(instances) {
            record.object_to_world = transforms[instance.object as usize];
        }
        self.tlas.borrow_mut().write(records)
    }
}

/// The lights buffer's contents: `lights`, then zeros up to its fixed length `MAX_LIGHTS`,
/// which the stages declare (the scene check keeps a scene within it).
fn lights_buffer(lights: &[Light]) -> Vec<u8> {
    let scene: &[u8] = bytemuck::cast_slice(lights);
    let mut bytes = vec![0; b::MAX_LIGHTS as usize * size_of::<Light>()];
    bytes[..scene.len()].copy_from_slice(scene);
    bytes
}

/// A scene's data and GPU resources, which any number of pipelines can trace.
pub(crate) struct UploadedScene {
    /// What was uploaded, its meshes let go of once in the buffers (`Pooled::release`): the
    /// scene holds them, or, where it gave them up, no one.
    pub data: SceneData,
    pub resources: Rc<SceneResources>,
    /// The TLAS instances as uploaded: a moving scene rewrites their transforms.
    pub instances: Vec<InstanceRecord>,
    pub accel: AccelStats,
    /// Each object's own bounds, in object order.
    pub object_bounds: Vec<Aabb>,
}

impl UploadedScene {
    /// Moves the upload to where `scene` (the scene it was uploaded from, centred elsewhere)
    /// puts the GPU's coordinates: the TLAS rebuilt over the instances moved there, the frame
    /// constants (for `frame` pixels) and the lights rewritten; the BLASes and buffers, and so
    /// every pipeline's descriptors and SBT over them, are kept. A probe launches its rays at
    /// several origins so.
    pub fn centre(
        &mut self,
        ctx: &Arc<Context>,
        one_shot: &OneShot,
        scene: &Scene,
        (width, height): (u32, u32),
    ) -> Result<()> {
        let frame = frame_data(&scene.file_on_gpu(&scene.file), width, height, &self.object_bounds);
        self.resources.place(&mut self.instances, &self.data.instances, &frame.transforms)?;
        let tlas = self.resources.tlas.borrow();
        one_shot.run(|_, cmd| {
            tlas.record(ctx, cmd, false);
            Ok(())
        })?;
        self.resources.write(b::BINDING_FRAME, bytemuck::bytes_of(&frame.uniform))?;
        // Only the scene's lights: the zeros after them, up to MAX_LIGHTS, never change.
        self.resources.write(b::BINDING_LIGHTS, bytemuck::cast_slice(&frame.lights))
    }
}

/// Builds the scene's acceleration structures and buffers, frame constants for `frame` pixels:
/// from `data` where given (`Scene::on_gpu`'s, built before the scene gave its meshes up: they
/// are freed once the buffers hold them, before the structures are built), else from `scene`.
pub(crate) fn upload_shared(
    ctx: &Arc<Context>,
    scene: &Scene,
    data: Option<SceneData>,
    frame: (u32, u32),
) -> Result<UploadedScene> {
    upload_scene(ctx, (scene, data), frame, None)
}

/// What changes in a moving scene from frame to frame.
pub(crate) struct Movement<'a> {
    /// How its TLAS is made.
    pub flags: TlasFlags,
    /// The mesh shapes whose vertices move (skins, morph targets).
    pub posed: &'a [String],
    /// Whether objects move: then only objects of one body share an instance
    /// (`scene::merge`).
    pub objects: bool,
    /// Each object's rigid body, where the animation knows them (`Animation::bodies`); with
    /// objects moving and none known, no two objects share an instance.
    pub bodies: Option<Vec<usize>>,
}

impl Movement<'_> {
    /// Whether objects `a` and `b` stay placed alike from frame to frame.
    fn together(&self, a: usize, b: usize) -> bool {
        !self.objects
            || self.bodies.as_ref().is_some_and(|bodies| bodies.get(a).is_some_and(|x| bodies.get(b) == Some(x)))
    }
}

/// As `upload_shared`, with a TLAS made with `movement.flags` but not built: the caller builds
/// it, frame after frame, with `Tlas::record`. The BLASes of the posed mesh shapes are made
/// with those flags too, for the caller to refit or rebuild (`SceneResources::moving`).
pub(crate) fn upload_moving(
    ctx: &Arc<Context>,
    scene: &Scene,
    frame: (u32, u32),
    movement: Movement,
) -> Result<UploadedScene> {
    upload_scene(ctx, (scene, None), frame, Some(movement))
}

fn upload_scene(
    ctx: &Arc<Context>,
    (scene, given): (&Scene, Option<SceneData>),
    (width, height): (u32, u32),
    moving: Option<Movement>,
) -> Result<UploadedScene> {
    let _doing = crate::util::activity::doing(format!("building the acceleration structures of {}", scene.name()));
    let started = std::time::Instant::now();
    let one_shot = &OneShot::new(ctx)?;
    // The GPU works around the scene's local origin (`scene::origin`).
    let scene = &*scene.on_gpu();
    let mut built = given.unwrap_or_else(|| scene.build());
    check_structure_limits(ctx, &built)?;
    let object_bounds = built.object_bounds();
    // Meshes are read by the BLAS builds and by the triangle closest-hit stage.
    let mesh_usage = vk::BufferUsageFlags::STORAGE_BUFFER
        | vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
        | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
    let vertices = upload_parts(ctx, "vertices", built.vertices.parts().map(bytemuck::cast_slice), mesh_usage)?;
    let indices = upload_parts(ctx, "indices", built.indices.parts().map(bytemuck::cast_slice), mesh_usage)?;
    // Held now by the buffers: on a device whose buffers are host memory, a copy while the
    // structures are built would double a large model's share of the peak.
    built.vertices.release();
    built.indices.release();
    let data = &built;
    let (vertex_address, index_address) = (vertices.device_address(), indices.device_address());
    let (flags, moving_shapes) = moving.as_ref().map_or((TlasFlags::FastTrace, &[][..]), |m| (m.flags, m.posed));
    let mut moving_blases = Vec::new();
    for shape in moving_shapes {
        let Some(object) = scene.file.objects.iter().position(|o| o.shape == *shape) else { continue };
        let i = data.instances[object].blas;
        let BlasDesc::Triangles { vertex_base, vertex_count, index_base, index_count } = data.blases[i] else {
            continue;
        };
        let vertices = (vertex_address + u64::from(vertex_base) * VERTEX_BYTES, VERTEX_BYTES, vertex_count);
        let indices = (index_address + u64::from(index_base) * 4, index_count);
        let blas = MovingBlas::new(ctx, one_shot, vertices, indices, flags)?;
        moving_blases.push((shape.clone(), vertex_base, i, blas));
    }
    let posed = |object: usize| moving_blases.iter().any(|m| m.2 == data.instances[object].blas);
    let together = |a: usize, b: usize| moving.as_ref().is_none_or(|m| m.together(a, b));
    let limits = BlasLimits { geometries: ctx.geometries_per_blas(), primitives: ctx.info.max_primitive_count };
    let runs = merge::runs(data, |a, b| !posed(a) && !posed(b) && together(a, b), limits);
    let (inputs, of_run) = blas_inputs(data, &runs, |run| posed(run.first), (vertex_address, index_address));
    let blases = build_blases(ctx, one_shot, &inputs)?;
    let mut instances: Vec<_> = data
        .instances
        .iter()
        .map(|i| InstanceRecord {
            object_to_world: i.object_to_world,
            custom_index: i.custom_index,
            mask: i.mask,
            sbt_offset: i.hit_group,
            opaque: !data.plan.hit_groups.get(i.hit_group as usize).is_some_and(|g| g.cutout),
            single_sided: i.single_sided,
            // Inactive until its run places it: objects after a run's first are its geometries.
            blas_address: 0,
        })
        .collect();
    for (run, built) in runs.iter().zip(&of_run) {
        instances[run.first].blas_address = match built {
            Some(k) => blases[*k].address,
            None => moving_blases.iter().find(|m| m.2 == run.blases[0]).map_or(0, |m| m.3.accel.address),
        };
    }
    let tlas = match moving {
        Some(m) => Tlas::new(ctx, &instances, m.flags)?,
        None => build_tlas(ctx, one_shot, &instances)?,
    };
    let frame = crate::scene::frame_uniform(&scene.file, width, height, &data.placed_boxes(&object_bounds));
    let storage = vk::DescriptorType::STORAGE_BUFFER;
    let buffers = vec![
        (b::BINDING_FRAME, vk::DescriptorType::UNIFORM_BUFFER, upload(ctx, "frame", bytemuck::bytes_of(&frame))?),
        (b::BINDING_OBJECTS, storage, upload(ctx, "objects", bytemuck::cast_slice(&data.objects))?),
        (b::BINDING_PRIMITIVES, storage, upload(ctx, "primitives", bytemuck::cast_slice(&data.primitives))?),
        (b::BINDING_MATERIALS, storage, upload(ctx, "materials", bytemuck::cast_slice(&data.materials))?),
        (b::BINDING_LIGHTS, storage, upload(ctx, "lights", &lights_buffer(&data.lights))?),
        (b::BINDING_VERTICES, storage, vertices),
        (b::BINDING_INDICES, storage, indices),
    ];
    let all_blases = || blases.iter().chain(moving_blases.iter().map(|m| &m.3.accel));
    let accel = AccelStats {
        blases: blases.len() + moving_blases.len(),
        triangles: inputs.iter().map(BlasInput::triangles).sum::<u64>()
            + moving_blases.iter().map(|m| u64::from(m.3.triangles())).sum::<u64>(),
        instanced_triangles: data
            .instances
            .iter()
            .map(|i| match &data.blases[i.blas] {
                BlasDesc::Triangles { index_count, .. } => u64::from(*index_count / 3),
                BlasDesc::Aabbs(_) => 0,
            })
            .sum(),
        procedural_primitives: data.primitives.len() as u64,
        instances: instances.iter().filter(|i| i.blas_address != 0).count(),
        blas_built_bytes: all_blases().map(|b| b.built_bytes).sum(),
        blas_bytes: all_blases().map(|b| b.bytes).sum(),
        tlas_bytes: tlas.accel.bytes,
        build_ms: started.elapsed().as_secs_f64() * 1e3,
    };
    log::info!("scene {}: {accel}", scene.name());
    let textures = upload_textures(ctx, one_shot, &data.textures)?;
    let resources = SceneResources {
        _blases: blases,
        moving: moving_blases,
        textures,
        tlas: RefCell::new(tlas),
        buffers: RefCell::new(buffers),
    };
    Ok(UploadedScene { data: built, resources: Rc::new(resources), instances, accel, object_bounds })
}

/// Every shape's BLAS within the device's `maxPrimitiveCount`, and the objects within its
/// `maxInstanceCount`: past either a build is undefined, so the scene is refused before any
/// structure is made.
fn check_structure_limits(ctx: &Context, data: &SceneData) -> Result<()> {
    let most = ctx.info.max_primitive_count;
    if let Some(count) = primitives_past(&data.blases, most) {
        return Err(crate::error::Error::Input(format!(
            "a shape of {count} primitives is more than {} takes in one acceleration structure ({most})",
            ctx.info.name
        )));
    }
    if data.instances.len() as u64 > ctx.info.max_instance_count {
        return Err(crate::error::Error::Input(format!(
            "{} objects are more than {} takes in one acceleration structure ({})",
            data.instances.len(),
            ctx.info.name,
            ctx.info.max_instance_count
        )));
    }
    Ok(())
}

/// What each BLAS to build is made of: one per distinct run (instances of a mesh share it),
/// none for a run `skip` keeps out (a posed mesh's, built apart); for each run, the index of
/// its BLAS among them.
fn blas_inputs(
    data: &SceneData,
    runs: &[Run],
    skip: impl Fn(&Run) -> bool,
    (vertices, indices): (vk::DeviceAddress, vk::DeviceAddress),
) -> (Vec<BlasInput>, Vec<Option<usize>>) {
    let mut inputs = Vec::new();
    let mut index: std::collections::HashMap<&[usize], usize> = std::collections::HashMap::new();
    let of_run = runs
        .iter()
        .map(|run| {
            if skip(run) {
                return None;
            }
            let next = inputs.len();
            let k = *index.entry(run.blases.as_slice()).or_insert(next);
            if k == next {
                inputs.push(blas_input(data, &run.blases, (vertices, indices)));
            }
            Some(k)
        })
        .collect();
    (inputs, of_run)
}

/// The BLAS over `blases` (a procedural shape's boxes, or meshes each a geometry).
fn blas_input(
    data: &SceneData,
    blases: &[usize],
    (vertices, indices): (vk::DeviceAddress, vk::DeviceAddress),
) -> BlasInput {
    let mesh = |blas: &BlasDesc| match *blas {
        BlasDesc::Triangles { vertex_base, vertex_count, index_base, index_count } => Some(MeshGeometry {
            vertices: vertices + u64::from(vertex_base) * VERTEX_BYTES,
            stride: VERTEX_BYTES,
            vertex_count,
            indices: indices + u64::from(index_base) * 4,
            index_count,
        }),
        BlasDesc::Aabbs(_) => None,
    };
    match &data.blases[blases[0]] {
        BlasDesc::Aabbs(boxes) => BlasInput::Aabbs(boxes.iter().map(aabb_positions).collect()),
        BlasDesc::Triangles { .. } => BlasInput::Meshes(blases.iter().filter_map(|&b| mesh(&data.blases[b])).collect()),
    }
}

fn aabb_positions(b: &Aabb) -> vk::AabbPositionsKHR {
    vk::AabbPositionsKHR {
        min_x: b.min.x,
        min_y: b.min.y,
        min_z: b.min.z,
        max_x: b.max.x,
        max_y: b.max.y,
        max_z: b.max.z,
    }
}

/// The primitives of the first of `blases` that has more than `most`.
fn primitives_past(blases: &[BlasDesc], most: u64) -> Option<u64> {
    let count = |blas: &BlasDesc| match blas {
        BlasDesc::Triangles { index_count, .. } => u64::from(*index_count / 3),
        BlasDesc::Aabbs(boxes) => boxes.len() as u64,
    };
    blases.iter().map(count).find(|&n| n > most)
}

/// What a scene's acceleration structures hold and took: counts, device memory (bottom-level
/// structures as built and once compacted), and the host's wall time to build them all
/// (uploads, builds, compaction, each waited for).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct AccelStats {
    pub blases: usize,
    /// Triangles in the BLASes, each once.
    pub triangles: u64,
    /// Triangles of every instance: what the scene places.
    pub instanced_triangles: u64,
    pub procedural_primitives: u64,
    pub instances: usize,
    pub blas_built_bytes: u64,
    pub blas_bytes: u64,
    pub tlas_bytes: u64,
    pub build_ms: f64,
}

impl std::fmt::Display for AccelStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mib = |b: u64| b as f64 / (1u64 << 20) as f64;
        write!(
            f,
            "{} BLASes ({} triangles, {} placed; {} procedural primitives): {:.2} MiB as built, {:.2} MiB compacted; TLAS of {} instances {:.2} MiB; built in {:.0} ms",
            self.blases,
            self.triangles,
            self.instanced_triangles,
            self.procedural_primitives,
            mib(self.blas_built_bytes),
            mib(self.blas_bytes),
            self.instances,
            mib(self.tlas_bytes),
            self.build_ms
        )
    }
}

/// A host-visible buffer usable as a uniform or storage buffer; an empty slice still gets a
/// (zeroed) element's worth of memory, so every binding has a valid buffer.
fn upload(ctx: &Arc<Context>, name: &str, bytes: &[u8]) -> Result<Buffer> {
    upload_with(ctx, name, bytes, vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::UNIFORM_BUFFER)
}

/// A host-visible buffer holding `parts` end to end, each written straight from where it
/// lies (a scene's meshes), with no copy of the whole on the host.
fn upload_parts<'a>(
    ctx: &Arc<Context>,
    name: &str,
    parts: impl Iterator<Item = &'a [u8]> + Clone,
    usage: vk::BufferUsageFlags,
) -> Result<Buffer> {
    let size: usize = parts.clone().map(<[u8]>::len).sum();
    if size == 0 {
        return upload_with(ctx, name, &[], usage);
    }
    let mut buffer = Buffer::new(ctx, name, size as u64, usage, MemoryLocation::CpuToGpu)?;
    buffer.write_parts(parts)?;
    Ok(buffer)
}

fn upload_with(ctx: &Arc<Context>, name: &str, bytes: &[u8], usage: vk::BufferUsageFlags) -> Result<Buffer> {
    if bytes.is_empty() {
        return Buffer::with_data(ctx, name, &[0; 256], usage);
    }
    Buffer::with_data(ctx, name, bytes, usage)
}

#[cfg(test)]
mod tests {
    use super::*;
    use bytemuck::Zeroable;

    #[test]
    fn a_blas_past_the_device_limit_is_found() {
        let mesh = |triangles: u32| BlasDesc::Triangles {
            vertex_base: 0,
            vertex_count: 3,
            index_base: 0,
            index_count: 3 * triangles,
        };
        let boxes = BlasDesc::Aabbs(vec![Aabb { min: glam::Vec3::ZERO, max: glam::Vec3::ONE }; 5]);
        assert_eq!(primitives_past(&[mesh(4), boxes.clone()], 5), None);
        assert_eq!(primitives_past(&[mesh(4), mesh(6), boxes.clone()], 5), Some(6));
        assert_eq!(primitives_past(&[boxes, mesh(2)], 4), Some(5));
    }

    #[test]
    fn lights_buffer_holds_the_scene_lights_then_zeros_to_max_lights() {
        let lights = [Light { kind: 2, samples: 4, shadows: 1, ..Light::zeroed() }; 3];
        let bytes = lights_buffer(&lights);
        let size = size_of::<Light>();
        assert_eq!(bytes.len(), b::MAX_LIGHTS as usize * size);
        assert_eq!(&bytes[..3 * size], bytemuck::cast_slice::<Light, u8>(&lights));
        assert!(bytes[3 * size..].iter().all(|&byte| byte == 0));
    }
}
