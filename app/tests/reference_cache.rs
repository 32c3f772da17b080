//! Reference cache files that are corrupted, truncated, foreign or not files at all: `twinray
//! reference` (and the bench, which reads the cache through the same function) must notice,
//! render again and overwrite them, never read garbage and never hang.

use std::path::Path;
use twinray_tests::cli::twinray;

/// Runs `twinray reference` of the default scene at 8x8 and 1 spp into `cache`: whether it
/// came from the cache, and the file's path.
fn reference(cache: &Path) -> (bool, String) {
    let dir = tempfile::tempdir().unwrap();
    let cache = cache.to_str().unwrap();
    let args = ["reference", "--spp", "1", "--width", "8", "--height", "8", "--cache", cache, "--json", "--validate"];
    let out = twinray(&args, dir.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    (json["cached"].as_bool().unwrap(), json["path"].as_str().unwrap().to_string())
}

#[test]
fn damaged_cache_files_are_rendered_again() {
    let cache = tempfile::tempdir().unwrap();
    let (cached, path) = reference(cache.path());
    assert!(!cached, "an empty cache has nothing to read");
    let good = std::fs::read(&path).unwrap();
    assert_eq!(reference(cache.path()), (true, path.clone()), "a good file is read");
    let mut flipped = good.clone();
    flipped[good.len() / 2] ^= 0x01;
    let mut old_format = good.clone();
    old_format[..8].copy_from_slice(b"TWREF1\0\0");
    let damages: [(&str, Vec<u8>); 6] = [
        ("one bit flipped in a pixel", flipped),
        ("truncated by a byte", good[..good.len() - 1].to_vec()),
        ("a byte appended", [good.as_slice(), &[0]].concat()),
        ("empty", Vec::new()),
        ("a foreign file (a scene)", include_bytes!("../../scenes/spheres.toml").to_vec()),
        ("the previous format's magic", old_format),
    ];
    for (what, bytes) in damages {
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(reference(cache.path()), (false, path.clone()), "{what}: must be rendered again");
        assert_eq!(std::fs::read(&path).unwrap(), good, "{what}: must be overwritten with the same reference");
    }
    // A FIFO in its place: reading it would block forever.
    std::fs::remove_file(&path).unwrap();
    assert!(std::process::Command::new("mkfifo").arg(&path).status().unwrap().success());
    assert_eq!(reference(cache.path()), (false, path.clone()), "a FIFO must be rendered over, not read");
    assert_eq!(std::fs::read(&path).unwrap(), good);
}
