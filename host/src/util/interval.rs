//! The uncertainty of a GPU-time ratio: a 95% confidence interval over placements, and the
//! verdict it supports in words.
//!
//! A placement is one independent making of every set's pipeline, SBT and descriptors (see
//! `render::placement`); each gives one median time per set. Within a placement the sets are
//! traced interleaved, so they share the GPU's clocks and the ratio of their medians is one
//! paired observation. Where the driver puts a set's code moves its time from placement to
//! placement, and the spread of the traces inside one placement says nothing about that: the
//! interval is a Student t interval on the logs of the placement ratios (a ratio is
//! symmetric on a log scale: a/b and b/a give mirrored intervals).

use serde::Serialize;

/// Confidence of every interval twinray reports.
pub const CONFIDENCE: f64 = 0.95;

/// The ratio of A's to B's time with its 95% confidence interval, over `placements` paired
/// observations.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RatioInterval {
    /// The geometric mean of the placement ratios.
    pub ratio: f64,
    /// The 95% interval's ends; equal to `ratio` when one placement gives no spread to go on.
    pub low: f64,
    pub high: f64,
    pub placements: usize,
    /// The standard deviation of the log ratios (0 with one placement).
    pub log_sd: f64,
}

impl RatioInterval {
    /// The interval of the ratios `a[p] / b[p]` of paired placement times; `None` when no pair
    /// has two positive finite times.
    pub fn paired(a: &[f64], b: &[f64]) -> Option<RatioInterval> {
        let ok = |x: f64| x.is_finite() && x > 0.0;
        let logs: Vec<f64> = a.iter().zip(b).filter(|(x, y)| ok(**x) && ok(**y)).map(|(x, y)| (x / y).ln()).collect();
        Self::of_logs(&logs)
    }

    /// The interval of the ratios whose natural logs are `logs`.
    pub fn of_logs(logs: &[f64]) -> Option<RatioInterval> {
        let n = logs.len();
        if n == 0 {
            return None;
        }
        let mean = logs.iter().sum::<f64>() / n as f64;
        let log_sd =
            if n > 1 { (logs.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt() } else { 0.0 };
        let half = if n > 1 { t_975(n - 1) * log_sd / (n as f64).sqrt() } else { 0.0 };
        Some(RatioInterval {
            ratio: mean.exp(),
            low: (mean - half).exp(),
            high: (mean + half).exp(),
            placements: n,
            log_sd,
        })
    }

    /// B's time over A's: every end inverted, the interval mirrored.
    pub fn inverse(&self) -> RatioInterval {
        RatioInterval { ratio: 1.0 / self.ratio, low: 1.0 / self.high, high: 1.0 / self.low, ..*self }
    }

    /// Whether there is an interval at all (two placements or more).
    pub fn has_interval(&self) -> bool {
        self.placements > 1
    }

    /// Whether the interval lies wholly above or below 1.
    pub fn resolved(&self) -> bool {
        self.has_interval() && (self.low > 1.0 || self.high < 1.0)
    }

    /// The interval's width as a fraction of the ratio: (high - low) / ratio.
    pub fn width(&self) -> f64 {
        (self.high - self.low) / self.ratio
    }

    /// The interval as percentages of difference: "95% CI -1.1% to +1.4%".
    pub fn ci_text(&self) -> String {
        format!("95% CI {:+.1}% to {:+.1}%", 100.0 * (self.low - 1.0), 100.0 * (self.high - 1.0))
    }

    /// The verdict in words, of `a` against `b`: "rust slower by 3.1% (95% CI 1.2% to 5.0%)",
    /// "rust faster by 2.0% (95% CI 0.4% to 3.6%)", or "no difference resolved (95% CI -1.1%
    /// to +1.4%)".
    pub fn verdict(&self, a: &str) -> String {
        if !self.has_interval() {
            return format!(
                "{a} {:+.1}% from one placement: no interval (time over 2 or more placements)",
                100.0 * (self.ratio - 1.0)
            );
        }
        let pct = |x: f64| 100.0 * (x - 1.0).abs();
        if self.low > 1.0 {
            format!("{a} slower by {:.1}% (95% CI {:.1}% to {:.1}%)", pct(self.ratio), pct(self.low), pct(self.high))
        } else if self.high < 1.0 {
            format!("{a} faster by {:.1}% (95% CI {:.1}% to {:.1}%)", pct(self.ratio), pct(self.high), pct(self.low))
        } else {
            format!("no difference resolved ({})", self.ci_text())
        }
    }
}

/// The 97.5% quantile of Student's t with `df` degrees of freedom (so a two-sided 95%
/// interval), from the table to 30 and the Cornish-Fisher expansion beyond (error under 1e-4).
pub fn t_975(df: usize) -> f64 {
    const TABLE: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
        2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042,
    ];
    match df {
        0 => f64::INFINITY,
        1..=30 => TABLE[df - 1],
        _ => {
            let (z, v) = (1.959_964f64, df as f64);
            z + (z.powi(3) + z) / (4.0 * v) + (5.0 * z.powi(5) + 16.0 * z.powi(3) + 3.0 * z) / (96.0 * v * v)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t_quantiles_match_the_tables() {
        assert_eq!(t_975(1), 12.706);
        assert_eq!(t_975(5), 2.571);
        assert!((t_975(40) - 2.021).abs() < 1e-3, "{}", t_975(40));
        assert!((t_975(120) - 1.980).abs() < 1e-3, "{}", t_975(120));
    }

    #[test]
    fn interval_of_known_logs() {
        // Logs 0.01, 0.03, 0.02: mean 0.02, sd 0.01, half width 4.303 * 0.01 / sqrt(3).
        let r = RatioInterval::of_logs(&[0.01, 0.03, 0.02]).unwrap();
        let half = 4.303 * 0.01 / 3f64.sqrt();
        assert!((r.ratio - 0.02f64.exp()).abs() < 1e-12);
        assert!((r.low - (0.02 - half).exp()).abs() < 1e-12 && (r.high - (0.02 + half).exp()).abs() < 1e-12);
        assert!(!r.resolved(), "the interval reaches below 1: {r:?}");
        assert!(r.verdict("a").starts_with("no difference resolved (95% CI -0.5% to +4.6%)"), "{}", r.verdict("a"));
    }

    #[test]
    fn verdicts_name_the_direction_and_mirror() {
        let a = [1.05, 1.06, 1.04, 1.05];
        let b = [1.0, 1.0, 1.0, 1.0];
        let slower = RatioInterval::paired(&a, &b).unwrap();
        assert!(slower.resolved() && slower.low > 1.0);
        assert!(slower.verdict("rust").starts_with("rust slower by 5.0% (95% CI"), "{}", slower.verdict("rust"));
        let faster = RatioInterval::paired(&b, &a).unwrap();
        let inverse = slower.inverse();
        assert!((inverse.ratio - faster.ratio).abs() < 1e-12 && (inverse.low - faster.low).abs() < 1e-12);
        assert!((faster.ratio * slower.ratio - 1.0).abs() < 1e-12 && (faster.low * slower.high - 1.0).abs() < 1e-12);
        assert!(faster.verdict("glsl").starts_with("glsl faster by 4.8%"), "{}", faster.verdict("glsl"));
    }

    #[test]
    fn one_placement_has_no_interval_and_bad_times_are_dropped() {
        let one = RatioInterval::paired(&[2.0, f64::NAN], &[1.0, 1.0]).unwrap();
        assert_eq!((one.placements, one.ratio, one.low, one.high), (1, 2.0, 2.0, 2.0));
        assert!(!one.resolved() && one.verdict("a").contains("no interval"));
        assert_eq!(RatioInterval::paired(&[0.0], &[1.0]), None);
    }
}
