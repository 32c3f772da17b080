//! What `cargo xtask new-shape` promises, checked in the tutorial's scratch copy right after
//! the tutorial's first step runs it (`xtask/tests/tutorial.rs`): one scratch copy builds the
//! shader sets and the host once for both, where a second copy cost CI about 260 s on 2 cores.

use crate::scratch::{cargo, cargo_envs, text};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// Every file under `dir` but its build folder, with its contents.
pub fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            let relative = path.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
            // The build folder, and host/spirv, host/scenes and host/probes: links to folders listed anyway.
            if relative == "target" || path.is_symlink() {
                continue;
            }
            if path.is_dir() {
                stack.push(path);
            } else {
                out.insert(relative, std::fs::read(&path).unwrap());
            }
        }
    }
    out
}

/// After `cargo xtask new-shape NAME` printed `said` in `dir`, whose files were `before`: the
/// scaffold built, its scene passed parity with both sets, it added and changed exactly the
/// files [Adding stages](docs/adding-stages.md) lists, registered the next hit kind, its CPU
/// tests pass, and a second run refuses the taken name.
pub fn check_new_shape(dir: &Path, name: &str, before: &BTreeMap<String, Vec<u8>>, said: &str) {
    let scene = format!("scene {name} ");
    assert!(said.contains(&scene) && said.contains("PASS: within the scene's parity tolerance"), "{said}");
    let after = files(dir);
    let added: Vec<&str> = after.keys().filter(|f| !before.contains_key(*f)).map(String::as_str).collect();
    // spirv/ is all written by `cargo xtask shaders`; besides the new modules, rust-gpu (without
    // its spirv-opt pass) may renumber others, such as raygen, which keeps the new hit kind as
    // an unused constant.
    let changed: Vec<&str> = before
        .iter()
        .filter(|(f, bytes)| after.get(*f) != Some(bytes) && !f.starts_with("spirv/"))
        .map(|(f, _)| f.as_str())
        .collect();
    let want = [
        format!("scenes/{name}.toml"),
        format!("shaders-glsl/shapes/{name}.glsl"),
        format!("shaders-rs/shared/src/shapes/{name}.rs"),
        format!("spirv/glsl/{name}_intersection.spv"),
        format!("spirv/rust/{name}_intersection.spv"),
    ];
    assert_eq!(
        added, want,
        "files added: the shape, its twin and scene by hand, the two modules by cargo xtask shaders"
    );
    assert_eq!(
        changed,
        [
            "docs/scene-format.md",
            "shaders-glsl/shape_dispatch.glsl",
            "shaders-glsl/twinray_layout.glsl",
            "shaders-rs/shared/src/shapes/mod.rs",
            "shaders-rs/stages/src/intersection.rs"
        ],
        "files changed: the registry and the Rust stages by hand; the docs' table, the GLSL shape dispatch (ray \
         queries) and the GLSL include by cargo xtask shaders"
    );
    let registry = String::from_utf8_lossy(&after["shaders-rs/shared/src/shapes/mod.rs"]).into_owned();
    let kind = twinray_shared::shapes::SHAPES.iter().map(|s| s.hit_kind).max().unwrap_or(0) + 1;
    let line = format!("\"{name}\" => {name} ({kind}): {name}_intersection;");
    assert!(registry.contains(&line), "{registry}");
    let tests = cargo(&["test", "-p", "twinray-shared", "--lib", "shapes::"], dir);
    let said = text(&tests);
    assert!(tests.status.success(), "the scaffold's CPU tests fail:\n{said}");
    let far_test = format!("shapes::{name}::tests::a_far_ray_keeps_its_accuracy ... ok");
    assert!(said.contains(&far_test), "{said}");
    let again = cargo(&["xtask", "new-shape", name], dir);
    assert!(!again.status.success() && text(&again).contains("already registered"), "{}", text(&again));
}

/// `cargo xtask watch` on the new scene: after its first verdict, a one-line edit of the GLSL
/// twin (a comment added at its end, whatever the twin says by then) rebuilds the GLSL set only and prints a verdict and the time from the save; a save
/// whose ray generation stage never returns ends in a verdict line within the deadline, and
/// the save that fixes it passes again, without a restart.
pub fn watch_sees_an_edit_of_the_twin(dir: &Path, name: &str) {
    use std::io::{BufRead, BufReader};
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut child = Command::new(cargo)
        // 15 s: the deadline also bounds each pipeline creation, and lavapipe compiling a
        // changed set's pipeline with a cold shader cache took 6 s under a test run's load (3 s
        // failed a clean clone's CI). It is also how long the looping save below keeps a core
        // busy: 30 s, as it was, is half a minute of a CI run that has ten.
        .args(["xtask", "watch", name, "--changes", "3", "--poll-ms", "100", "--", "--gpu-timeout", "15"])
        .current_dir(dir)
        .envs(cargo_envs())
        // Every pipeline compiled cold, as on a fresh machine: the verdicts must not need a
        // warm shader cache (a specialised stage once missed it and overran a 3 s deadline).
        .env("MESA_SHADER_CACHE_DISABLE", "true")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::inherit())
        .spawn()
        .expect("starting cargo xtask watch");
    let lines = BufReader::new(child.stdout.take().expect("piped stdout")).lines();
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || lines.map_while(Result::ok).for_each(|l| drop(send.send(l))));
    let wait_for = |needle: &str, seen: &mut Vec<String>| loop {
        match receive.recv_timeout(std::time::Duration::from_secs(600)) {
            Ok(line) if line.contains(needle) => return seen.push(line),
            Ok(line) => seen.push(line),
            Err(e) => panic!("no {needle:?} from watch ({e}); it said:\n{}", seen.join("\n")),
        }
    };
    let mut seen = Vec::new();
    wait_for("watch: watching", &mut seen);
    let twin = dir.join(format!("shaders-glsl/shapes/{name}.glsl"));
    let text = std::fs::read_to_string(&twin).unwrap();
    std::fs::write(&twin, text + "// edited while watched\n").unwrap();
    wait_for("watch: save to verdict", &mut seen);
    let first = seen.len();
    // A ray generation stage that never returns (its store keeps the loop from being removed),
    // in its first invocation only: one of lavapipe's threads spins until the deadline, not
    // every thread, which the other test binaries of a CI run share the cores with.
    let raygen = dir.join("shaders-glsl/raygen_main.glsl");
    let body = std::fs::read_to_string(&raygen).unwrap();
    let looping = "void main() {\n    while (LAUNCH_ID == uvec2(0) && hit_ids[0] != 0xfffffff0u) { hit_ids[1] += 1u; }";
    std::fs::write(&raygen, body.replacen("void main() {", looping, 1)).unwrap();
    let saved = std::time::Instant::now();
    wait_for("watch: save to verdict", &mut seen);
    let hung = saved.elapsed();
    let second = seen.len();
    std::fs::write(&raygen, &body).unwrap();
    wait_for("watch: save to verdict", &mut seen);
    assert!(child.wait().expect("watch exits").success(), "{}", seen.join("\n"));
    let after = seen.iter().skip_while(|l| !l.contains("watch: watching")).cloned().collect::<Vec<_>>().join("\n");
    assert!(after.contains(&format!("watch: changed shaders-glsl/shapes/{name}.glsl")), "{after}");
    assert!(after.contains("built the glsl set") && !after.contains("built the rust set"), "{after}");
    assert!(seen[..first].join("\n").contains("PASS: within the scene's parity tolerance"), "{after}");
    let looped = seen[first..second].join("\n");
    assert!(looped.contains("did not finish in 15 s") && looped.contains("raygen"), "{looped}");
    assert!(looped.contains("watch: verdict: a stage did not finish in time"), "{looped}");
    assert!(hung < std::time::Duration::from_secs(120), "the looping save took {hung:?}");
    let fixed = seen[second..].join("\n");
    assert!(fixed.contains("PASS: within the scene's parity tolerance"), "the next good save recovers: {fixed}");
}
