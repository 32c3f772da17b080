//! The material `{material}`, to make your own: as written, two colours blended in waves along
//! the object's own y axis, one wave per `period`. A material gives the colour of a surface at
//! a point (its albedo); twinray's closest-hit stages light it as any other.
//!
//! Its keys reach the GPU as the two vectors of `Material` its callable reads: here `color_a`
//! holds the first colour and the period, `color_b` the second colour (`MATERIAL.parameters`
//! fills them).

#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;
use twinray_shared::glam::{Vec3, Vec4Swizzles};
use twinray_shared::layout::Material;

/// The colour of material `m` at an object-space `point` with object-space `normal` (any
/// length), as its callable stage computes it.
pub fn color(m: &Material, point: Vec3, _normal: Vec3) -> Vec3 {
    let (a, b, period) = (m.color_a.xyz(), m.color_b.xyz(), m.color_a.w);
    let s = 0.5 + 0.5 * (point.y * (core::f32::consts::TAU / period)).cos();
    a + (b - a) * s
}

#[cfg(not(target_arch = "spirv"))]
pub use cpu::MATERIAL;

/// What twinray's host reads, on the CPU only.
#[cfg(not(target_arch = "spirv"))]
mod cpu {
    use twinray_shared::custom::CustomMaterial;
    use twinray_shared::glam::{Vec3, Vec4};
    use twinray_shared::shapes::spec::{Param, ParamType, Values};

    /// The material as scenes name it (`kind = "{material}"`).
    pub const MATERIAL: CustomMaterial = CustomMaterial {
        name: "{material}",
        about: "two colours in waves along y: `color_a`, `color_b`, a wave per `period`",
        params: &[
            Param::finite("color_a", ParamType::Triple),
            Param::finite("color_b", ParamType::Triple),
            Param::positive("period"),
        ],
        check,
        parameters,
    };

    /// Colours are albedos: none below 0.
    fn check(keys: &Values) -> Result<(), String> {
        for key in ["color_a", "color_b"] {
            if keys.triple(key).iter().any(|c| *c < 0.0) {
                return Err(format!("{key}: a colour has no part below 0 (got {:?})", keys.triple(key)));
            }
        }
        Ok(())
    }

    /// The two vectors the callable reads: `color_a` = (first colour, period), `color_b` =
    /// (second colour, 0).
    fn parameters(keys: &Values) -> [Vec4; 2] {
        let a = Vec3::from(keys.triple("color_a")).extend(keys.number("period"));
        [a, Vec3::from(keys.triple("color_b")).extend(0.0)]
    }
}
