//! Shader sets from disk: a folder of modules or one module file takes the place of the
//! built-in SPIR-V, and every file is checked before use, with a one-line error naming the file
//! and what is wrong (exit code 2, nothing written).

use std::path::{Path, PathBuf};
use twinray_tests::cli::{assert_bad_input, twinray, UNTIMED};
use twinray_tests::repo_root as repo;

/// A copy of the committed GLSL set, as `cargo xtask shaders` leaves a build folder.
fn glsl_folder(dir: &Path) -> PathBuf {
    let folder = dir.join("modules");
    std::fs::create_dir(&folder).unwrap();
    for entry in std::fs::read_dir(repo().join("spirv/glsl")).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, folder.join(path.file_name().unwrap())).unwrap();
    }
    folder
}

fn words(path: &Path) -> Vec<u32> {
    let bytes = std::fs::read(path).unwrap();
    bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
}

fn write_words(path: &Path, words: &[u32]) -> String {
    std::fs::write(path, words.iter().flat_map(|w| w.to_le_bytes()).collect::<Vec<u8>>()).unwrap();
    path.to_string_lossy().into_owned()
}

/// The committed raygen module with `edit` applied to each instruction (opcode, operands).
fn edited_raygen(dir: &Path, name: &str, edit: impl Fn(u32, &mut Vec<u32>) -> bool) -> String {
    let words = words(&repo().join("spirv/rust/raygen.spv"));
    let mut out = words[..5].to_vec();
    let mut at = 5;
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let mut instruction = words[at..at + count].to_vec();
        if edit(words[at] & 0xffff, &mut instruction) {
            out.extend(instruction);
        }
        at += count;
    }
    write_words(&dir.join(name), &out)
}

#[test]
fn compare_takes_a_folder_of_modules_and_a_single_module_file() {
    let dir = tempfile::tempdir().unwrap();
    let folder = glsl_folder(dir.path());
    let folder_arg = folder.to_string_lossy().into_owned();
    let raygen = repo().join("spirv/glsl/raygen.spv").to_string_lossy().into_owned();
    let mix = format!("rust,raygen={raygen}");
    let args = ["--validate", "compare", "--a", &mix, "--b", &folder_arg, "--width", "64", "--height", "48"];
    let out = twinray(&[&args[..], &UNTIMED, &["--json"]].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("compare --json prints JSON");
    assert_eq!(json["set_a"], mix.as_str());
    assert_eq!(json["set_b"], folder_arg.as_str());
    assert_eq!(json["pass"], true);
    // The folder holds the GLSL set itself: the two renders agree to the bit with the built-in one.
    let same = ["compare", "--a", "glsl", "--b", &folder_arg, "--width", "64", "--height", "48"];
    let out = twinray(&[&same[..], &UNTIMED, &["--json"]].concat(), dir.path());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!((json["rmse"].as_f64(), json["hit_mismatches"].as_u64()), (Some(0.0), Some(0)));
}

/// A closest-hit module as rust-gpu writes it, before the pass that adds NonUniform: it
/// renders right here (lavapipe reads the right texture anyway), and its texture access is
/// reported, naming the file, the stage and the access.
#[test]
fn a_texture_indexed_per_hit_without_non_uniform_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let module = repo().join("shaders-rs/compile/testdata/triangle_closest_hit.undecorated.spv");
    let set = format!("rust,triangle_closest_hit={}", module.display());
    let out = twinray(&["render", "meshes", "--shaders", &set, "--width", "32", "--height", "24"], dir.path());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let line = stderr.lines().find(|l| l.contains("NonUniform")).unwrap_or_else(|| panic!("no report in {stderr}"));
    assert!(line.contains("triangle_closest_hit.undecorated.spv (closest_hit stage)"), "{line}");
    assert!(line.contains("OpAccessChain") && line.contains("binding 12") && line.contains("InstanceId"), "{line}");
    let clean = twinray(&["render", "meshes", "--shaders", "rust", "--width", "32", "--height", "24"], dir.path());
    assert!(!String::from_utf8_lossy(&clean.stderr).contains("NonUniform"));
}

#[test]
fn a_folder_without_a_needed_module_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let folder = glsl_folder(dir.path());
    std::fs::remove_file(folder.join("sphere_intersection.spv")).unwrap();
    let folder_arg = folder.to_string_lossy().into_owned();
    assert_bad_input(
        &["compare", "--b", &folder_arg, "--width", "8", "--height", "8"],
        &["no module sphere_intersection", "sphere_intersection.spv does not exist"],
    );
    // A scene without spheres does not need it.
    let out = twinray(&["render", "box", "--shaders", &folder_arg, "--width", "8", "--height", "8"], dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn bad_modules_are_refused_with_the_file_and_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = d.join("text.spv");
    std::fs::write(&text, "#version 460\nvoid main() {}\n").unwrap();
    let old = {
        let mut w = words(&repo().join("spirv/rust/raygen.spv"));
        w[1] = 0x0001_0300;
        write_words(&d.join("old.spv"), &w)
    };
    // OpEntryPoint is opcode 15; OpDecorate (71) with Binding (33) gets an unknown number.
    let no_entry = edited_raygen(d, "no-entry.spv", |op, _| op != 15);
    let unknown_binding = edited_raygen(d, "binding.spv", |op, i| {
        if op == 71 && i.get(2) == Some(&33) {
            i[3] = 99;
        }
        true
    });
    // A module twinray built, recording another contract version than this build speaks.
    let other_contract = {
        let bytes = std::fs::read(repo().join("spirv/rust/raygen.spv")).unwrap();
        let path = d.join("other-contract.spv");
        std::fs::write(&path, twinray_shared::spirv_info::with_record(&bytes, "twinray-shared 9.0.0").unwrap())
            .unwrap();
        path.to_string_lossy().into_owned()
    };
    let miss = repo().join("spirv/glsl/miss.spv").to_string_lossy().into_owned();
    let text = text.to_string_lossy().into_owned();
    let cases = [
        (format!("rust,raygen={text}"), vec![text.as_str(), "not a SPIR-V module"]),
        (format!("rust,raygen={old}"), vec![old.as_str(), "SPIR-V 1.3, where twinray reads 1.4 to 1.6"]),
        (format!("rust,raygen={miss}"), vec![miss.as_str(), "no raygen entry point", "a miss entry point \"main\""]),
        (format!("glsl,raygen={no_entry}"), vec![no_entry.as_str(), "no raygen entry point", "it has none"]),
        (format!("rust,raygen={unknown_binding}"), vec![unknown_binding.as_str(), "binding 99"]),
        (
            format!("rust,raygen={other_contract}"),
            vec![
                other_contract.as_str(),
                "built against twinray-shared 9.0.0",
                twinray_shared::contract::CONTRACT_VERSION,
            ],
        ),
        (
            format!("rust,intersection={miss}"),
            vec!["the intersection stage has several modules", "sphere_intersection"],
        ),
        ("rust,raygen=no/such.spv".to_string(), vec!["no/such.spv: no such file or folder"]),
        (miss.clone(), vec!["a base set is rust, glsl or a folder"]),
    ];
    for (set, needles) in &cases {
        let needles: Vec<&str> = needles.clone();
        assert_bad_input(&["render", "--shaders", set, "--out", "x.png"], &needles);
    }
    // The same check for a bad file inside a folder set.
    let folder = glsl_folder(d);
    std::fs::copy(d.join("old.spv"), folder.join("raygen.spv")).unwrap();
    let folder_arg = folder.to_string_lossy().into_owned();
    assert_bad_input(&["compare", "--a", &folder_arg], &["raygen.spv", "SPIR-V 1.3, where twinray reads 1.4 to 1.6"]);
}

/// A user's module compiled the usual way, for Vulkan 1.2 (SPIR-V 1.5) or 1.3 (SPIR-V 1.6):
/// the GLSL raygen stage through glslang with `--target-env vulkan1.2` and `vulkan1.3` renders
/// the same image as the committed SPIR-V 1.4 build (under validation), and `inspect` reads it.
#[test]
fn modules_compiled_for_vulkan_1_2_and_1_3_render() {
    let dir = tempfile::tempdir().unwrap();
    for (env, version) in [("vulkan1.2", 5u32), ("vulkan1.3", 6)] {
        let spv = dir.path().join(format!("raygen-{env}.spv"));
        let out = std::process::Command::new("glslangValidator")
            .args(["-V", "--target-env", env])
            .arg(format!("-I{}", repo().join("shaders-glsl").display()))
            .arg("-o")
            .args([&spv, &repo().join("shaders-glsl/raygen.rgen")])
            .output()
            .expect("glslangValidator (cargo xtask setup installs it)");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stdout));
        assert_eq!(words(&spv)[1], 0x0001_0000 | (version << 8), "glslang wrote SPIR-V 1.{version}");
        let set = format!("glsl,raygen={}", spv.display());
        let args = ["--validate", "compare", "--a", "glsl", "--b", &set, "--width", "64", "--height", "48"];
        let out = twinray(&[&args[..], &UNTIMED, &["--json"]].concat(), dir.path());
        assert!(out.status.success(), "{env}: {}", String::from_utf8_lossy(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
        assert_eq!((json["rmse"].as_f64(), json["hit_mismatches"].as_u64()), (Some(0.0), Some(0)), "{env}");
        let out = twinray(&["inspect", "--a", &set, "--b", "glsl"], dir.path());
        assert!(out.status.success(), "{env}: {}", String::from_utf8_lossy(&out.stderr));
    }
}
