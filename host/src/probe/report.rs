//! Judging a probe run against the f64 reference: false hits and misses on the rays the
//! reference decides (ambiguous ones apart), and the error of t and of the normal.

use super::case::ProbeCase;
use crate::reference::scene::SceneVerdict;
use serde::Serialize;
use twinray_shared::bindings::NO_HIT;
use twinray_shared::layout::ProbeResult;

/// Median, 99th percentile and maximum.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Spread {
    pub median: f64,
    pub p99: f64,
    pub max: f64,
}

impl Spread {
    fn of(mut values: Vec<f64>) -> Spread {
        if values.is_empty() {
            return Spread::default();
        }
        values.sort_by(f64::total_cmp);
        let at = |q: f64| values[((values.len() - 1) as f64 * q).round() as usize];
        Spread { median: at(0.5), p99: at(0.99), max: at(1.0) }
    }
}

/// The accuracy of one probe run against the reference; serialised as `probe --json` prints it.
#[derive(Clone, Debug, Serialize)]
pub struct ProbeReport {
    pub case: String,
    pub set: String,
    pub device: String,
    pub rays: usize,
    /// Rays the reference decides (hit or miss); the others are within float noise of a
    /// boundary and are not counted as errors.
    pub decided: usize,
    pub ambiguous: usize,
    pub false_hits: usize,
    pub false_misses: usize,
    /// Both hit, but different objects.
    pub wrong_object: usize,
    /// |t - t_ref| / t_ref over rays both hit.
    pub relative_t_error: Spread,
    /// |t - t_ref| in f32 ULPs of t_ref, 99th percentile.
    pub ulp_error_p99: f64,
    /// Angle between the normals, radians, 99th percentile.
    pub normal_angle_error_p99: f64,
    /// Median GPU milliseconds of tracing every ray once, and per million rays.
    pub gpu_ms: Option<f64>,
    pub gpu_ms_per_million_rays: Option<f64>,
}

fn ulp(x: f32) -> f64 {
    let x = x.abs();
    f64::from(f32::from_bits(x.to_bits() + 1) - x)
}

/// Judges each result against the reference of its ray.
pub fn evaluate(
    case: &ProbeCase,
    results: &[ProbeResult],
    set: &str,
    device: &str,
    gpu_ms: Option<f64>,
) -> ProbeReport {
    let mut report = ProbeReport {
        case: case.file.name.clone(),
        set: set.into(),
        device: device.into(),
        rays: case.rays.len(),
        decided: 0,
        ambiguous: 0,
        false_hits: 0,
        false_misses: 0,
        wrong_object: 0,
        relative_t_error: Spread::default(),
        ulp_error_p99: 0.0,
        normal_angle_error_p99: 0.0,
        gpu_ms,
        gpu_ms_per_million_rays: gpu_ms.map(|ms| ms * 1e6 / case.rays.len().max(1) as f64),
    };
    let (mut rel, mut ulps, mut angles) = (Vec::new(), Vec::new(), Vec::new());
    for (ray, result) in case.reference_rays().iter().zip(results) {
        let o = ray.origin.truncate().as_dvec3();
        let d = ray.direction.truncate().as_dvec3();
        let verdict = case.reference.trace(o, d, f64::from(ray.origin.w), f64::from(ray.direction.w));
        let got_hit = result.ids.w != NO_HIT;
        match verdict {
            SceneVerdict::Ambiguous => {
                report.ambiguous += 1;
                continue;
            }
            SceneVerdict::Miss => report.false_hits += usize::from(got_hit),
            SceneVerdict::Hit { object, t, normal } => {
                if !got_hit {
                    report.false_misses += 1;
                } else if result.ids.x as usize != object {
                    report.wrong_object += 1;
                } else {
                    let got_t = f64::from(result.normal_t.w);
                    rel.push((got_t - t).abs() / t.abs().max(1e-30));
                    ulps.push((got_t - t).abs() / ulp(t as f32));
                    let n = result.normal_t.truncate().normalize().as_dvec3();
                    angles.push(n.dot(normal).clamp(-1.0, 1.0).acos());
                }
            }
        }
        report.decided += 1;
    }
    report.relative_t_error = Spread::of(rel);
    report.ulp_error_p99 = Spread::of(ulps).p99;
    report.normal_angle_error_p99 = Spread::of(angles).p99;
    report
}

impl ProbeReport {
    /// The text `twinray probe` prints.
    pub fn summary(&self) -> String {
        let t = &self.relative_t_error;
        let ms = match (self.gpu_ms, self.gpu_ms_per_million_rays) {
            (Some(ms), Some(per)) => format!("GPU {ms:.3} ms ({per:.3} ms per million rays)"),
            _ => "GPU time n/a".into(),
        };
        format!(
            "case {} with {} on {}: {} rays, {} decided, {} ambiguous\n  false hits {}, false misses {}, wrong object {}\n  relative t error: median {:.2e}, p99 {:.2e}, max {:.2e}; ULP error p99 {:.1}\n  normal angle error p99 {:.2e} rad\n  {ms}\n",
            self.case, self.set, self.device, self.rays, self.decided, self.ambiguous, self.false_hits,
            self.false_misses, self.wrong_object, t.median, t.p99, t.max, self.ulp_error_p99, self.normal_angle_error_p99
        )
    }
}
