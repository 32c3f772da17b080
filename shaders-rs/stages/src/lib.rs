//! twinray's Rust ray tracing stages. Each `pub fn` with a `#[spirv(...)]` stage attribute is an
//! entry point; a build (`twinray build`, or twinray's own for its built-in set) writes one SPIR-V
//! module per entry point.
//! Bindings are literals here because attributes need them; a test checks them against
//! `twinray_shared::bindings`. Ray generation shades; the hit stages only describe the surface.
#![cfg_attr(target_arch = "spirv", no_std)]
// `spirv_std::ray_query!` declares its ray query object with inline assembly, and material
// callables are called by an index known only at run time (hit.rs).
#![cfg_attr(target_arch = "spirv", feature(asm_experimental_arch))]

#[macro_use]
mod any_hit;
mod flags;
#[macro_use]
mod hit;
#[macro_use]
mod probe;
mod query;
mod texture;
mod trace;

use spirv_std::glam::{UVec2, UVec3, UVec4, Vec2, Vec3, Vec3Swizzles, Vec4, Vec4Swizzles};
use spirv_std::matrix::Matrix4x3;
use spirv_std::ray_tracing::AccelerationStructure;
use spirv_std::{spirv, Image, RuntimeArray};
use texture::Texture;
use trace::Lights;
use twinray_shared::bindings::{
    no_payload_word, CUTOUT_TEXTURE, EXPLAIN_SHADOW, HIT_IDS_PER_PIXEL, MISS_PRIMARY, NO_HIT, PROBE_NO_PAYLOAD,
    SHADOW_SAMPLER_STRATIFIED,
};
use twinray_shared::features::Features;
use twinray_shared::layout::{
    ExplainRay, ExplainResult, FrameUniform, HitPayload, Material, MaterialCall, ObjectData, Primitive, ProbeRay,
    ProbeResult, ShadowPayload, Vertex,
};
use twinray_shared::{camera, random, shading};

/// Where pixel `pixel_index`'s hit-id words start in the hit-id buffer.
fn hit_id_base(pixel_index: u32) -> usize {
    (HIT_IDS_PER_PIXEL * pixel_index) as usize
}

/// Defines a renderer's entry point `$name`, of stage `$stage` with built-ins `$builtins`: M x M
/// primary samples for pixel `$pixel` of an image of `$size`; each traced by `$primary` (given
/// `$payload` and the resources `$pres`) and shaded by `$shade` (given the resources `$sres`);
/// writes the mean colour and the ids of what the first sample hit. The payload is poisoned
/// before each trace; a ray whose hit or miss stage left it so is not shaded but counted in the
/// pixel's fourth hit-id word, and the pixel's colour is NaN. The entry also declares
/// `$params`, and runs `$setup` first. Names the caller's expressions use (`$frame`,
/// `$payload`) come from the caller, as macro hygiene asks.
///
/// Expands to one `#[spirv($stage)] pub fn $name(..)`: the built-ins, the renderers' common
/// bindings (TLAS, image, frame, lights, hit ids) and specialisation constants, then
/// `$params`; its body is `$setup` and the sample loop below. Used three times: `raygen`,
/// `raygen_query` and `render_compute`. twinray's guide, *Rust stages* shows stages as plain Rust.
macro_rules! renderer {
    (
        $(#[$doc:meta])* $name:ident, #[spirv($($stage:tt)*)], [$($builtins:tt)*], $frame:ident,
        [$($params:tt)*], [$($setup:tt)*], ($pixel:expr, $size:expr),
        $primary:path, $payload:ident, ($($pres:ident),*), $shade:path, ($($sres:expr),*)
    ) => {
$(#[$doc])*
#[spirv($($stage)*)]
#[allow(clippy::too_many_arguments)]
pub fn $name(
    $($builtins)*
    #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
    #[spirv(descriptor_set = 0, binding = 1)] image: &Image!(2D, format = rgba32f, sampled = false),
    #[spirv(uniform, descriptor_set = 0, binding = 2)] $frame: &FrameUniform,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] lights: &Lights,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 7)] hit_ids: &mut [u32],
    #[spirv(spec_constant(id = 0, default = 0))] shadows: u32,
    #[spirv(spec_constant(id = 1, default = 1))] samples_per_side: u32,
    #[spirv(spec_constant(id = 2, default = 0))] shadow_sampler: u32,
    // The scene's features (twinray_shared::features; 31 is `ALL`, for a host that sets none).
    #[spirv(spec_constant(id = 3, default = 31))] features: u32,
    #[spirv(spec_constant(id = 4, default = 0))] shaded_hits: u32,
    $($params)*
) {
    $($setup)*
    let features = Features::new(features);
    let pixel: UVec2 = $pixel;
    let size: UVec2 = $size;
    let pixel_index = pixel.y * size.x + pixel.x;
    // The hit ids are not checked against `hit_ids.len()` here, as the image is not against its
    // size: the host sizes both to the launch. A buffer length read before the first trace is
    // waited for by every thread as the launch starts; on NVIDIA's driver this check cost about
    // 5 µs a frame, up to 4% at 1 spp (twinray's nvidia-code bench report).
    let mut sum = Vec3::ZERO;
    let mut shadow_rays = 0;
    let mut no_payload = 0;
    // Bottom-tested: not `for` over ranges (trace.rs), nor `while`, whose condition rust-gpu
    // tests again after the body, alive across its traces. samples_per_side is at least 1.
    // Unlike the GLSL twin, one sample is looped over too: a branch around a copy of the body
    // made 1-spp frames up to 1.8% slower (twinray's nvidia-code bench report).
    let mut sy = 0;
    loop {
        let mut sx = 0;
        loop {
            let sample = sy * samples_per_side + sx;
            // Jitter only when there is more than one sample: the spine's pipeline paid nothing.
            let (r1, r2) = if samples_per_side > 1 {
                (random::random($frame.seed, pixel_index, sample, 0), random::random($frame.seed, pixel_index, sample, 1))
            } else {
                (0.5, 0.5)
            };
            let offset = camera::sample_offset(sx, sy, samples_per_side, r1, r2);
            let ray = camera::primary_ray($frame, pixel, size, offset);
            $payload.poison();
            $primary(tlas, ray, ($frame.reach.z, $frame.reach.x), features, $payload, $($pres),*);
            let unwritten = $payload.unwritten(true);
            if sample == 0 {
                let base = hit_id_base(pixel_index);
                // SAFETY: base + 1 < hit_ids.len(): the host sizes the buffer to the launch.
                unsafe {
                    *hit_ids.get_unchecked_mut(base) = if unwritten { NO_HIT } else { $payload.ids.x };
                    *hit_ids.get_unchecked_mut(base + 1) = if unwritten { NO_HIT } else { $payload.ids.y };
                }
            }
            if unwritten {
                no_payload = no_payload_word(no_payload, sample);
            } else {
                sum += $shade(
                    tlas,
                    $frame,
                    lights,
                    shadows != 0,
                    shadow_sampler == SHADOW_SAMPLER_STRATIFIED,
                    shaded_hits != 0,
                    features,
                    $payload,
                    $($sres,)*
                    pixel_index,
                    sample,
                    &mut shadow_rays,
                );
            }
            sx += 1;
            if sx >= samples_per_side {
                break;
            }
        }
        sy += 1;
        if sy >= samples_per_side {
            break;
        }
    }
    let base = hit_id_base(pixel_index);
    // SAFETY: base + 3 < hit_ids.len(): the host sizes the buffer to the launch.
    unsafe {
        *hit_ids.get_unchecked_mut(base + 2) = shadow_rays;
        *hit_ids.get_unchecked_mut(base + 3) = no_payload;
    }
    let color = if no_payload == 0 { sum / (samples_per_side * samples_per_side) as f32 } else { Vec3::splat(f32::NAN) };
    // SAFETY: the pixel lies inside the image, which the host sizes to the launch.
    unsafe { image.write(pixel, color.extend(1.0)) };
}
    };
}

renderer!(
    /// Ray generation with shadow rays traced by `traceRay` (the shadow miss stage clears the
    /// shadow payload).
    raygen,
    #[spirv(ray_generation)],
    [#[spirv(launch_id)] launch_id: UVec3, #[spirv(launch_size)] launch_size: UVec3,],
    frame,
    [
        #[spirv(ray_payload)] payload: &mut HitPayload,
        #[spirv(ray_payload)] shadow: &mut ShadowPayload,
    ],
    [],
    (launch_id.xy(), launch_size.xy()),
    trace::primary, payload, (), trace::shade, (shadow)
);
renderer!(
    /// Ray generation with shadow rays traced inline by ray queries (`VK_KHR_ray_query`): it
    /// intersects procedural primitives and decides cutouts itself.
    raygen_query,
    #[spirv(ray_generation)],
    [#[spirv(launch_id)] launch_id: UVec3, #[spirv(launch_size)] launch_size: UVec3,],
    frame,
    [
        #[spirv(ray_payload)] payload: &mut HitPayload,
        #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
        #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    ],
    [],
    (launch_id.xy(), launch_size.xy()),
    trace::primary, payload, (), trace::shade_query, ((objects, primitives, materials), (vertices, indices), textures)
);
renderer!(
    /// The compute renderer (`renderer = "compute"`): primary and shadow rays traced inline by
    /// ray queries, with no pipeline stages or SBT; one invocation per pixel, in workgroups of
    /// `RENDER_GROUP_SIZE` x `RENDER_GROUP_SIZE` (the literal is the attribute's).
    render_compute,
    #[spirv(compute(threads(8, 8)))],
    [#[spirv(global_invocation_id)] id: UVec3,],
    frame,
    [
        #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
        #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
        #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
    ],
    [
        // Whole workgroups cover the image; compute has no launch size, so the frame says it.
        if id.x >= frame.width || id.y >= frame.height {
            return;
        }
        let mut hit = HitPayload::NONE;
        let payload = &mut hit;
    ],
    (id.xy(), UVec2::new(frame.width, frame.height)),
    query::primary_query, payload, (frame, objects, primitives, materials, vertices, indices, textures),
    trace::shade_query, ((objects, primitives, materials), (vertices, indices), textures)
);

probe_stages!();

/// Primary rays that hit nothing see the background.
#[spirv(miss)]
pub fn miss(
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
) {
    payload.color = frame.background;
    payload.ids = UVec4::splat(NO_HIT);
}

/// A shadow ray that reaches its light.
#[spirv(miss)]
pub fn shadow_miss(#[spirv(incoming_ray_payload)] shadow: &mut ShadowPayload) {
    shadow.occluded = 0;
}

/// One intersection entry point per procedural shape: the shape of the AABB `primitive_id`,
/// from the shared routine `$intersect`, reporting the object-space normal as hit attribute.
/// The instance custom index is the object's first primitive, so the stage that runs most
/// often reads one buffer, as the spine's did.
///
/// Expands to one `#[spirv(intersection)] pub fn $name(..)` that reports `$intersect`'s hit
/// with hit kind `$hit_kind`, on the ray brought near the primitive's sphere `$bound`; twinray's guide, *Rust stages* shows the sphere's expanded.
macro_rules! procedural_intersection {
    ($name:ident, $intersect:path, $bound:expr, $hit_kind:expr) => {
        #[spirv(intersection)]
        #[allow(clippy::too_many_arguments)]
        pub fn $name(
            #[spirv(instance_custom_index)] primitive_base: u32,
            #[spirv(primitive_id)] primitive_id: u32,
            #[spirv(world_ray_origin)] world_origin: Vec3,
            #[spirv(world_ray_direction)] world_direction: Vec3,
            #[spirv(object_ray_origin)] object_origin: Vec3,
            #[spirv(object_ray_direction)] object_direction: Vec3,
            #[spirv(object_to_world)] object_to_world: Matrix4x3,
            #[spirv(world_to_object)] world_to_object: Matrix4x3,
            #[spirv(ray_tmin)] t_min: f32,
            #[spirv(ray_tmax)] t_max: f32,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
            #[spirv(hit_attribute)] normal: &mut Vec3,
            #[spirv(spec_constant(id = 3, default = 31))] features: u32,
        ) {
            // Not bounds-checked, as GLSL's twin is not: the index is the instance's custom index
            // (its object's first primitive) plus the AABB's index in its BLAS, both made by the
            // host from one primitive list. Timed over placements on the H100, the check costs
            // 0.4% on `cylinder` at 16 spp, nothing resolved elsewhere (the 3% once measured on
            // `showcase` was where the driver put the code: twinray's nvidia-code bench report, 0).
            // SAFETY: see above; every AABB of a BLAS has its primitive at that index.
            let p = unsafe { *primitives.get_unchecked((primitive_base + primitive_id) as usize) };
            // Where the scene has far instances, the object-space ray from the world ray,
            // brought near the primitive first, not the driver's, which loses precision there
            // (twinray_shared::transform).
            let ray = twinray_shared::transform::stage_ray(
                Features::new(features),
                (object_origin, object_direction),
                (world_origin, world_direction),
                (object_to_world.w_axis, world_to_object.to_mat3()),
                ($bound)(&p),
            );
            let (near, far) = ray.range(t_min, t_max);
            if let Some(hit) = $intersect(ray.origin, ray.direction, &p, near, far) {
                // Put back what was there if the hit is not taken (a cutout's any-hit stage
                // ignored it): lavapipe 25.0.7 hands closest-hit the attribute last written,
                // not the one reported with the committed hit (Vulkan-Docs #2681), so a hole
                // in front of a shape gave it this normal. Elsewhere the store is dead.
                let before = *normal;
                *normal = hit.normal;
                // SAFETY: called from an intersection stage, as OpReportIntersectionKHR requires.
                if !unsafe { spirv_std::arch::report_intersection(ray.world_t(hit.t, t_max), $hit_kind) } {
                    *normal = before;
                }
            }
        }
    };
}

/// The intersection entry points of every registered shape (`twinray_shared::shapes`): its
/// robust routine and, for shapes that keep one, the textbook variant, the probes' baseline.
///
/// Expands to one `procedural_intersection!` per registry line (two for a line with
/// `naive`), so that a shape's line in `twinray_shared::shapes` is all its stage needs.
macro_rules! intersection_stages {
    ($($shape:literal => $module:ident ($kind:literal): $entry:ident $(, naive $naive:ident)?;)*) => {
        $(
            procedural_intersection!(
                $entry,
                twinray_shared::shapes::$module::intersect,
                twinray_shared::shapes::$module::bound,
                $kind
            );
            // The textbook routine keeps the textbook transform: no bound, the ray not moved.
            $(procedural_intersection!(
                $naive,
                twinray_shared::shapes::$module::naive_intersect,
                |_: &Primitive| Vec4::ZERO,
                $kind
            );)?
        )*
    };
}

twinray_shared::procedural_shapes!(intersection_stages);

procedural_closest_hit!(
    /// Every procedural shape, the material's colour computed here.
    procedural_closest_hit, [], |m, p, n| shading::material_color(m, p, n)
);
procedural_closest_hit!(
    /// Every procedural shape of diffuse, emissive and cutout materials: their one colour, no branch on the
    /// kind (`hit_groups = "per-material"`).
    procedural_closest_hit_flat, [], |m, _p, _n| m.color_a.xyz()
);
procedural_closest_hit!(
    /// Every procedural shape, the material's colour from its callable.
    procedural_closest_hit_callable,
    [#[spirv(callable_data)] call: &mut MaterialCall,],
    |m, p, n| hit::call_material(call, m, p, n)
);

triangle_closest_hit!(
    /// Triangle meshes, the material's colour computed here.
    triangle_closest_hit, [], |m, p, n| shading::material_color(m, p, n)
);
triangle_closest_hit!(
    /// Triangle meshes of diffuse, emissive and cutout materials: their one colour, no branch on the
    /// kind (`hit_groups = "per-material"`).
    triangle_closest_hit_flat, [], |m, _p, _n| m.color_a.xyz()
);
triangle_closest_hit!(
    /// Triangle meshes, the material's colour from its callable.
    triangle_closest_hit_callable,
    [#[spirv(callable_data)] call: &mut MaterialCall,],
    |m, p, n| hit::call_material(call, m, p, n)
);

/// Diffuse, emissive and cutout materials: their one colour.
#[spirv(callable)]
pub fn flat_material(#[spirv(incoming_callable_data)] call: &mut MaterialCall) {
    call.color = call.material.color_a;
}

/// Checker materials: the pattern at the point.
#[spirv(callable)]
pub fn checker_material(#[spirv(incoming_callable_data)] call: &mut MaterialCall) {
    call.color = shading::material_color(&call.material, call.point.xyz(), call.normal.xyz()).extend(1.0);
}

any_hit_stages!();
