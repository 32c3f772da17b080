//! Rendering several sets together (`render_sets`, which `compare` and `bench` use): the
//! sets share the scene and the output image, are timed in turn over several placements, and
//! each must still get its own image, hit ids and timings.

use twinray_host::{render_sets, RenderOptions, Scene};
use twinray_tests::{set, validated_context};

/// Soft shadows, every shape and a mesh: every stage of every set runs.
fn showcase() -> Scene {
    Scene::load(Some("showcase")).unwrap_or_else(|e| panic!("showcase: {e}"))
}

/// The sets agree bit for bit on lavapipe, so this catches a missing, partial or stale
/// readback rather than two sets' outputs swapped (the order of copies rules that out). On
/// `sphere` (procedural shapes, shadow rays of two lights), not showcase: every place is a
/// pipeline of its own, twelve here, and lavapipe compiles showcase's in 2.0 s, sphere's in
/// 0.55 s (alone with an empty shader cache: 36 s on showcase, 11 s on sphere); what is
/// checked is the bookkeeping of rounds and readbacks, which no stage kind changes.
#[test]
fn each_set_gets_what_it_renders_alone() {
    let ctx = validated_context();
    let scene = Scene::load(Some("sphere")).unwrap_or_else(|e| panic!("sphere: {e}"));
    let sets = [set("rust"), set("glsl"), set("glsl,intersection=rust")];
    let opts = RenderOptions { width: 48, height: 27, warmup: 1, runs: 3, placements: 3, first_placement: 0 };
    let together = render_sets(&ctx, &scene, &sets, &opts).unwrap();
    assert_eq!(together.len(), sets.len());
    // Every set at places of its own, one a round: no place timed twice.
    let places: Vec<u64> = together.iter().flat_map(|o| o.placements.place.clone()).collect();
    assert_eq!(places.len(), sets.len() * opts.placements as usize, "{places:?}");
    assert_eq!(places.iter().collect::<std::collections::HashSet<_>>().len(), places.len(), "{places:?}");
    for (s, out) in sets.iter().zip(&together) {
        let alone = twinray_host::render(&ctx, &scene, s, &RenderOptions { runs: 1, warmup: 0, placements: 1, ..opts })
            .unwrap();
        // Bit-exact: the same pipeline traced the same rays over the same scene.
        assert_eq!(out.hit_ids, alone.hit_ids, "{s}: hit ids");
        assert_eq!(out.rays, alone.rays, "{s}: ray counts");
        assert!(out.linear == alone.linear, "{s}: image differs from its render alone");
        // Every timed placement adds `runs` timed traces and one median; the warm-up none.
        assert_eq!(out.gpu_ms.len(), (opts.placements * opts.runs) as usize, "{s}: timed traces");
        assert_eq!(out.placements.median_ms.len(), opts.placements as usize, "{s}: placements");
        assert!(out.placements.position.iter().all(|&p| (p as usize) < sets.len()), "{s}");
        assert!(out.gpu_ms.iter().all(|&ms| ms > 0.0), "{s}: {:?}", out.gpu_ms);
        assert!(out.raygen_stack_bytes > 0, "{s}: no raygen stack size");
    }
}

#[test]
fn one_placement_has_no_warm_up_placement() {
    let ctx = validated_context();
    let scene = showcase();
    let opts = RenderOptions::once(16, 16, 0, 1);
    let outs = render_sets(&ctx, &scene, &[set("rust"), set("glsl")], &opts).unwrap();
    let counts: Vec<_> = outs.iter().map(|o| (o.gpu_ms.len(), o.placements.median_ms.len())).collect();
    assert!(counts.iter().all(|&c| c == (1, 1)), "{counts:?}");
}

/// Two identical sets agree bit for bit; a set rendered after them whose ray generation
/// stage writes nothing is judged on its own outputs (every word still the sentinel), never
/// on the pixels the sets before it left in the shared image.
#[test]
fn identical_sets_agree_bit_for_bit_and_an_empty_set_is_judged_on_its_own_pixels() {
    let ctx = validated_context();
    let dir = tempfile::tempdir().unwrap();
    let noop = dir.path().join("noop.spv");
    let compiled = std::process::Command::new("glslangValidator")
        .args(["-V", "--target-env", "spirv1.4", "-o"])
        .arg(&noop)
        .arg(twinray_tests::repo_root().join("tests/hostile/stages/noop.rgen"))
        .output()
        .expect("glslangValidator (cargo xtask setup installs it)");
    assert!(compiled.status.success(), "{}", String::from_utf8_lossy(&compiled.stdout));
    let sets = [set("glsl"), set("glsl"), set(&format!("glsl,raygen={}", noop.display()))];
    let opts = RenderOptions::once(48, 27, 0, 1);
    let outs = render_sets(&ctx, &showcase(), &sets, &opts).unwrap();
    let bits = |i: usize| outs[i].linear.iter().flatten().map(|v| v.to_bits()).collect::<Vec<u32>>();
    assert_eq!(bits(0), bits(1), "identical sets, identical bits");
    assert_eq!(outs[0].hit_ids, outs[1].hit_ids);
    assert!(outs[0].written.is_clean() && outs[1].written.is_clean(), "{:?}", outs[0].written);
    let pixels = 48 * 27;
    let empty = outs[2].written;
    assert_eq!((empty.unwritten, empty.unwritten_color, empty.unwritten_ids), (pixels, pixels, pixels));
    assert!(bits(2).iter().all(|&b| b == twinray_shared::bindings::UNWRITTEN), "the sentinel, not set 1's pixels");
    assert_eq!(outs[2].rays.shadow, 0, "no shadow ray counted from unwritten counts");
    assert_eq!(outs[2].mrays_per_s(), None, "no rate for a set that traced nothing");
}

/// `render_owned` (what the `render` command calls: the scene's meshes freed once uploaded)
/// draws what `render` draws with the scene kept, bit for bit, on scenes of meshes, of
/// procedural shapes, of a glTF model and of a far object whose GPU coordinates are centred
/// on a local origin.
#[test]
fn a_render_that_gives_the_meshes_up_draws_what_one_that_keeps_them_draws() {
    twinray_tests::allow_installed_models();
    let ctx = validated_context();
    let opts = RenderOptions { width: 48, height: 27, warmup: 0, runs: 1, placements: 1, first_placement: 0 };
    let far = twinray_tests::repo_root().join("tests/bisect/far-sphere.toml");
    let cube = "/usr/share/assimp/models/glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf";
    for name in ["meshes", "swarm", far.to_str().unwrap(), cube] {
        let scene = Scene::load(Some(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(name != far.to_str().unwrap() || scene.origin.is_some(), "{name}: no local origin");
        let kept = twinray_host::render(&ctx, &scene, &set("rust"), &opts).unwrap();
        let given = twinray_host::render_owned(&ctx, scene, &set("rust"), &opts).unwrap();
        assert_eq!(given.hit_ids, kept.hit_ids, "{name}: hit ids");
        assert!(given.linear == kept.linear, "{name}: the images differ");
    }
}
