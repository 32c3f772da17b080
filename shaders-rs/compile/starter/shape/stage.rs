//! The intersection stage of the shape `{shape}` (`{shared}::{shape}`): its routine on the
//! object-space ray the driver hands the stage, reporting the object-space normal as the hit
//! attribute that twinray's closest-hit stages read.

use spirv_std::glam::Vec3;
use spirv_std::spirv;
use twinray_shared::layout::Primitive;
use {shared}::{shape}::{intersect, HIT_KIND};

#[spirv(intersection)]
#[allow(clippy::too_many_arguments)]
pub fn {shape}_intersection(
    // An object's first primitive is its instance's custom index; this box is `primitive_id` more.
    #[spirv(instance_custom_index)] primitive_base: u32,
    #[spirv(primitive_id)] primitive_id: u32,
    #[spirv(object_ray_origin)] origin: Vec3,
    #[spirv(object_ray_direction)] direction: Vec3,
    #[spirv(ray_tmin)] t_min: f32,
    #[spirv(ray_tmax)] t_max: f32,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
    #[spirv(hit_attribute)] normal: &mut Vec3,
) {
    let p = primitives[(primitive_base + primitive_id) as usize];
    if let Some(hit) = intersect(origin, direction, &p, t_min, t_max) {
        // Put back what was there if the hit is not taken: some drivers hand the closest hit
        // the attribute last written, not the one reported with the hit kept.
        let before = *normal;
        *normal = hit.normal;
        // SAFETY: called from an intersection stage, as OpReportIntersectionKHR requires.
        if !unsafe { spirv_std::arch::report_intersection(hit.t, HIT_KIND) } {
            *normal = before;
        }
    }
}
