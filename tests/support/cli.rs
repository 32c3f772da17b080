//! What the command-line tests share: running the binary, the bad-input check, and stages
//! planted for them to catch.

use crate::repo_root as repo;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `twinray` binary of the build this test belongs to. Cargo builds a package's binaries
/// before its integration tests and puts them beside `deps/`, where the test binary runs from
/// (`CARGO_BIN_EXE_twinray` is only known to the test crate itself, at compile time).
pub fn exe() -> PathBuf {
    let test = std::env::current_exe().expect("the test binary's path");
    let exe = test.parent().and_then(Path::parent).map(|p| p.join("twinray")).expect("a target folder");
    assert!(exe.is_file(), "{} is missing: command-line tests belong to the twinray package", exe.display());
    exe
}

/// `compare`'s arguments where its verdict is what a test checks, not its times: one timed
/// render of each set, no warm-up, one placement (on lavapipe the two compares of
/// `gltf_cli::meshes_with_shared_diagonals_pass_compare` took 25 s with the defaults, 0.3 s so).
pub const UNTIMED: [&str; 6] = ["--runs", "1", "--warmup", "0", "--placements", "1"];

pub fn twinray(args: &[&str], dir: &Path) -> Output {
    Command::new(exe()).args(args).current_dir(dir).output().expect("running twinray")
}

/// Asserts exit code 2, one line on stderr containing each of `needles`, and an empty `dir`.
pub fn assert_bad_input(args: &[&str], needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = twinray(args, dir.path());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{args:?}: not one line: {stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{args:?}: {stderr:?} does not mention {n:?}");
    }
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "{args:?} left files behind: {left:?}");
}

/// Waits for `child`, killing it past `limit`; `Err` says it ran too long.
pub fn wait_within(
    child: &mut std::process::Child,
    limit: std::time::Duration,
) -> Result<std::process::ExitStatus, String> {
    let start = std::time::Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return Ok(status);
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("still running after {limit:?}"));
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// Set B of the planted formula: the Rust set with the textbook sphere intersection stage.
pub fn naive_sphere() -> String {
    format!("rust,sphere_intersection={}", repo().join("spirv/rust/sphere_naive_intersection.spv").display())
}

/// A user's stage: the GLSL stage file `file` of `shaders-glsl/` with `edit.0` replaced by
/// `edit.1`, compiled by glslang into `dir`; the SPIR-V file.
pub fn planted_glsl(file: &str, edit: (&str, &str), dir: &Path) -> PathBuf {
    planted_include(file, file, edit, dir)
}

/// A user's stage whose edit lies in a file it includes: `stage` of `shaders-glsl/` compiled
/// with `edited` (that file or one it includes) changed as `planted_glsl` changes it. Both go
/// to `dir`, where glslang looks for includes first (the including file's folder).
pub fn planted_include(stage: &str, edited: &str, edit: (&str, &str), dir: &Path) -> PathBuf {
    let source = std::fs::read_to_string(repo().join("shaders-glsl").join(edited)).unwrap();
    let planted = source.replace(edit.0, edit.1);
    assert_ne!(planted, source, "the planted edit must apply to {edited}");
    std::fs::write(dir.join(edited), planted).unwrap();
    if stage != edited {
        std::fs::copy(repo().join("shaders-glsl").join(stage), dir.join(stage)).unwrap();
    }
    let spv = dir.join(format!("planted-{stage}.spv"));
    let out = Command::new("glslangValidator")
        .args(["-V", "--target-env", "spirv1.4"])
        .arg(format!("-I{}", repo().join("shaders-glsl").display()))
        .arg("-o")
        .args([&spv, &dir.join(stage)])
        .output()
        .expect("glslangValidator (cargo xtask setup installs it)");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stdout));
    spv
}

/// `spirv` with one more `OpCapability capability` and `OpExtension extension` declared (at
/// the first instruction that is not a capability, where SPIR-V wants both): a valid module
/// that asks the device for more than it uses.
pub fn with_capability(spirv: &[u8], capability: u32, extension: &str) -> Vec<u8> {
    let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    let mut at = 5;
    while at < words.len() && words[at] & 0xffff == 17 {
        at += (words[at] >> 16) as usize;
    }
    let mut name = extension.as_bytes().to_vec();
    name.resize((name.len() / 4 + 1) * 4, 0);
    let name: Vec<u32> = name.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    let mut added = vec![(2 << 16) | 17, capability, ((1 + name.len() as u32) << 16) | 10];
    added.extend(name);
    let out: Vec<u32> = words[..at].iter().chain(&added).chain(&words[at..]).copied().collect();
    out.iter().flat_map(|w| w.to_le_bytes()).collect()
}
