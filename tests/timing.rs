//! GPU-time ratios and their intervals over placements, on lavapipe: a set against a salted copy
//! of itself (the null control) is not resolved; a ray generation stage that does the work
//! twice is resolved as slower, its interval excluding 1.

use twinray_host::compare::compare_sets;
use twinray_host::{RenderOptions, Scene, ShaderSet};
use twinray_tests::{set, validated_context};

fn sphere() -> Scene {
    Scene::load(Some("sphere")).unwrap_or_else(|e| panic!("sphere: {e}"))
}

/// The tests of this file time lavapipe, which runs on the CPU: run side by side (cargo runs a
/// file's tests in parallel) each steals the other's cores mid-trace. In one CI run on 2 cores
/// that widened the planted variant's interval to 0.58-0.86 (log sd 0.19); one at a time, it
/// stays well under 0.8. They take turns on this lock.
static LAVAPIPE: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn opts() -> RenderOptions {
    RenderOptions { width: 96, height: 72, warmup: 1, runs: 5, placements: 6, first_placement: 0 }
}

/// A 95% interval misses a true ratio of 1 in one run out of 20, by design: a second run is
/// allowed, so that the test fails by chance about once in 400 runs, not once in 20.
#[test]
fn a_set_against_its_salted_copy_is_not_resolved() {
    let _turn = LAVAPIPE.lock().unwrap_or_else(|e| e.into_inner());
    let ctx = validated_context();
    let glsl = set("glsl");
    let mut verdicts = Vec::new();
    for _ in 0..2 {
        let c = compare_sets(&ctx, &sphere(), (&glsl, &glsl), &opts(), None).unwrap();
        let r = &c.report;
        assert!(r.null_control && r.set_b == "glsl (copy 1)", "{} / {}", r.set_a, r.set_b);
        assert!(r.pass, "a copy renders what the set renders: {:?}", r.failures);
        let timing = r.timing.clone().expect("lavapipe times");
        assert_eq!(timing.interval.placements, 6, "one median per timed placement, the warm-up dropped");
        assert_eq!(r.placements_a.median_ms.len(), 6);
        if !timing.interval.resolved() {
            assert!(timing.verdict.starts_with("no difference resolved (95% CI"), "{}", timing.verdict);
            return;
        }
        verdicts.push(timing.verdict);
    }
    panic!("identical code resolved as different twice: {verdicts:?}");
}

#[test]
fn twice_the_work_is_resolved_as_slower() {
    let _turn = LAVAPIPE.lock().unwrap_or_else(|e| e.into_inner());
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let twice = dir.path().join("raygen-twice.spv");
    let compiled = std::process::Command::new("glslangValidator")
        .args(["-V", "--target-env", "spirv1.4"])
        .arg(format!("-I{}", twinray_tests::repo_root().join("shaders-glsl").display()))
        .arg("-o")
        .arg(&twice)
        .arg(twinray_tests::repo_root().join("tests/timing/raygen-twice.rgen"))
        .output()
        .expect("glslangValidator (cargo xtask setup installs it)");
    assert!(compiled.status.success(), "{}", String::from_utf8_lossy(&compiled.stdout));
    let heavy: ShaderSet = twinray_tests::set(&format!("glsl,raygen={}", twice.display()));
    // The claim is that doubled work is resolved: the interval excludes 1 and the ratio shows
    // a large difference. A bar on the interval's far end (it was `high < 0.8`) tested how quiet
    // the machine was, not the instrument: one CI run on a loaded 2-core machine measured 0.70
    // (0.56 to 0.87, log sd 0.21). A second try is allowed for the same reason as above.
    let mut tries = Vec::new();
    for _ in 0..2 {
        let c = compare_sets(&ctx, &sphere(), (&set("glsl"), &heavy), &opts(), None).unwrap();
        let r = c.report;
        assert!(r.pass && !r.null_control, "the same image, not a copy: {:?}", r.failures);
        let timing = r.timing.clone().expect("lavapipe times");
        let i = timing.interval;
        // Twice the rays take about twice the time.
        if i.high < 1.0 && i.ratio < 0.8 && i.ratio > 0.35 {
            assert!(timing.verdict.starts_with("a faster by"), "{}", timing.verdict);
            return each_set_led_as_often(&r);
        }
        tries.push(i);
    }
    panic!("twice the work not resolved as slower, twice: {tries:?}");
}

fn each_set_led_as_often(r: &twinray_host::compare::CompareReport) {
    // Each set was timed at both ends of the order, as often.
    for p in [&r.placements_a, &r.placements_b] {
        let first = p.position.iter().filter(|&&x| x == 0).count();
        assert_eq!(first, 3, "{:?}", p.position);
    }
}
