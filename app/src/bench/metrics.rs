//! Error of an image against its reference, on display values (radiance clamped to [0, 1],
//! as the PNGs show it, but not quantised): RMSE over RGB, PSNR, and mean FLIP (NVIDIA's
//! perceptual difference, on the 8-bit images) with its error map.

use twinray_host::render::to_rgba8;

/// Image error of a render against a reference.
pub struct Errors {
    pub rmse: f64,
    /// 20 log10(1 / RMSE); infinite for identical images.
    pub psnr: f64,
    pub flip: f64,
    /// The FLIP error map in the magma colour map, RGBA8.
    pub flip_map_rgba: Vec<u8>,
}

/// RMSE, PSNR and mean FLIP of `test` against `reference` (linear RGB), with the FLIP map.
pub fn errors(test: &[[f32; 3]], reference: &[[f32; 3]], (width, height): (u32, u32)) -> Errors {
    let rmse = rmse(test, reference);
    let flip_map =
        nv_flip::flip(rgb8(reference, width, height), rgb8(test, width, height), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let flip = f64::from(nv_flip::FlipPool::from_image(&flip_map).mean());
    let colours = flip_map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    let flip_map_rgba = colours.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect();
    Errors { rmse, psnr: 20.0 * (1.0 / rmse).log10(), flip, flip_map_rgba }
}

/// Root mean square difference over RGB of display values.
pub fn rmse(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let display = |v: f32| f64::from(v.clamp(0.0, 1.0));
    let sum: f64 =
        a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |c| (display(p[c]) - display(q[c])).powi(2))).sum();
    (sum / (3 * a.len().max(1)) as f64).sqrt()
}

fn rgb8(linear: &[[f32; 3]], width: u32, height: u32) -> nv_flip::FlipImageRgb8 {
    let rgb: Vec<u8> = to_rgba8(linear).chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
    nv_flip::FlipImageRgb8::with_data(width, height, &rgb)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_images_have_no_error_and_noise_has_some() {
        let a: Vec<[f32; 3]> = (0..64).map(|i| [i as f32 / 64.0, 0.5, 1.5]).collect();
        let same = errors(&a, &a, (8, 8));
        assert_eq!((same.rmse, same.flip), (0.0, 0.0));
        assert!(same.psnr.is_infinite());
        let b: Vec<[f32; 3]> =
            a.iter().enumerate().map(|(i, p)| [p[0] + if i % 2 == 0 { 0.1 } else { -0.1 }, p[1], p[2]]).collect();
        let noisy = errors(&b, &a, (8, 8));
        // Channel 0 differs by 0.1 except where clamping at 0 cuts it: about 0.1 / sqrt(3).
        assert!((noisy.rmse - 0.1 / 3f64.sqrt()).abs() < 0.01, "{}", noisy.rmse);
        assert!(noisy.flip > 0.0 && noisy.flip_map_rgba.len() == 64 * 4);
    }
}
