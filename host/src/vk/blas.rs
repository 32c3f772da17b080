//! Bottom-level structures built once and traced many times: many per submission, each
//! compacted (see `compact`), so that a scene of thousands of meshes costs a few waits, not
//! two per mesh. A BLAS holds boxes (procedural primitives) or one or more meshes, each a
//! geometry of its own, all opaque.

use super::accel::{allocate_sized, build_info, built_for_reading, scratch, triangles, AccelStruct};
use super::buffer::Buffer;
use super::commands::{memory_barrier, OneShot};
use super::compact::{record_copy, CompactedSizes};
use super::context::Context;
use crate::error::Result;
use ash::vk;
use std::sync::Arc;

/// One mesh of a BLAS: `vertex_count` vertices of `stride` bytes (an f32 position at offset 0)
/// from `vertices`, `index_count` u32 indices from `indices` (device addresses).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshGeometry {
    pub vertices: vk::DeviceAddress,
    pub stride: u64,
    pub vertex_count: u32,
    pub indices: vk::DeviceAddress,
    pub index_count: u32,
}

/// What one BLAS is built over.
#[derive(Clone, Debug)]
pub enum BlasInput {
    /// Axis-aligned boxes, one procedural primitive each: one geometry.
    Aabbs(Vec<vk::AabbPositionsKHR>),
    /// Meshes, geometry `g` the `g`-th: a hit on it reports geometry index `g`.
    Meshes(Vec<MeshGeometry>),
}

impl BlasInput {
    /// Its triangles (none for boxes).
    pub fn triangles(&self) -> u64 {
        match self {
            BlasInput::Aabbs(_) => 0,
            BlasInput::Meshes(meshes) => meshes.iter().map(|m| u64::from(m.index_count / 3)).sum(),
        }
    }

    /// Primitives of each geometry.
    fn counts(&self) -> Vec<u32> {
        match self {
            BlasInput::Aabbs(boxes) => vec![boxes.len() as u32],
            BlasInput::Meshes(meshes) => meshes.iter().map(|m| m.index_count / 3).collect(),
        }
    }
}

/// Most bytes of structures and scratch one submission builds: a batch's scratch and its
/// structures before compaction are what batching adds to a scene's peak memory (one large
/// mesh is a batch of its own). 16 MiB builds 20,164 small BLASes as fast as 256 MiB on
/// lavapipe, and 406 BLASes of 105 MiB in all peak at 364 MB against 430 MB.
const BATCH_BYTES: u64 = 16 << 20;
/// Most structures one submission builds.
const BATCH_COUNT: usize = 4096;

/// The BLAS of each of `inputs`, in order: built in batches, waited for, and compacted.
pub fn build_blases(ctx: &Arc<Context>, one_shot: &OneShot, inputs: &[BlasInput]) -> Result<Vec<AccelStruct>> {
    let mut built = Vec::with_capacity(inputs.len());
    while built.len() < inputs.len() {
        let rest = &inputs[built.len()..];
        let sizes = batch_sizes(ctx, rest);
        built.extend(build_batch(ctx, one_shot, &rest[..sizes.len()], &sizes)?);
    }
    Ok(built)
}

/// The build sizes of as many of `inputs` (at least one) as one batch takes.
fn batch_sizes(ctx: &Context, inputs: &[BlasInput]) -> Vec<vk::AccelerationStructureBuildSizesInfoKHR<'static>> {
    let mut sizes = Vec::new();
    let mut bytes = 0u64;
    for input in inputs.iter().take(BATCH_COUNT) {
        // Sizes depend on the counts and formats, not on the addresses, which are left 0.
        let geometries = geometries(input, 0);
        let info = build_info(vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, blas_flags(), &geometries);
        let mut size = vk::AccelerationStructureBuildSizesInfoKHR::default();
        // SAFETY: info and counts describe the same geometries; no buffer is read.
        unsafe {
            ctx.accel.get_acceleration_structure_build_sizes(
                vk::AccelerationStructureBuildTypeKHR::DEVICE,
                &info,
                &input.counts(),
                &mut size,
            )
        };
        bytes += size.acceleration_structure_size + size.build_scratch_size;
        if !sizes.is_empty() && bytes > BATCH_BYTES {
            break;
        }
        sizes.push(size);
    }
    sizes
}

fn blas_flags() -> vk::BuildAccelerationStructureFlagsKHR {
    vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_TRACE | vk::BuildAccelerationStructureFlagsKHR::ALLOW_COMPACTION
}

/// The geometries of `input`, its boxes (if any) read from `aabbs`.
fn geometries(input: &BlasInput, aabbs: vk::DeviceAddress) -> Vec<vk::AccelerationStructureGeometryKHR<'static>> {
    match input {
        BlasInput::Aabbs(_) => {
            let data = vk::AccelerationStructureGeometryAabbsDataKHR::default()
                .data(vk::DeviceOrHostAddressConstKHR { device_address: aabbs })
                .stride(size_of::<vk::AabbPositionsKHR>() as u64);
            vec![vk::AccelerationStructureGeometryKHR::default()
                .geometry_type(vk::GeometryTypeKHR::AABBS)
                .geometry(vk::AccelerationStructureGeometryDataKHR { aabbs: data })
                .flags(vk::GeometryFlagsKHR::OPAQUE)]
        }
        BlasInput::Meshes(meshes) => {
            meshes.iter().map(|m| triangles(m.vertices, m.stride, m.vertex_count, m.indices)).collect()
        }
    }
}

/// Builds `inputs` (whose sizes are `sizes`) in one submission, then compacts them in another.
fn build_batch(
    ctx: &Arc<Context>,
    one_shot: &OneShot,
    inputs: &[BlasInput],
    sizes: &[vk::AccelerationStructureBuildSizesInfoKHR<'static>],
) -> Result<Vec<AccelStruct>> {
    // Every box of the batch in one buffer, each BLAS's from its offset.
    let mut box_bytes = Vec::new();
    let mut box_offsets = Vec::with_capacity(inputs.len());
    for input in inputs {
        box_offsets.push(box_bytes.len() as u64);
        if let BlasInput::Aabbs(boxes) = input {
            box_bytes.extend(boxes.iter().flat_map(aabb_bytes));
        }
    }
    let usage = vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
        | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
    let boxes = match box_bytes.is_empty() {
        true => None,
        false => Some(Buffer::with_data(ctx, "aabbs", &box_bytes, usage)?),
    };
    let box_base = boxes.as_ref().map_or(0, Buffer::device_address);
    let geometries: Vec<_> = inputs.iter().zip(&box_offsets).map(|(i, o)| geometries(i, box_base + o)).collect();
    let ty = vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL;
    let accels = sizes
        .iter()
        .map(|s| allocate_sized(ctx, ty, s.acceleration_structure_size, "blas"))
        .collect::<Result<Vec<_>>>()?;
    let align = u64::from(ctx.info.min_scratch_offset_alignment.max(1));
    let scratch_offsets: Vec<u64> = sizes
        .iter()
        .scan(0u64, |at, s| {
            let here = *at;
            *at += s.build_scratch_size.next_multiple_of(align);
            Some(here)
        })
        .collect();
    let scratch_total = sizes.iter().map(|s| s.build_scratch_size.next_multiple_of(align)).sum::<u64>();
    let (scratch, scratch_address) = scratch(ctx, scratch_total.max(align))?;
    let infos: Vec<_> = geometries
        .iter()
        .zip(&accels)
        .zip(&scratch_offsets)
        .map(|((g, accel), offset)| {
            build_info(ty, blas_flags(), g)
                .dst_acceleration_structure(accel.raw)
                .scratch_data(vk::DeviceOrHostAddressKHR { device_address: scratch_address + offset })
        })
        .collect();
    let ranges: Vec<Vec<_>> = inputs
        .iter()
        .map(|i| {
            i.counts()
                .into_iter()
                .map(|n| vk::AccelerationStructureBuildRangeInfoKHR::default().primitive_count(n))
                .collect()
        })
        .collect();
    let range_refs: Vec<&[_]> = ranges.iter().map(Vec::as_slice).collect();
    let query = CompactedSizes::new(ctx, inputs.len() as u32)?;
    let raws: Vec<_> = accels.iter().map(|a| a.raw).collect();
    let primitives: u64 = ranges.iter().flatten().map(|r| u64::from(r.primitive_count)).sum();
    // A deadline that grows with the work: a batch of many meshes is many builds.
    let units = 1 + (inputs.len() / 256) as u32 + (primitives >> 20) as u32;
    one_shot.run_units(units, |device, cmd| {
        query.reset(cmd);
        // SAFETY: every buffer the infos name (boxes, meshes, storage, scratch) is alive until
        // run_units has waited; each build has its own scratch range.
        unsafe { ctx.accel.cmd_build_acceleration_structures(cmd, &infos, &range_refs) };
        written_for_reading(device, cmd);
        query.write(cmd, &raws);
        Ok(())
    })?;
    // The scratch and boxes are done with: freed before the compacted copies are made.
    drop((scratch, boxes));
    compacted(ctx, one_shot, accels, &query.read(inputs.len())?)
}

/// Each of `built` copied into a structure of its compacted size in `sizes`, in one
/// submission; the built ones are freed once the copies have completed. An equal size
/// (lavapipe reports the size as built) is copied too up to `COPIED_WHEN_EQUAL` bytes, so that
/// what every driver traces is a copy, in CI under validation as well; a larger one is kept as
/// built, as the copy would double it at the scene's peak memory for nothing.
fn compacted(
    ctx: &Arc<Context>,
    one_shot: &OneShot,
    built: Vec<AccelStruct>,
    sizes: &[u64],
) -> Result<Vec<AccelStruct>> {
    let copied =
        |a: &AccelStruct, size: u64| size != 0 && size <= a.bytes && !(size == a.bytes && size > COPIED_WHEN_EQUAL);
    let ty = vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL;
    let mut small = Vec::with_capacity(built.len());
    for (accel, &size) in built.iter().zip(sizes) {
        small.push(match copied(accel, size) {
            true => Some(allocate_sized(ctx, ty, size, "blas")?),
            false => None,
        });
    }
    if small.iter().any(Option::is_some) {
        one_shot.run_units(1 + (built.len() / 256) as u32, |device, cmd| {
            for (from, to) in built.iter().zip(&small) {
                if let Some(to) = to {
                    record_copy(ctx, cmd, from.raw, to.raw);
                }
            }
            written_for_reading(device, cmd);
            Ok(())
        })?;
    }
    Ok(built
        .into_iter()
        .zip(small)
        .map(|(built, small)| match small {
            Some(mut small) => {
                small.built_bytes = built.bytes;
                small
            }
            None => built,
        })
        .collect())
}

/// Largest BLAS copied when compaction would not make it smaller (see `compacted`).
const COPIED_WHEN_EQUAL: u64 = 16 << 20;

/// A barrier after acceleration structures are written: a later build, copy, query or trace
/// reads what was written.
fn written_for_reading(device: &ash::Device, cmd: vk::CommandBuffer) {
    let written =
        (vk::PipelineStageFlags::ACCELERATION_STRUCTURE_BUILD_KHR, vk::AccessFlags::ACCELERATION_STRUCTURE_WRITE_KHR);
    memory_barrier(device, cmd, written, built_for_reading());
}

/// VkAabbPositionsKHR as bytes.
fn aabb_bytes(b: &vk::AabbPositionsKHR) -> Vec<u8> {
    [b.min_x, b.min_y, b.min_z, b.max_x, b.max_y, b.max_z].iter().flat_map(|v| v.to_le_bytes()).collect()
}
