//! Origins of secondary rays: Wächter and Binder, "A Fast and Robust Method for Avoiding
//! Self-Intersection" (Ray Tracing Gems ch. 6). The point moves along the geometric normal by a
//! number of ULPs that scales with its magnitude, so shadow rays start off the surface at any
//! distance from the origin and can use t_min = 0 (see NUMERICS.md).

use glam::Vec3;

/// Below this magnitude a coordinate moves by a fixed step instead of by ULPs.
pub const OFFSET_ORIGIN: f32 = 1.0 / 32.0;
/// The fixed step near the origin, times the normal.
pub const OFFSET_FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// ULPs to move, times the normal.
pub const OFFSET_INT_SCALE: f32 = 256.0;

fn offset_component(p: f32, n: f32) -> f32 {
    if p.abs() < OFFSET_ORIGIN {
        return p + OFFSET_FLOAT_SCALE * n;
    }
    let of = (OFFSET_INT_SCALE * n) as i32;
    let step = if p < 0.0 { -of } else { of };
    f32::from_bits((p.to_bits() as i32).wrapping_add(step) as u32)
}

/// `p` moved off the surface along `n` (unit, pointing to the side the new ray leaves from).
pub fn offset_ray(p: Vec3, n: Vec3) -> Vec3 {
    Vec3::new(offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moves_to_the_normal_side_at_any_magnitude() {
        for scale in [0.01f32, 1.0, 100.0, 2.0e4, 1.0e6] {
            let p = Vec3::new(scale, -scale, scale * 0.5);
            let n = Vec3::new(1.0, 1.0, -1.0).normalize();
            let q = offset_ray(p, n);
            assert!((q - p).dot(n) > 0.0, "no progress along the normal at {scale}");
            assert!((q - p).length() < scale.max(1.0) * 1e-3, "moved too far at {scale}");
        }
    }
}
