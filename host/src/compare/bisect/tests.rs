//! Bisecting a made-up subject whose image and time depend on chosen modules in known ways.

use super::*;
use crate::sets::Language;

/// Four "pixels"; each module from GLSL adds its term to them and its cost to the time.
struct Fake {
    /// (module, added to every pixel when from GLSL).
    image: Vec<(&'static str, f64)>,
    /// Added to pixel 0 only when every listed module is from GLSL.
    joint: Vec<&'static str>,
    cost: Vec<(&'static str, f64)>,
    runs: usize,
    calls: usize,
}

fn fake() -> Fake {
    Fake { image: Vec::new(), joint: Vec::new(), cost: Vec::new(), runs: 5, calls: 0 }
}

const USED: [&str; 6] =
    ["raygen", "miss", "shadow_miss", "sphere_intersection", "box_intersection", "procedural_closest_hit"];

fn glsl(set: &ShaderSet, module: &str) -> bool {
    set.same_module(&ShaderSet::uniform(Language::Glsl), module)
}

impl Subject for Fake {
    type Data = Vec<f64>;

    fn name(&self) -> String {
        "fake".into()
    }

    fn device(&self) -> String {
        "none".into()
    }

    fn items(&self) -> &'static str {
        "values"
    }

    fn modules(&self) -> Vec<&'static str> {
        USED.to_vec()
    }

    fn run(&mut self, sets: &[ShaderSet]) -> Result<Vec<Run<Vec<f64>>>> {
        self.calls += 1;
        Ok(sets
            .iter()
            .map(|set| {
                let shift: f64 = self.image.iter().filter(|(m, _)| glsl(set, m)).map(|(_, d)| d).sum();
                let mut data = vec![shift; 4];
                if !self.joint.is_empty() && self.joint.iter().all(|m| glsl(set, m)) {
                    data[0] += 1.0;
                }
                let ms: f64 = 10.0 + self.cost.iter().filter(|(m, _)| glsl(set, m)).map(|(_, c)| c).sum::<f64>();
                let placement_ms = (0..self.runs).map(|i| ms + 0.001 * i as f64).collect();
                Run { data, placement_ms, raygen_stack_bytes: 0, written: Default::default() }
            })
            .collect())
    }

    fn gap(&self, a: &Vec<f64>, b: &Vec<f64>) -> Gap {
        let sq: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
        let mismatches = a.iter().zip(b).filter(|(x, y)| (*x - *y).abs() > 0.5).count() as u64;
        Gap { rmse: (sq / a.len() as f64).sqrt(), over: mismatches, mismatches, within_tolerance: sq < 1e-6 }
    }
}

fn run(subject: &mut Fake) -> BisectReport {
    bisect(subject, &ShaderSet::uniform(Language::Rust), &ShaderSet::uniform(Language::Glsl)).unwrap()
}

#[test]
fn a_difference_made_by_one_stage_is_pinned_on_it() {
    let mut subject = Fake { image: vec![("shadow_miss", 0.25)], ..fake() };
    let report = run(&mut subject);
    assert_eq!(report.stages.len(), 4, "every stage differs between rust and glsl");
    assert_eq!(report.image.explained_by, ["miss", "miss: shadow_miss"], "the stage, then its module");
    let miss = report.stages.iter().find(|r| r.unit == "miss").unwrap();
    assert_eq!(miss.rmse_share, Some([1.0, 1.0]));
    assert!(report.stages.iter().filter(|r| r.unit != "miss").all(|r| r.rmse_share == Some([0.0, 0.0])));
    assert_eq!(report.time.difference, "within noise");
    assert!(report.pinned && report.pairs.is_empty(), "no pairs when one stage explains it");
    // The miss stage has two modules: each is tried alone.
    assert_eq!(report.modules.iter().map(|r| r.unit.as_str()).collect::<Vec<_>>(), ["miss: miss", "miss: shadow_miss"]);
}

#[test]
fn time_is_pinned_on_the_stage_that_costs_it_and_images_and_times_apart() {
    let mut subject =
        Fake { image: vec![("box_intersection", 0.5)], cost: vec![("raygen", 1.0), ("miss", 0.05)], ..fake() };
    let report = run(&mut subject);
    assert_eq!(report.time.difference, "significant");
    assert_eq!(report.time.explained_by, ["raygen"]);
    assert_eq!(report.image.explained_by, ["intersection", "intersection: box_intersection"]);
    let raygen = report.stages.iter().find(|r| r.unit == "raygen").unwrap();
    let [forward, reverse] = raygen.time_share.unwrap();
    assert!((forward - 1.0 / 1.05).abs() < 1e-2 && (reverse - 1.0 / 1.05).abs() < 1e-2, "{forward} {reverse}");
    assert!((raygen.ratio_forward.unwrap().ratio - 1.1).abs() < 1e-3);
    assert!(report.pinned);
}

#[test]
fn a_difference_two_stages_make_together_is_pinned_on_the_pair() {
    let mut subject = Fake { joint: vec!["raygen", "procedural_closest_hit"], ..fake() };
    let report = run(&mut subject);
    assert!(report.stages.iter().all(|r| !r.explains_image));
    assert_eq!(report.image.explained_by, ["raygen+closest_hit"]);
    assert_eq!(report.pairs.len(), 6);
    assert!(report.pinned);
}

#[test]
fn time_needs_two_placements_and_no_difference_needs_no_pinning() {
    // One placement: a ratio but no interval to judge it by.
    let mut subject = Fake { cost: vec![("raygen", 1.0)], runs: 1, ..fake() };
    let report = run(&mut subject);
    assert!(report.time.difference.starts_with("not judged"), "{}", report.time.difference);
    assert_eq!(report.image.difference, "none");
    assert!(report.pinned && report.pairs.is_empty() && report.modules.is_empty());
    assert!(report.summary().contains("no difference to pin (none)"), "{}", report.summary());
}

#[test]
fn identical_sets_have_no_units() {
    let rust = ShaderSet::uniform(Language::Rust);
    let mut subject = fake();
    let report = bisect(&mut subject, &rust, &rust).unwrap();
    assert!(report.stages.is_empty());
    assert_eq!(report.same_modules.len(), USED.len());
    assert_eq!(subject.calls, 1);
}

#[test]
fn a_difference_within_tolerance_is_bisected_but_need_not_be_pinned() {
    // Rounding-level: bisected and named, but not required.
    let mut subject = Fake { image: vec![("miss", 1e-4)], ..fake() };
    let report = run(&mut subject);
    assert_eq!(report.image.difference, "within tolerance");
    assert_eq!(report.image.explained_by, ["miss", "miss: miss"], "still named");
    assert!(report.pinned && report.pairs.is_empty(), "no pairs are tried for it");
    assert!(
        report.summary().contains("no difference to pin (within tolerance); carried by miss, miss: miss"),
        "{}",
        report.summary()
    );
}
