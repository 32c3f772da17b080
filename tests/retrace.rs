//! The experiment behind how twinray measures triangle hits of rays from afar (docs/numerics.md,
//! "Triangles measured near the hit"): a second, short trace from just before the first hit, in a
//! frame centred on the instance hit, against the stages measuring the hit again on its
//! triangle's plane (`transform::triangle_t`), against the driver alone. Ignored in CI (it
//! prints a table; run it with `cargo test --release -p twinray-tests --test integration retrace
//! -- --ignored --nocapture`); it asserts what the docs claim of both ways.
//!
//! The re-trace is emulated on the host, with the stages as they are: each hit ray restarts two
//! object bounds before the reference's hit, its start relative to the instance rounded once to
//! f32 (what exact arithmetic in the instance's frame gives, as `exact::moved_origin` does), and
//! is traced through the case's scene moved so that the instance is at the world origin. The
//! driver alone is the case with `far-instances` off (for a mesh, that leaves its triangle hits
//! as the driver found them); the stages' measure is the case as it runs.

use glam::DVec3;
use twinray_host::probe::case::ProbeCase;
use twinray_host::probe::run::probe;
use twinray_host::probe::ProbeRay;
use twinray_host::reference::scene::SceneVerdict;
use twinray_host::reference::shapes::bounding_radius;
use twinray_host::scene::Scene;
use twinray_host::util::stats::{median, Quantiles};
use twinray_tests::{repo_root, set, validated_context};

/// Relative t errors of `results` (t of each ray of `each`) against the reference's t.
fn errors(t_ref: &[f64], got: impl Iterator<Item = f64>) -> Quantiles {
    Quantiles::of(t_ref.iter().zip(got).map(|(t, g)| (g - t).abs() / t).collect())
}

fn with_features(scene: &Scene, names: &[&str]) -> Scene {
    let mut scene = scene.clone();
    scene.file.features = Some(names.iter().map(|n| n.to_string()).collect());
    scene
}

#[test]
#[ignore = "an experiment docs/numerics.md cites; run with --ignored --nocapture"]
fn retracing_near_the_hit_against_measuring_it_again() {
    let ctx = validated_context();
    let shaders = set("rust");
    println!("| case | rays | driver alone p99 | re-trace p99 | stages' measure p99 | GPU ms: driver, second trace, stages |");
    // The suite's one case of a small mesh grazed from afar (a mesh's rays that start near it
    // keep the driver's t, and are not restarted).
    for name in ["mesh-turned-scaled-grazing-1e3"] {
        let case = ProbeCase::load(&repo_root().join(format!("probes/stability/{name}.toml"))).expect("case");
        assert_eq!(case.reference.objects.len(), 1, "{name}: the emulation moves one instance");
        let object = &case.reference.objects[0];
        let translation = object.object_to_world.w_axis.truncate();
        let scale = object.object_to_world.transform_vector3(DVec3::ONE).length();
        let bound = object.shapes.iter().map(bounding_radius).fold(0.0, f64::max) * scale;
        // The hits the reference decides, each with its restart two bounds before it.
        let mut hits = Vec::new();
        for (i, r) in case.rays.iter().enumerate() {
            let (o, d) = (r.origin.truncate().as_dvec3(), r.direction.truncate().as_dvec3());
            if let SceneVerdict::Hit { t, .. } = case.reference.trace(o, d, 0.0, 1e30) {
                let shift = t - 2.0 * bound / d.length();
                if shift > 0.0 {
                    let start = (o + d * shift - translation).as_vec3();
                    let again = ProbeRay { origin: start.extend(0.0), direction: r.direction.truncate().extend(1e30) };
                    hits.push((i, t, shift, again));
                }
            }
        }
        let t_ref: Vec<f64> = hits.iter().map(|h| h.1).collect();
        let rays: Vec<ProbeRay> = hits.iter().map(|h| case.rays[h.0]).collect();
        let driver = probe(&ctx, &with_features(&case.scene, &[]), &shaders, &rays, 2, 5).expect("driver");
        let stages = probe(&ctx, &case.scene, &shaders, &rays, 2, 5).expect("stages");
        let mut centred = with_features(&case.scene, &[]);
        centred.file.objects[0].translate = [0.0; 3];
        let second: Vec<ProbeRay> = hits.iter().map(|h| h.3).collect();
        let retrace = probe(&ctx, &centred, &shaders, &second, 2, 5).expect("re-trace");
        let t = |out: &twinray_host::probe::run::ProbeOutput, k: usize| f64::from(out.results[k].normal_t.w);
        let d = errors(&t_ref, (0..hits.len()).map(|k| t(&driver, k)));
        let r = errors(&t_ref, (0..hits.len()).map(|k| hits[k].2 + t(&retrace, k)));
        let s = errors(&t_ref, (0..hits.len()).map(|k| t(&stages, k)));
        let ms = |out: &twinray_host::probe::run::ProbeOutput| median(&out.gpu_ms).unwrap_or(f64::NAN);
        println!(
            "| {name} | {} | {:.1e} | {:.1e} | {:.1e} | {:.3}, {:.3}, {:.3} |",
            hits.len(),
            d.p99,
            r.p99,
            s.p99,
            ms(&driver),
            ms(&retrace),
            ms(&stages)
        );
        assert!(hits.len() > 200, "{name}: only {} hits restarted", hits.len());
        assert!(d.p99 > 1e-6, "{name}: the driver alone is already at {:.1e}: the case is not hard", d.p99);
        assert!(r.p99 < 1e-6 && s.p99 < 1e-6, "{name}: re-trace {:.1e}, stages {:.1e}", r.p99, s.p99);
    }
    ctx.close().expect("validation errors or leaked objects at teardown");
}
