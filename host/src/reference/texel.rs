//! A texture's alpha in the f64 reference, read as the stages read a cutout's texture: at
//! level 0 (`textureGrad` with zero gradients selects the magnification filter), through the
//! sampler's wrap modes, nearest or bilinear, with how far a device's sampling may land from
//! the exact value.

use crate::scene::texture::{Filter, SamplerDesc, TextureImage, Wrap};
use glam::DVec2;

/// Fraction bits of a device's bilinear weights that the reference allows for: 8, as lavapipe
/// and NVIDIA report (`subTexelPrecisionBits`), and as filtering in 8-bit fixed point rounds.
const WEIGHT_BITS: i32 = 8;

/// One texture's alpha channel and how it is sampled.
#[derive(Clone, Debug, PartialEq)]
pub struct RefTexture {
    width: usize,
    height: usize,
    /// Row-major texel alphas, in [0, 1] (unorm 8-bit, alike in sRGB and linear formats).
    alpha: Vec<f64>,
    wrap: [Wrap; 2],
    linear: bool,
}

impl RefTexture {
    pub fn of(image: &TextureImage, sampler: &SamplerDesc) -> RefTexture {
        RefTexture {
            width: image.width.max(1) as usize,
            height: image.height.max(1) as usize,
            alpha: image.rgba.chunks_exact(4).map(|t| f64::from(t[3]) / 255.0).collect(),
            wrap: sampler.wrap,
            linear: sampler.mag == Filter::Linear,
        }
    }

    /// The alpha at texture coordinates `uv`, and how far from it a device's sample may be:
    /// none for nearest (a texel's value), and for bilinear the weights' rounding
    /// (`WEIGHT_BITS`) over the four texels' spread plus one 8-bit step of the result.
    pub fn alpha(&self, uv: DVec2) -> (f64, f64) {
        let texel = |i: i64, j: i64| {
            let x = wrap(i, self.width, self.wrap[0]);
            let y = wrap(j, self.height, self.wrap[1]);
            self.alpha.get(y * self.width + x).copied().unwrap_or(1.0)
        };
        let at = uv * DVec2::new(self.width as f64, self.height as f64);
        if !self.linear {
            return (texel(at.x.floor() as i64, at.y.floor() as i64), 0.0);
        }
        let corner = at - DVec2::splat(0.5);
        let (i, j) = (corner.x.floor() as i64, corner.y.floor() as i64);
        let w = corner - corner.floor();
        let four = [texel(i, j), texel(i + 1, j), texel(i, j + 1), texel(i + 1, j + 1)];
        let top = four[0] + (four[1] - four[0]) * w.x;
        let bottom = four[2] + (four[3] - four[2]) * w.x;
        let value = top + (bottom - top) * w.y;
        let spread = four.iter().copied().fold(f64::MIN, f64::max) - four.iter().copied().fold(f64::MAX, f64::min);
        let error = if spread > 0.0 { spread * 2f64.powi(-WEIGHT_BITS) + 1.0 / 255.0 } else { 0.0 };
        (value, error)
    }
}

/// Texel index `i` of a row or column of `size` texels under `mode` (Vulkan's address modes).
fn wrap(i: i64, size: usize, mode: Wrap) -> usize {
    let n = size as i64;
    let k = match mode {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::Clamp => i.clamp(0, n - 1),
        Wrap::Mirror => {
            let t = i.rem_euclid(2 * n);
            if t < n {
                t
            } else {
                2 * n - 1 - t
            }
        }
    };
    k as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4 x 1 texture of alphas 0, 85, 170, 255 (0, 1/3, 2/3, 1).
    fn ramp(mag: Filter, wrap: Wrap) -> RefTexture {
        let rgba = [0u8, 85, 170, 255].iter().flat_map(|&a| [9, 9, 9, a]).collect();
        let image = TextureImage { name: "ramp".into(), width: 4, height: 1, rgba, srgb: true };
        RefTexture::of(&image, &SamplerDesc { wrap: [wrap; 2], mag, ..SamplerDesc::DEFAULT })
    }

    #[test]
    fn nearest_reads_the_texel_under_the_point_through_the_wrap_mode() {
        let t = ramp(Filter::Nearest, Wrap::Repeat);
        assert_eq!(t.alpha(DVec2::new(0.3, 0.5)), (1.0 / 3.0, 0.0));
        assert_eq!(t.alpha(DVec2::new(1.3, 0.5)), (1.0 / 3.0, 0.0), "repeat");
        assert_eq!(ramp(Filter::Nearest, Wrap::Clamp).alpha(DVec2::new(1.3, 0.5)).0, 1.0, "clamp");
        assert_eq!(ramp(Filter::Nearest, Wrap::Mirror).alpha(DVec2::new(1.3, 0.5)).0, 2.0 / 3.0, "mirror");
    }

    #[test]
    fn bilinear_weighs_the_two_nearest_texel_centres_and_allows_for_rounding() {
        let t = ramp(Filter::Linear, Wrap::Clamp);
        // Halfway between the centres of texels 1 and 2 (at 0.375 and 0.625).
        let (value, error) = t.alpha(DVec2::new(0.5, 0.5));
        assert!((value - 0.5).abs() < 1e-12, "{value}");
        assert!((error - (1.0 / 3.0 / 256.0 + 1.0 / 255.0)).abs() < 1e-12, "{error}");
        // At a texel's centre its own value; where all four agree, no rounding.
        assert!((t.alpha(DVec2::new(0.375, 0.5)).0 - 1.0 / 3.0).abs() < 1e-12);
        assert_eq!(t.alpha(DVec2::new(0.999, 0.5)), (1.0, 0.0), "clamped: texel 3 four times");
    }
}
