//! A shader crate of one's own (`twinray new`, `twinray build`, a folder of sources named as a
//! set): unchanged it builds to the built-in sets byte for byte and renders as they do, an
//! edit shows in a verdict, an unchanged crate is not rebuilt, and every bad crate is one line
//! (or the compiler's own errors) with exit 2, nothing of the crate written but its `target/`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;
use twinray_shared::contract::{parse_version, CONTRACT_VERSION};
use twinray_tests::cli::twinray;
use twinray_tests::repo_root as repo;
use twinray_tests::scratch::seed_crate_target;

mod shading;
use shading::shade_in_closest_hits;

fn text(out: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr))
}

fn ok(args: &[&str], dir: &Path) -> String {
    let out = twinray(args, dir);
    assert!(out.status.success(), "{args:?}: {}", text(&out));
    text(&out)
}

/// Every file of a crate but those under `target/`, with its bytes.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.file_name().is_some_and(|n| n == "target") {
                continue;
            }
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                out.insert(path.strip_prefix(root).unwrap().to_path_buf(), std::fs::read(&path).unwrap());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// Asserts that `args` exits with 2, its last line of stderr holds every one of `needles`
/// (the lines above it, if any, being the compiler's), and the crate's files outside
/// `target/` are as they were.
fn refused(args: &[&str], dir: &Path, krate: &Path, needles: &[&str]) -> String {
    let before = files(krate);
    let out = twinray(args, dir);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    let last = stderr.trim().lines().last().unwrap_or_default();
    for needle in needles {
        assert!(last.contains(needle), "{args:?}: {last:?} does not say {needle:?}\n{stderr}");
    }
    assert!(files(krate) == before, "{args:?} wrote in the crate outside target/");
    stderr
}

/// The name of every file and folder under `dir`.
fn names_under(dir: &Path) -> Vec<String> {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap().map(Result::unwrap) {
        names.push(entry.file_name().to_string_lossy().into_owned());
        if entry.file_type().unwrap().is_dir() {
            names.extend(names_under(&entry.path()));
        }
    }
    names
}

fn same_modules(set: &Path, language: &str) {
    for entry in std::fs::read_dir(repo().join("spirv").join(language)).unwrap() {
        let path = entry.unwrap().path();
        let built = std::fs::read(set.join(path.file_name().unwrap())).unwrap();
        assert!(built == std::fs::read(&path).unwrap(), "{} differs from the built-in {language} set", path.display());
    }
}

const SMALL: [&str; 8] = ["--width", "64", "--height", "48", "--runs", "1", "--warmup", "0"];

#[test]
fn a_new_crate_is_the_rust_set_until_edited() {
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    let said = ok(&["new", "mine", "--glsl"], dir);
    assert!(said.contains("twinray build mine"), "{said}");
    let krate = dir.join("mine");
    let written = files(&krate);
    seed_crate_target(&krate);
    let built = ok(&["build", "mine"], dir);
    assert!(built.contains(&format!("mine: built, 30 modules (twinray-shared {CONTRACT_VERSION})")), "{built}");
    assert!(!built.contains("warning"), "the starter's own code warns of nothing: {built}");
    same_modules(&krate.join("target/twinray/set"), "rust");
    // Named relatively, as here, the crate still builds in its own target/twinray/.
    let target: Vec<_> = std::fs::read_dir(krate.join("target")).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(target, ["twinray"], "the build's folders under mine/target");
    // The crate's own build is there (the target was seeded with its dependencies').
    assert!(names_under(&krate.join("target/twinray/cargo")).iter().any(|n| n.contains("mine")), "no build of mine");
    assert!(ok(&["build", "mine"], dir).contains("mine: up to date"));
    assert!(files(&krate) == written, "a build wrote in the crate outside target/");
    // Two builds of one changed crate at once take turns: one builds, the other finds it built.
    let readme = krate.join("README.md");
    std::fs::write(&readme, std::fs::read_to_string(&readme).unwrap() + "\nEdited.\n").unwrap();
    let written = files(&krate);
    let build =
        || std::process::Command::new(twinray_tests::cli::exe()).args(["build", "mine"]).current_dir(dir).output();
    let (first, second) = std::thread::scope(|s| {
        let first = s.spawn(build);
        let second = s.spawn(build);
        (first.join().unwrap().unwrap(), second.join().unwrap().unwrap())
    });
    let said = [text(&first), text(&second)];
    assert!(first.status.success() && second.status.success(), "{said:?}");
    assert_eq!(said.iter().filter(|t| t.contains("mine: built")).count(), 1, "{said:?}");
    same_modules(&krate.join("target/twinray/set"), "rust");
    ok(&["build", "mine/glsl"], dir);
    same_modules(&krate.join("glsl/target/twinray/set"), "glsl");
    assert!(files(&krate) == written, "a build wrote in the crate outside target/");

    let compare = |a: &str, b: &str| {
        twinray(&[&["--validate", "compare", "--a", a, "--b", b, "--json"], &SMALL[..]].concat(), dir)
    };
    let out = compare("./mine", "rust");
    assert!(out.status.success(), "{}", text(&out));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let exact = (json["max_abs_diff"].as_u64(), json["hit_mismatches"].as_u64(), json["rmse"].as_f64());
    assert_eq!(exact, (Some(0), Some(0), Some(0.0)), "unchanged, the crate renders bit for bit as rust: {json}");

    // A new material response in the closest hit, saved while `twinray watch` compares the
    // crate with its GLSL twins: the crate is rebuilt and the verdict, now a fail, comes with
    // the time from the save; then a save of a twin, which lies in the crate's folder but is
    // a set of its own, is seen too.
    let lib = krate.join("src/hit.rs");
    let source = std::fs::read_to_string(&lib).unwrap();
    let old = "        shading::material_color(material, point, normal)\n";
    assert!(source.contains(old), "the starter's closest hit moved: this test must follow");
    let log = dir.join("watch.log");
    let mut watch = std::process::Command::new(twinray_tests::cli::exe())
        .args(["watch", "mine", "--against", "./mine/glsl", "--changes", "2", "--", "--width", "64", "--height", "48"])
        .current_dir(dir)
        .stdout(std::fs::File::create(&log).unwrap())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let watched = || std::fs::read_to_string(&log).unwrap_or_default();
    let start = std::time::Instant::now();
    while !watched().contains("PASS") {
        assert!(start.elapsed().as_secs() < 300, "watch gave no first verdict:\n{}", watched());
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    std::fs::write(&lib, source.replacen(old, &format!("{} * 0.5\n", old.trim_end()), 1)).unwrap();
    while !watched().contains("watch: save to verdict") {
        assert!(start.elapsed().as_secs() < 600, "watch gave no verdict on the crate's save:\n{}", watched());
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    let twin = krate.join("glsl/raygen.rgen");
    std::fs::write(&twin, std::fs::read_to_string(&twin).unwrap() + "// edited while watched\n").unwrap();
    let ended = twinray_tests::cli::wait_within(&mut watch, std::time::Duration::from_secs(300));
    let said = watched();
    assert!(ended.is_ok_and(|s| s.success()), "watch: {said}");
    assert!(said.contains("watch: changed src/hit.rs") && said.contains("FAIL"), "{said}");
    assert!(said.contains("watch: changed ./mine/glsl/raygen.rgen"), "the twin's save was not seen: {said}");
    assert_eq!(said.matches("watch: save to verdict").count(), 2, "{said}");
    let out = compare("./mine", "rust");
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    // Per-stage mixes take the folder too: its closest hits fail, its (unchanged) raygen passes.
    assert_eq!(compare("rust,closest_hit=./mine", "rust").status.code(), Some(1));
    assert!(compare("rust,raygen=./mine", "rust").status.success());
}

/// The starter crate with `lib` as its whole `src/lib.rs`.
fn with_lib(krate: &Path, lib: &str) {
    std::fs::write(krate.join("src/lib.rs"), format!("#![cfg_attr(target_arch = \"spirv\", no_std)]\n{lib}")).unwrap();
}

#[test]
fn bad_crates_are_refused_in_one_line_and_leave_the_crate_as_it_was() {
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    std::fs::create_dir(dir.join("empty")).unwrap();
    let empty = dir.join("empty");
    refused(&["build", "empty"], dir, &empty, &["no shader sources"]);
    refused(&["compare", "--a", "./empty", "--b", "rust"], dir, &empty, &["neither a set nor a shader crate"]);
    ok(&["new", "c"], dir);
    refused(&["new", "c"], dir, &dir.join("c"), &["already holds files"]);
    refused(&["new", "9lives"], dir, &dir.join("c"), &["cannot be a crate's name"]);

    let krate = dir.join("c");
    seed_crate_target(&krate);
    let manifest = krate.join("twinray-shared/Cargo.toml");
    let original = std::fs::read_to_string(&manifest).unwrap();
    // The next minor version, which this host cannot read (before 1.0 every minor version is
    // a contract of its own).
    let (major, minor, _) = parse_version(CONTRACT_VERSION).unwrap();
    let next = format!("{major}.{}.0", minor + 1);
    let ours = format!("version = \"{CONTRACT_VERSION}\"");
    std::fs::write(&manifest, original.replacen(&ours, &format!("version = \"{next}\""), 1)).unwrap();
    let speaks = format!("speaks twinray-shared {CONTRACT_VERSION}");
    refused(&["build", "c"], dir, &krate, &[&format!("twinray-shared {next}"), &speaks]);
    std::fs::write(&manifest, &original).unwrap();

    let cargo = krate.join("Cargo.toml");
    let starter = std::fs::read_to_string(&cargo).unwrap();
    std::fs::write(&cargo, starter.replace("crate-type = [\"dylib\"]", "crate-type = [\"rlib\"]")).unwrap();
    refused(&["build", "c"], dir, &krate, &["not a shader crate"]);
    let alone = "[package]\nname = \"c\"\nversion = \"0.1.0\"\nedition = \"2021\"\n[workspace]\n[lib]\ncrate-type = [\"dylib\"]\n";
    std::fs::write(&cargo, format!("{alone}[dependencies]\nspirv-std = \"0.11.0\"\n")).unwrap();
    refused(&["build", "c"], dir, &krate, &["does not depend on twinray-shared"]);
    std::fs::write(&cargo, &starter).unwrap();

    let spirv = "use spirv_std::spirv;\nuse twinray_shared as _;\n";
    with_lib(&krate, &format!("{spirv}pub fn broken() -> u32 {{ \"not a number\" }}\n"));
    let said = refused(&["build", "c"], dir, &krate, &["the crate does not build"]);
    assert!(said.contains("error[E0308]: mismatched types"), "the compiler's errors, as cargo prints them:\n{said}");
    with_lib(&krate, "use twinray_shared as _;\npub fn helper() {}\n");
    refused(&["build", "c"], dir, &krate, &["no stage entry points"]);
    with_lib(&krate, &format!("{spirv}#[spirv(miss)]\npub fn my_miss() {{}}\n"));
    refused(&["compare", "--a", "c", "--b", "rust"], dir, &krate, &["entry point `my_miss` is no module"]);
    with_lib(&krate, &format!("{spirv}#[spirv(miss)]\npub fn raygen() {{}}\n"));
    refused(&["build", "c"], dir, &krate, &["raygen"]);
    let payload = "#[spirv(miss)]\npub fn miss(#[spirv(incoming_ray_payload)] p: &mut u32) { *p = 1; }\n";
    with_lib(&krate, &format!("{spirv}{payload}"));
    refused(&["build", "c"], dir, &krate, &["miss"]);

    // A build that never ends is stopped at the deadline, its build script with it.
    std::fs::write(
        krate.join("build.rs"),
        "fn main() { loop { std::thread::sleep(std::time::Duration::from_secs(1)); } }\n",
    )
    .unwrap();
    let started = std::time::Instant::now();
    refused(&["--build-timeout", "5", "build", "c"], dir, &krate, &["did not finish within 5 s"]);
    assert!(started.elapsed().as_secs() < 60, "the deadline was not kept: {:?}", started.elapsed());
}

/// The probe report of `case` with `set`, and whether the command passed.
fn probe(case: &str, set: &str, dir: &Path) -> (serde_json::Value, Option<i32>) {
    let out = twinray(&["--validate", "probe", case, "--shaders", set, "--json", "--runs", "1", "--warmup", "0"], dir);
    let json = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{case} with {set}: {e}: {}", text(&out)));
    (json, out.status.code())
}

#[test]
fn a_crates_own_shape_material_and_shading_agree_in_both_languages_and_the_shape_is_judged_by_its_definition() {
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    let said = ok(&["new", "shapes", "--glsl", "--shape", "capsule", "--material", "waves"], dir);
    assert!(said.contains("the shape capsule (hit kind 32)") && said.contains("the material waves"), "{said}");
    let krate = dir.join("shapes");
    seed_crate_target(&krate);
    // The material edited as a user would, in both languages: waves of the opposite phase.
    for (file, from, to) in [
        ("shared/src/waves.rs", "let s = 0.5 + 0.5 *", "let s = 0.5 - 0.5 *"),
        ("glsl/waves_material.rcall", "float s = 0.5 + 0.5 *", "float s = 0.5 - 0.5 *"),
    ] {
        let source = std::fs::read_to_string(krate.join(file)).unwrap();
        assert!(source.contains(from), "{file}: the template moved: this test must follow");
        std::fs::write(krate.join(file), source.replacen(from, to, 1)).unwrap();
    }
    shade_in_closest_hits(&krate);
    let written = files(&krate);
    let small = ["--width", "96", "--height", "72", "--runs", "1", "--warmup", "0", "--placements", "1"];
    let compare = |scene: &str, a: &str, b: &str| {
        let args = [&["--validate", "compare", scene, "--a", a, "--b", b][..], &small].concat();
        twinray(&args, dir)
    };
    for scene in ["shapes/scenes/capsule.toml", "shapes/scenes/waves.toml"] {
        let both = compare(scene, "shapes", "shapes/glsl");
        assert!(both.status.success(), "{scene}, Rust against its GLSL twin: {}", text(&both));
        assert!(text(&both).contains("PASS"), "{}", text(&both));
    }
    assert!(files(&krate) == written, "building wrote in the crate outside target/ (its Cargo.lock?)");
    // view reads the scene with the kinds of its sets' crates: it serves the page.
    let mut view = std::process::Command::new(env!("CARGO_BIN_EXE_twinray"))
        .args(["view", "shapes/scenes/capsule.toml", "--a", "shapes", "--b", "shapes/glsl", "--port", "0"])
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    std::io::BufRead::read_line(&mut std::io::BufReader::new(view.stdout.take().unwrap()), &mut first).unwrap();
    // Ctrl-C, as a user stops it: it removes its work folder and exits.
    let _ = std::process::Command::new("kill").args(["-INT", &view.id().to_string()]).status();
    let ended = view.wait_with_output().unwrap();
    let said = String::from_utf8_lossy(&ended.stderr);
    assert!(first.starts_with("twinray view: serving http://"), "view of a crate's own kinds: {first:?} {said}");
    // explain reports what the closest hits computed, and claims no lighting of its own.
    let args = ["explain", "shapes/scenes/waves.toml", "--pixel", "29,31", "--a", "shapes", "--b", "shapes/glsl"];
    let said = ok(&[&args[..], &["--width", "96", "--height", "72"]].concat(), dir);
    assert!(said.contains("radiance its closest hit shaded") && !said.contains("light 0 sample"), "{said}");
    assert!(said.contains("all rays agree, and the pixels are identical"), "{said}");
    for set in ["shapes", "shapes/glsl"] {
        let (report, code) = probe("shapes/probes/capsule.toml", set, dir);
        assert_eq!(code, Some(0), "{set}: {report}");
        let wrong = (report["false_hits"].as_u64(), report["false_misses"].as_u64());
        assert_eq!(wrong, (Some(0), Some(0)), "{set} against the crate's definition: {report}");
        assert!(report["decided"].as_u64() > Some(8000), "{report}");
    }
    // A logic slip in the GPU routine alone (the side runs past the caps), which the crate's
    // f64 distance does not share: the probe sees it.
    let routine = krate.join("shared/src/capsule.rs");
    let source = std::fs::read_to_string(&routine).unwrap();
    let exact = "if q.y.abs() <= half {";
    assert!(source.contains(exact), "the template's side test moved: this test must follow");
    std::fs::write(&routine, source.replacen(exact, "if q.y.abs() <= half * 1.2 {", 1)).unwrap();
    // In the same build, a material callable that forgets its colour: the poison it leaves is
    // a pixel that is not finite, which fails the comparison.
    let callable = krate.join("src/waves.rs");
    let stage = std::fs::read_to_string(&callable).unwrap();
    std::fs::write(&callable, stage.replacen("call.color = color(", "let _ = color(", 1)).unwrap();
    let (report, code) = probe("shapes/probes/capsule.toml", "shapes", dir);
    assert_eq!(code, Some(1), "{report}");
    assert!(report["false_hits"].as_u64() > Some(10), "the planted slip: {report}");
    let forgot = compare("shapes/scenes/waves.toml", "shapes", "shapes/glsl");
    assert_eq!(forgot.status.code(), Some(1), "{}", text(&forgot));
    assert!(text(&forgot).contains("pixels non-finite in set a"), "{}", text(&forgot));
    // The slips stay: what follows refuses sets and scenes before anything is traced, so the
    // crate needs no build of its own again (one fewer rust-gpu build).
    // A set that lacks the shape: one line, exit 2.
    let lacks = |args: &[&str], needle: &str| {
        let out = twinray(args, dir);
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!((out.status.code(), stderr.trim().lines().count()), (Some(2), 1), "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    };
    let render = ["render", "shapes/scenes/capsule.toml", "--shaders", "rust", "--out", "x.png"];
    lacks(&render, "unknown shape kind \"capsule\"");
    let render = ["render", "shapes/scenes/waves.toml", "--shaders", "rust", "--out", "x.png"];
    lacks(&render, "unknown material kind \"waves\"");
    // The crate's built folder named as a folder of modules is data: its CPU library, native
    // code, is not loaded from there, so neither the kinds it lists nor the recursion depth it
    // declares are known, and its closest hits, which trace, are refused.
    let modules = ["render", "shapes/scenes/capsule.toml", "--shaders", "shapes/target/twinray/set", "--out", "x.png"];
    lacks(&modules, "procedural_closest_hit.spv: it calls traceRay, but its set's pipelines have recursion depth 1");
    let mixed = ["compare", "shapes/scenes/capsule.toml", "--a", "shapes", "--b", "rust"];
    lacks(&mixed, "no module capsule_intersection");
    let mixed = ["compare", "shapes/scenes/waves.toml", "--a", "shapes", "--b", "rust"];
    lacks(&mixed, "no module waves_material");
    refused(&["new", "shapes", "--shape", "capsule"], dir, &krate, &["has a shape \"capsule\" already"]);
}

/// A crate as a stranger writes one, from scratch: no toolchain file, no lint settings, one
/// stage, the contract by a path of its own.
const SKY_MANIFEST: &str = r#"[package]
name = "sky"
version = "0.1.0"
edition = "2021"

[lib]
crate-type = ["dylib"]

[dependencies]
spirv-std = "0.11.0"
twinray-shared = { path = "../starter/twinray-shared" }
"#;

/// A miss stage that shows half the background.
const SKY_LIB: &str = r#"#![cfg_attr(target_arch = "spirv", no_std)]
use spirv_std::glam::UVec4;
use spirv_std::spirv;
use twinray_shared::bindings::NO_HIT;
use twinray_shared::layout::{FrameUniform, HitPayload};

#[spirv(miss)]
pub fn miss(
    #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
    #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
) {
    let dim = 0.5;
    let unused = 1;
    payload.color = frame.background * dim;
    payload.ids = UVec4::splat(NO_HIT);
}
"#;

#[test]
fn a_crate_written_from_scratch_builds_shows_its_warnings_and_lends_its_one_stage() {
    let scratch = tempfile::tempdir().unwrap();
    let dir = scratch.path();
    ok(&["new", "starter"], dir);
    let sky = dir.join("sky");
    std::fs::create_dir_all(sky.join("src")).unwrap();
    std::fs::write(sky.join("Cargo.toml"), SKY_MANIFEST).unwrap();
    // The starter's lock: the same versions, so the test needs no network.
    let lock = std::fs::read_to_string(dir.join("starter/Cargo.lock")).unwrap();
    std::fs::write(sky.join("Cargo.lock"), lock.replace("name = \"starter\"", "name = \"sky\"")).unwrap();
    std::fs::write(sky.join("src/lib.rs"), SKY_LIB).unwrap();
    seed_crate_target(&sky);
    let built = ok(&["build", "sky"], dir);
    assert!(built.contains(&format!("sky: built, 1 modules (twinray-shared {CONTRACT_VERSION})")), "{built}");
    // A warning of the crate's own is shown, and does not fail its build.
    assert!(built.contains("warning: unused variable: `unused`"), "{built}");
    assert!(!built.contains("--no-spirv-opt"), "twinray's own choice is not the crate's warning: {built}");

    let compare =
        |scene: &str, a: &str| twinray(&[&["compare", scene, "--a", a, "--b", "rust"][..], &SMALL[..]].concat(), dir);
    let spheres = compare("spheres", "rust,miss=./sky");
    assert_eq!(spheres.status.code(), Some(1), "the background differs: {}", text(&spheres));
    let file = "rust,miss=sky/target/twinray/set/miss.spv";
    assert_eq!(compare("spheres", file).status.code(), Some(1));
    // `miss=FOLDER` takes the miss stage's every module; this crate has no shadow miss.
    let boxes = compare("box", "rust,miss=./sky");
    assert_eq!(boxes.status.code(), Some(2), "{}", text(&boxes));
    assert!(text(&boxes).contains("shadow_miss"), "{}", text(&boxes));
}

/// Folders and files only a checkout of twinray has: a comment of the starter crate that
/// names one points its reader at nothing.
const REPO_ONLY: &[&str] = &[
    "docs/",
    "bench/",
    "probes/",
    "tests/",
    "host/",
    "app/",
    "xtask/",
    "spirv/",
    "scenes/",
    "shaders-glsl",
    "shaders-rs",
    "../",
];

/// The lines of `text` a reader reads as prose: every line of a README or manifest, the
/// comments of source files (code strings name the built-in sets' files for the host).
fn prose(name: &str, text: &str) -> Vec<(usize, String)> {
    let whole = name.ends_with(".md") || name.ends_with(".toml");
    text.lines()
        .enumerate()
        .filter(|(_, l)| {
            let t = l.trim_start();
            whole || t.starts_with("//") || t.starts_with('#') || t.starts_with('*') || l.contains(" // ")
        })
        .map(|(n, l)| (n + 1, l.to_string()))
        .collect()
}

#[test]
fn the_starter_crate_names_no_file_only_a_checkout_has() {
    let scratch = tempfile::tempdir().unwrap();
    ok(&["new", "mine", "--glsl"], scratch.path());
    let written = files(&scratch.path().join("mine"));
    assert!(written.len() > 50, "{} files written", written.len());
    let mut found = Vec::new();
    for (path, bytes) in &written {
        let name = path.display().to_string();
        if name.ends_with("Cargo.lock") {
            continue;
        }
        // A path dependency within the crate (its shared library's on the contract) is no
        // reference to a checkout.
        // Nor are the crate's own scenes/ and probes/, which `--shape NAME` writes.
        let within = |line: &str| line.contains("path = \"../twinray-shared\"") || line.contains("NAME.toml");
        for (n, line) in prose(&name, &String::from_utf8_lossy(bytes)).into_iter().filter(|(_, l)| !within(l)) {
            if let Some(what) = REPO_ONLY.iter().find(|w| line.contains(*w)) {
                found.push(format!("{name}:{n}: {what} in {}", line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "the starter crate refers to a checkout's files:\n{}", found.join("\n"));
}
