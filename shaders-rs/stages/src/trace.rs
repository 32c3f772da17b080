//! Tracing from ray generation: primary rays, and shading with shadow rays to every light,
//! traced with `traceRay` or inline with ray queries.
//! Free functions rather than a struct of references: rust-gpu cannot keep references in a
//! struct (logical SPIR-V has no pointers to pointers).

use crate::flags::PRIMARY_RAY_FLAGS;
use crate::query::{visible_query, Scene};
use crate::render::Options;
use crate::texture::Texture;
use spirv_std::glam::{Vec3, Vec4Swizzles};
use spirv_std::ray_tracing::{AccelerationStructure, RayFlags};
use spirv_std::RuntimeArray;
use twinray_shared::bindings::{
    LIGHT_RECT, MASK_OCCLUDER, MATERIAL_EMISSIVE, MATERIAL_SHADED, MAX_LIGHTS, MISS_PRIMARY, MISS_SHADOW, NO_HIT,
};
use twinray_shared::camera::Ray;
use twinray_shared::features::{Features, AREA_LIGHTS, EMISSION, LIGHT_CONES};
use twinray_shared::layout::{FrameUniform, HitPayload, Light, ShadowPayload};
use twinray_shared::{lighting, offset, random};

/// The lights buffer, which the host fills to `MAX_LIGHTS`: a runtime array, not a slice,
/// whose length rust-gpu would read at the entry point, where every thread waits for it
/// before its first trace.
pub type Lights = RuntimeArray<Light>;

/// Traces a primary ray over `(t_min, t_max)` (the frame's near and far reach) into `payload`. No ray is traced `OPAQUE`: instances
/// say whether they are (cutouts are not, and their any-hit stage runs), so scenes without
/// cutouts run none.
/// `_features` are the scene's: the hit stages read their own.
pub fn primary(
    tlas: &AccelerationStructure,
    ray: Ray,
    (t_min, t_max): (f32, f32),
    _features: Features,
    payload: &mut HitPayload,
) {
    // SAFETY: the TLAS is bound and built; the payload is this stage's ray_payload variable.
    unsafe {
        tlas.trace_ray(
            PRIMARY_RAY_FLAGS,
            0xff,
            0,
            0,
            MISS_PRIMARY as i32,
            ray.origin,
            t_min,
            ray.direction,
            t_max,
            payload,
        );
    }
}

/// Defines `$name`, the colour seen along a primary ray: the background, an emitter's radiance,
/// or the albedo times the light arriving from every light (with shadows where lights cast
/// them, and `shadows`, a specialisation constant, is on) plus the radiance the surface emits
/// (`HitPayload::emission`). Rect lights' shadow samples are
/// `stratified` (one per cell of an N x N grid) or independent. Adds the shadow rays it traces
/// to `shadow_rays`. Shadow rays go to `$visible` with the resources `$res`: one body for
/// `traceRay` and ray-query shadows (a closure would be a struct of references, which rust-gpu
/// cannot build).
///
/// Expands to one plain `pub fn $name(..) -> Vec3` (not an entry point) whose shadow rays call
/// `$visible(.., $res)`; invoked twice, as `shade` and `shade_query`.
macro_rules! shading {
    ($(#[$doc:meta])* $name:ident, $visible:ident, $($res:ident: $ty:ty),*) => {
$(#[$doc])*
#[allow(clippy::too_many_arguments)]
pub fn $name(
    tlas: &AccelerationStructure,
    (frame, lights): (&FrameUniform, &Lights),
    options: Options,
    hit: &HitPayload,
    $($res: $ty,)*
    (pixel, sample): (u32, u32),
    shadow_rays: &mut u32,
) -> Vec3 {
    let Options { shadows, stratified, shaded_hits, features, .. } = options;
    let emission = features.has::<EMISSION>();
    // A miss, an emitter, or a surface its closest hit shaded (only where the set's may:
    // `shaded_hits`, a specialisation constant): the colour is the radiance.
    let shaded = shaded_hits & (hit.ids.z == MATERIAL_SHADED);
    if hit.ids.w == NO_HIT || (shaded | (emission & (hit.ids.z == MATERIAL_EMISSIVE))) {
        return hit.color.xyz();
    }
    // Without area lights every light takes one sample at a fixed place.
    let area = features.has::<AREA_LIGHTS>();
    let cones = features.has::<LIGHT_CONES>();
    let point = hit.position.xyz();
    let normal = hit.shading_normal.xyz();
    let origin = offset::offset_hit(point, hit.geometric_normal.xyz(), hit.position.w);
    let mut light_sum = Vec3::ZERO;
    // Counted `while` loops and nested `if`s, not `for` over ranges and `&&`: rust-gpu lowers
    // range iterators to struct and Option phis with undefined values, and NVIDIA's driver
    // computed this loop wrongly from that form (a light went missing) while lavapipe did not.
    let mut l = 0;
    while l < frame.light_count {
        // No indexing panic path in here either: rust-gpu turns it into a branch from an inner
        // loop to an outer loop's merge, which NVIDIA's driver also miscompiled. `get` is no way
        // out: rust-gpu cannot build Option<&T>.
        let index = l as usize;
        if index >= MAX_LIGHTS as usize {
            break;
        }
        // SAFETY: index < MAX_LIGHTS, the buffer's length (the host fills it), checked just
        // above. A reference, not a copy: the copy's fields were all live across every shadow
        // ray (`twinray inspect`).
        let light = unsafe { lights.index(index) };
        let n = if area { lighting::samples_per_side(light) } else { 1 };
        let casts = shadows && light.shadows != 0;
        // One loop over the n x n cells, stepping i and then j, where the GLSL twin nests a j
        // and an i loop: same samples in the same order. Each loop rust-gpu emits is a loop
        // and a selection construct with phis of undefined values on the way out: one loop
        // fewer made this stage about 1.3% faster at 16 spp on an H200. A single index split
        // by % and / kept 32 bytes less stack across each trace call, but was slower.
        let (mut i, mut j) = (0, 0);
        while j < n {
            let dimension = 2 + 2 * (l * 64 + j * n + i);
            // Only area lights are sampled at random positions (`&`: no branch for `&&`).
            let (r1, r2) = if area & (light.kind == LIGHT_RECT) {
                (
                    random::random(frame.seed, pixel, sample, dimension),
                    random::random(frame.seed, pixel, sample, dimension + 1),
                )
            } else {
                (0.0, 0.0)
            };
            // Independent samples: cell (0, 0) stretched over the whole light.
            let nf = n as f32;
            let (si, sj, r1, r2) = if stratified { (i, j, r1, r2) } else { (0, 0, r1 * nf, r2 * nf) };
            let s = lighting::sample(light, point, (si, sj), (r1, r2), frame.reach.y, cones);
            let cosine = normal.dot(s.direction);
            if cosine > 0.0 {
                let lit = if casts {
                    *shadow_rays += 1;
                    $visible(tlas, origin, s.direction, s.distance, features, $($res),*)
                } else {
                    true
                };
                if lit {
                    light_sum += s.irradiance * cosine;
                }
            }
            i += 1;
            if i == n {
                i = 0;
                j += 1;
            }
        }
        l += 1;
    }
    let lit = hit.color.xyz() * light_sum;
    if emission {
        lit + hit.emission()
    } else {
        lit
    }
}
    };
}

shading!(
    /// Shading with `traceRay` shadows.
    shade, visible, shadow: &mut ShadowPayload
);
shading!(
    /// Shading with shadows traced inline by ray queries (`shadow_method = "query"`), which
    /// read the scene's buffers and textures.
    shade_query, visible_query, scene: Scene, textures: &RuntimeArray<Texture>
);

/// Whether nothing that casts shadows lies between `origin` and `distance` along `direction`.
/// `_features` are the scene's: the any-hit stages read their own.
pub fn visible(
    tlas: &AccelerationStructure,
    origin: Vec3,
    direction: Vec3,
    distance: f32,
    _features: Features,
    shadow: &mut ShadowPayload,
) -> bool {
    shadow.occluded = 1;
    let flags = RayFlags::TERMINATE_ON_FIRST_HIT | RayFlags::SKIP_CLOSEST_HIT_SHADER;
    // SAFETY: as in `primary`; the shadow miss shader is in the SBT whenever shadows are on.
    unsafe {
        tlas.trace_ray(flags, MASK_OCCLUDER as i32, 0, 0, MISS_SHADOW as i32, origin, 0.0, direction, distance, shadow);
    }
    shadow.occluded == 0
}
