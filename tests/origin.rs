//! The local origin is never worse than world coordinates, on cases nobody chose: random scenes
//! (`twinray::probe::random`: two to four groups of objects far apart, at distances from the
//! world origin spread over several orders of magnitude, thin shapes among them, each group
//! probed from close by) probed with the Rust set (even seeds) or the GLSL set (odd) at the
//! origins twinray chooses and at world coordinates, on lavapipe with validation on. A ray the
//! chosen origins get wrong that world coordinates get right, or a relative t p99 grown beyond
//! `origins::P99_SLACK`, fails.
//!
//! `TWINRAY_ORIGIN_CASES=N` and `TWINRAY_ORIGIN_SEED=S` run N cases from seed S in place of the
//! few CI runs (`twinray stability --against-world --random N --seed S` is the same check from
//! the command line, on any device).

use twinray::probe::case::ProbeCase;
use twinray::probe::origins::{check, table};
use twinray::probe::random::origin_case;
use twinray_tests::{alternate_set, set, validated_context};

/// Cases CI runs: each is one set (rust for even seeds, glsl for odd) at two to five launches.
const CI_CASES: u64 = 6;

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

#[test]
fn random_far_apart_ray_groups_are_never_worse_at_the_chosen_origins() {
    let (count, first) = (env("TWINRAY_ORIGIN_CASES", CI_CASES), env("TWINRAY_ORIGIN_SEED", 0));
    let ctx = validated_context();
    let mut checks = Vec::new();
    for seed in first..first + count {
        let text = origin_case(seed);
        let case = ProbeCase::parse(&text, &format!("random case {seed}"), std::env::temp_dir())
            .unwrap_or_else(|e| panic!("random case {seed} does not load: {e}\n{text}"));
        // One set per case, alternating: where a case's origins come from is the host's choice,
        // the same for both sets, and each case's random shapes are pipelines of their own for
        // lavapipe to compile (a second set doubles them); both languages still meet far scenes.
        let shaders = set(alternate_set(seed as usize));
        checks.push(check(&ctx, &case, &shaders).unwrap_or_else(|e| panic!("random case {seed} with {shaders}: {e}")));
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
    let worse: Vec<_> = checks.iter().filter(|c| !c.failures.is_empty()).collect();
    assert!(worse.is_empty(), "worse at the chosen origins than at world coordinates:\n{}", table(&checks));
    // The check must have had something to check: most cases move their rays.
    let moved = checks.iter().filter(|c| c.launches.iter().any(|l| l.origin != [0.0; 3])).count();
    assert!(2 * moved >= checks.len(), "only {moved} of {} rows launched rays at a local origin", checks.len());
}
