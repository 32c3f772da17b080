//! Alpha exactly at the cutoff: a glTF quad whose alpha equals its material's cutoff, by its
//! base colour factor, by its vertex colours and by its texture, rendered by both sets with
//! `compare`. A tie is decided alike in both (the surface is there: alpha >= cutoff), so no
//! pixel differs. Without the tie-safe interpolation, the sets interpolated a vertex colour's alpha of 1 to
//! 0.99999994 in one set and 1 in the other, and a BLEND material of alpha 0.5 (tested at 0.5)
//! had hit mismatches in `compare`.

use std::path::Path;
use twinray_tests::cli::{planted_glsl, twinray, UNTIMED};
use twinray_tests::gltf::{Quad, UNIT_UV};

/// One way to put the alpha at the cutoff.
struct Tie {
    what: &'static str,
    /// The material's JSON members besides its base colour texture.
    material: &'static str,
    /// Every vertex's COLOR_0.
    vertex: [f32; 4],
    /// Every texel's RGBA, if the quad has a base colour texture.
    texel: Option<[u8; 4]>,
}

const TIES: [Tie; 4] = [
    Tie {
        what: "BLEND, factor 0.5",
        material: r#""alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.2, 0.5]"#,
        vertex: [1.0; 4],
        texel: None,
    },
    Tie {
        what: "MASK 0.25, factor 0.25",
        material: r#""alphaMode": "MASK", "alphaCutoff": 0.25, "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.6, 0.9, 0.25]"#,
        vertex: [1.0; 4],
        texel: None,
    },
    Tie {
        what: "MASK 0.5, vertex alpha 0.5",
        material: r#""alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]"#,
        vertex: [0.8, 0.4, 0.1, 0.5],
        texel: None,
    },
    Tie {
        // 128/255 as f32, the value the sampler returns for a texel's alpha of 128.
        what: "MASK 128/255, texel alpha 128",
        material: r#""alphaMode": "MASK", "alphaCutoff": 0.501960813999176, "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]"#,
        vertex: [1.0; 4],
        texel: Some([200, 120, 40, 128]),
    },
];

/// A model of one quad in `dir` with the alpha of `tie`; its path.
fn model(dir: &Path, tie: &Tie) -> std::path::PathBuf {
    let texture = tie.texel.map(|texel| image::RgbaImage::from_pixel(8, 8, image::Rgba(texel)));
    quad(dir, tie.material, [tie.vertex; 4], texture.as_ref())
}

/// A model of one unit quad in `dir` with material members `material`, the corners' COLOR_0
/// `colors` and, if given, a base colour `texture`; its path.
fn quad(dir: &Path, material: &str, colors: [[f32; 4]; 4], texture: Option<&image::RgbaImage>) -> std::path::PathBuf {
    Quad { material, colors, uv: UNIT_UV, texture: texture.map(|t| (t, "")) }.write(dir)
}

/// `twinray compare` of the model at `path` at `size`, untimed: its exit status and stdout.
fn compare(path: &Path, (width, height): (&str, &str), extra: &[&str], dir: &Path) -> std::process::Output {
    let size = ["--width", width, "--height", height];
    twinray(&[&["compare", path.to_str().unwrap()][..], &size, &UNTIMED, extra].concat(), dir)
}

#[test]
fn alpha_exactly_at_the_cutoff_is_decided_alike_in_both_sets() {
    for tie in &TIES {
        let dir = tempfile::tempdir().unwrap();
        let path = model(dir.path(), tie);
        let out = compare(&path, ("160", "120"), &[], dir.path());
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{}: {}\n{stdout}", tie.what, String::from_utf8_lossy(&out.stderr));
        assert!(stdout.contains("hit mismatches: 0 (0.000%)"), "{}: {stdout}", tie.what);
        // The surface is there: the quad covers the middle of the picture in both sets.
        let a = image::open(dir.path().join("compare/a.png")).unwrap().to_rgba8();
        let background = *a.get_pixel(0, 0);
        assert_ne!(*a.get_pixel(80, 60), background, "{}: the quad is a hole", tie.what);
    }
}

/// The hit mismatches, and those set apart at a cutout's alpha cutoff, of `compare` of the
/// model at `path` at 161x121 against set `b` (the Rust set is a): its exit code, the two
/// counts, its stdout.
fn against(path: &Path, b: &str, dir: &Path) -> (Option<i32>, u64, u64, String) {
    let out = compare(path, ("161", "121"), &["--b", b], dir);
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    let line = stdout.lines().find(|l| l.contains("hit mismatches:")).unwrap_or_default();
    let after = |words: &str| -> u64 {
        let at = line.find(words).unwrap_or_else(|| panic!("no {words:?} in {stdout}"));
        line[at + words.len()..].split_whitespace().next().unwrap().parse().unwrap()
    };
    let counts = (after("hit mismatches: "), after("edges inside a mesh, "));
    (out.status.code(), counts.0, counts.1, stdout)
}

/// The GLSL set with its triangle any-hit stage's alpha test `alpha < cutoff` replaced by
/// `test`, compiled into a folder of its own under `dir`.
fn planted_test(test: &str, dir: &Path) -> String {
    let own = tempfile::tempdir_in(dir).unwrap().keep();
    let spv = planted_glsl("triangle_cutout.rahit", ("alpha < material.cutout_threshold", test), &own);
    format!("glsl,triangle_cutout_any_hit={}", spv.display())
}

/// A vertex alpha gradient across the quad that stays within rounding of the cutoff (0.5 less
/// 3 f32 ULPs on its left edge, 0.5 and 2 ULPs on its right): a set whose alpha test rounds 4
/// ULPs the other way keeps the left half that the Rust set cuts away. Either is right there,
/// so `compare` sets those pixels apart (the f64 reference finds the alpha at the cutoff) and
/// passes, naming them.
#[test]
fn a_gradient_within_rounding_of_the_cutoff_is_set_apart() {
    let dir = tempfile::tempdir().unwrap();
    let (below, above) = (0.5 - 3.0 * f32::EPSILON / 4.0, 0.5 + 2.0 * f32::EPSILON / 2.0);
    let (left, right) = ([1.0, 0.6, 0.2, below], [1.0, 0.6, 0.2, above]);
    let material = r#""alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]"#;
    let path = quad(dir.path(), material, [left, right, right, left], None);
    let rounds_up = planted_test("alpha * (1.0 + 4.0 * 1.1920929e-7) < material.cutout_threshold", dir.path());
    let (code, mismatches, apart, stdout) = against(&path, &rounds_up, dir.path());
    assert_eq!((code, mismatches), (Some(0), 0), "{stdout}");
    assert!(apart > 1000, "the left half of the quad is set apart: {stdout}");
}

/// A steep gradient across the cutoff (0.1 on the quad's left edge, 0.9 on its right, cut at
/// 0.5 down its middle): the GLSL set agrees with the Rust one, and a set that cuts at 0.55 has
/// the pixels between the two contours as hit mismatches, not set apart, and fails. (At 161
/// pixels across, one column of rays meets the quad exactly at alpha 0.5, a tie: those pixels
/// are set apart, as either answer is right there.)
#[test]
fn a_cutout_cut_elsewhere_is_not_set_apart() {
    let dir = tempfile::tempdir().unwrap();
    let (left, right) = ([1.0, 0.6, 0.2, 0.1], [1.0, 0.6, 0.2, 0.9]);
    let material = r#""alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]"#;
    let path = quad(dir.path(), material, [left, right, right, left], None);
    let (code, mismatches, _, stdout) = against(&path, "glsl", dir.path());
    assert_eq!((code, mismatches), (Some(0), 0), "{stdout}");
    let cut_higher = planted_test("alpha < material.cutout_threshold + 0.05", dir.path());
    let (code, mismatches, apart, stdout) = against(&path, &cut_higher, dir.path());
    assert_eq!(code, Some(1), "{stdout}");
    assert!(mismatches > 3 * apart && mismatches > 150, "{stdout}");
}
