//! twinray's reference against Mitsuba's passes, in linear radiance: the passes composed as
//! docs/shading-model.md says, the pixels that cannot agree masked, and the figures.

use serde::Serialize;

/// One Mitsuba pass, rendered twice with half the samples each: RGBA per pixel.
pub struct PassRender {
    pub name: String,
    pub halves: [Vec<[f32; 4]>; 2],
}

/// Mitsuba's image of a scene, composed: radiance, each half's (for the noise), coverage,
/// and the mask of pixels where a sample saw an emitter.
pub struct Composed {
    pub radiance: Vec<[f32; 3]>,
    pub halves: [Vec<[f32; 3]>; 2],
    pub coverage: Vec<f32>,
    pub masked: Vec<bool>,
}

/// Sum of the light passes plus the background where coverage is not full; the `emitters`
/// pass gives the mask and the coverage (where nothing is masked it covers what the light
/// passes cover).
pub fn compose(passes: &[PassRender], emitters: &PassRender, background: [f32; 3]) -> Composed {
    let n = emitters.halves[0].len();
    let coverage: Vec<f32> = (0..n).map(|i| (emitters.halves[0][i][3] + emitters.halves[1][i][3]) / 2.0).collect();
    let masked: Vec<bool> =
        (0..n).map(|i| emitters.halves.iter().any(|h| h[i][..3].iter().any(|&c| c > 0.0))).collect();
    let half = |k: usize| -> Vec<[f32; 3]> {
        (0..n)
            .map(|i| {
                let uncovered = 1.0 - emitters.halves[k][i][3];
                std::array::from_fn(|c| {
                    passes.iter().map(|p| p.halves[k][i][c]).sum::<f32>() + uncovered * background[c]
                })
            })
            .collect()
    };
    let halves = [half(0), half(1)];
    let radiance =
        halves[0].iter().zip(&halves[1]).map(|(a, b)| std::array::from_fn(|c| (a[c] + b[c]) / 2.0)).collect();
    Composed { radiance, halves, coverage, masked }
}

/// twinray against Mitsuba over the pixels not masked, in linear radiance.
#[derive(Clone, Debug, Serialize)]
pub struct Figures {
    pub pixels: u64,
    pub masked: u64,
    /// Root mean square difference over the compared pixels and channels.
    pub rmse: f64,
    /// Mean of Mitsuba's radiance over the compared pixels and channels.
    pub mean: f64,
    /// `rmse / mean`.
    pub relative_rmse: f64,
    pub max_abs_diff: f64,
    /// Root mean square of Mitsuba's own noise in its composed image: half the RMS
    /// difference of its two halves. A disagreement well above it is not noise.
    pub mitsuba_noise: f64,
    /// Pixels where one renderer's coverage exceeds the other's by more than a half: a shape
    /// drawn differently, not shading.
    pub coverage_mismatches: u64,
    /// Mean absolute coverage difference over the compared pixels.
    pub mean_coverage_diff: f64,
}

/// The figures of `twinray` (radiance, and 1 - coverage from the coverage render) against
/// `mitsuba`.
pub fn figures(twinray: &[[f32; 3]], twinray_uncovered: &[f32], mitsuba: &Composed) -> Figures {
    let (mut sum_sq, mut sum, mut noise_sq, mut max_abs, mut count) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0u64);
    let (mut mismatches, mut coverage_diff) = (0u64, 0.0f64);
    for i in (0..twinray.len()).filter(|&i| !mitsuba.masked[i]) {
        for (c, &t) in twinray[i].iter().enumerate() {
            let (t, m) = (f64::from(t), f64::from(mitsuba.radiance[i][c]));
            sum_sq += (t - m) * (t - m);
            sum += m;
            max_abs = max_abs.max((t - m).abs());
            let d = f64::from(mitsuba.halves[0][i][c]) - f64::from(mitsuba.halves[1][i][c]);
            noise_sq += d * d / 4.0;
        }
        let d = (1.0 - f64::from(twinray_uncovered[i])) - f64::from(mitsuba.coverage[i]);
        mismatches += u64::from(d.abs() > 0.5);
        coverage_diff += d.abs();
        count += 1;
    }
    let samples = (3 * count).max(1) as f64;
    let rmse = (sum_sq / samples).sqrt();
    let mean = sum / samples;
    Figures {
        pixels: twinray.len() as u64,
        masked: twinray.len() as u64 - count,
        rmse,
        mean,
        relative_rmse: if mean > 0.0 { rmse / mean } else { f64::INFINITY },
        max_abs_diff: max_abs,
        mitsuba_noise: (noise_sq / samples).sqrt(),
        coverage_mismatches: mismatches,
        mean_coverage_diff: coverage_diff / count.max(1) as f64,
    }
}

/// A difference image: masked pixels blue, the rest grey from twinray's image with the
/// absolute difference in red, full red at a tenth of the mean radiance.
pub fn diff_image(twinray: &[[f32; 3]], mitsuba: &Composed, mean: f64) -> Vec<u8> {
    let scale = if mean > 0.0 { 1.0 / (0.1 * mean) } else { 1.0 };
    let mut out = Vec::with_capacity(twinray.len() * 4);
    for (i, t) in twinray.iter().enumerate() {
        let rgb = if mitsuba.masked[i] {
            [40, 80, 255]
        } else {
            let d = (0..3).map(|c| (f64::from(t[c]) - f64::from(mitsuba.radiance[i][c])).abs()).fold(0.0, f64::max);
            let grey = (t.iter().sum::<f32>() / 3.0).clamp(0.0, 1.0) * 60.0;
            let red = ((d * scale).min(1.0) * 255.0) as u8;
            [red.max(grey as u8), grey as u8, grey as u8]
        };
        out.extend_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass(name: &str, a: Vec<[f32; 4]>, b: Vec<[f32; 4]>) -> PassRender {
        PassRender { name: name.into(), halves: [a, b] }
    }

    /// Two pixels: one half covered with radiance 0.4 from two lights, one seeing an emitter.
    #[test]
    fn composes_lights_background_and_mask() {
        let l0 = pass("light-0", vec![[0.1; 4], [0.0; 4]], vec![[0.3; 4], [0.0; 4]]);
        let l1 = pass("light-1", vec![[0.2; 4], [0.0; 4]], vec![[0.2; 4], [0.0; 4]]);
        let e = pass("emitters", vec![[0.0, 0.0, 0.0, 0.5], [1.0; 4]], vec![[0.0, 0.0, 0.0, 0.5], [1.0; 4]]);
        let m = compose(&[l0, l1], &e, [1.0, 0.0, 0.0]);
        assert_eq!(m.masked, vec![false, true]);
        assert_eq!(m.coverage[0], 0.5);
        assert!((m.radiance[0][0] - (0.4 + 0.5)).abs() < 1e-6, "{:?}", m.radiance[0]);
        assert!((m.radiance[0][1] - 0.4).abs() < 1e-6);
        let f = figures(&[[0.9, 0.4, 0.4], [5.0; 3]], &[0.5, 0.0], &m);
        assert_eq!((f.masked, f.coverage_mismatches), (1, 0));
        assert!(f.rmse < 1e-6, "{f:?}");
        // The halves differ by 0.2 in every channel: noise of the mean 0.1.
        assert!((f.mitsuba_noise - 0.1).abs() < 1e-6, "{f:?}");
        let g = figures(&[[1.0, 0.4, 0.4], [5.0; 3]], &[1.0, 0.0], &m);
        assert!((g.max_abs_diff - 0.1).abs() < 1e-6 && g.mean_coverage_diff == 0.5, "{g:?}");
    }
}
