//! The on-disk pipeline cache through the `twinray` command: cold, then warm from the file a
//! render wrote; a damaged file ignored and replaced; `--no-pipeline-cache` writes nothing.

use std::path::Path;
use twinray_tests::cli::twinray;

/// `twinray --pipeline-cache DIR info --json`'s pipeline cache: (file, bytes read).
fn cache_state(dir: &Path, work: &Path) -> (String, u64) {
    let out = twinray(&["--pipeline-cache", &dir.to_string_lossy(), "info", "--json"], work);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let cache = &json["pipeline_cache"];
    (cache["file"].as_str().unwrap().to_string(), cache["loaded_bytes"].as_u64().unwrap())
}

fn render(flags: &[&str], work: &Path) {
    let args = [flags, &["render", "sphere", "--width", "32", "--height", "24", "--out", "r.png"]].concat();
    let out = twinray(&args, work);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// What lavapipe keeps in a pipeline cache is Vulkan's 32-byte header alone (it caches no ray
/// tracing pipeline there); NVIDIA's holds the compiled pipelines. So this checks the round
/// trip of the file, not what a warm cache saves (the bench measures that).
#[test]
fn a_run_leaves_a_cache_the_next_run_reads() {
    let work = tempfile::tempdir().unwrap();
    let dir = work.path().join("cache");
    let (file, cold) = cache_state(&dir, work.path());
    assert_eq!(cold, 0, "a new cache folder starts cold");
    assert!(std::fs::metadata(&file).is_ok_and(|m| m.len() >= 24 + 32), "the cache was not written at exit");
    let flags = ["--pipeline-cache", dir.to_str().unwrap()];
    render(&flags, work.path());
    let (again, warm) = cache_state(&dir, work.path());
    assert_eq!(file, again, "one file per device and driver");
    assert!(warm >= 32, "the cache written at exit was not read back");
    // A damaged file is ignored (cold), the render still works, and the file is rewritten.
    let mut bytes = std::fs::read(&file).unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 0xff;
    std::fs::write(&file, &bytes).unwrap();
    assert_eq!(cache_state(&dir, work.path()).1, 0, "a damaged cache must not be read");
    render(&flags, work.path());
    assert!(cache_state(&dir, work.path()).1 > 0, "the damaged cache was not replaced");
}

#[test]
fn no_pipeline_cache_reads_and_writes_nothing() {
    let work = tempfile::tempdir().unwrap();
    let home = work.path().join("home");
    std::fs::create_dir(&home).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_twinray"))
        .args(["--no-pipeline-cache", "render", "sphere", "--width", "32", "--height", "24", "--out", "r.png"])
        .current_dir(work.path())
        .env("XDG_CACHE_HOME", &home)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // Mesa keeps its own shader cache there (mesa_shader_cache); twinray's folder must not appear.
    assert!(!home.join("twinray").exists(), "--no-pipeline-cache wrote into twinray's cache folder");
    let both = twinray(&["--no-pipeline-cache", "--pipeline-cache", "x", "info"], work.path());
    assert_eq!(both.status.code(), Some(2), "the two flags conflict");
}

/// `pipeline-bench` times every configuration, each in a process of its own, and linked
/// against whole trace time; it writes its table and rows; bad input is refused.
#[test]
fn pipeline_bench_writes_a_row_per_configuration() {
    let work = tempfile::tempdir().unwrap();
    let trace = [
        "--trace-scenes",
        "sphere",
        "--width",
        "48",
        "--height",
        "32",
        "--runs",
        "3",
        "--warmup",
        "0",
        "--placements",
        "2",
    ];
    let args = ["pipeline-bench", "sphere", "--repeats", "1", "--thread-counts", "1", "--out", "pb"];
    let out = twinray(&[&args[..], &trace[..]].concat(), work.path());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let results: serde_json::Value =
        serde_json::from_slice(&std::fs::read(work.path().join("pb/results.json")).unwrap()).unwrap();
    let rows = results["creation"].as_array().unwrap();
    // Whole and linked, 2 sets and 16 mixes, cold and warm.
    assert_eq!(rows.len(), 8);
    assert!(rows.iter().all(|r| r["ms"].as_f64().is_some_and(|ms| ms > 0.0)));
    let linked_mixes = rows.iter().find(|r| r["pipelines"] == "libraries" && r["sets"] == 16).unwrap();
    assert!(linked_mixes["libraries"].as_u64().is_some_and(|n| n > 0 && n < 16 * 4), "{linked_mixes}");
    // Rust and GLSL, whole against linked, each timed in two placements.
    let linking = results["linking"].as_array().unwrap();
    assert_eq!(linking.len(), 2);
    for row in linking {
        assert_eq!(row["identical"], true, "{row}");
        assert_eq!(row["whole"]["samples"], 6, "3 runs in each of 2 placements: {row}");
        assert!(row["ratio"]["ratio"].as_f64().is_some_and(|r| r > 0.0), "{row}");
        assert_eq!(row["ratio"]["placements"], 2, "{row}");
    }
    let table = std::fs::read_to_string(work.path().join("pb/table.md")).unwrap();
    assert!(table.contains("| Libraries |") && table.contains("| sphere | 48x32 | rust |"), "{table}");
    assert!(!work.path().join("pb/caches").exists(), "the bench's cache files are removed");
    let bad = twinray(&["pipeline-bench", "--thread-counts", "0"], work.path());
    assert_eq!(bad.status.code(), Some(2));
    let bad = twinray(&["pipeline-bench", "--trace-scenes", "sphere,nosuchscene"], work.path());
    assert_eq!(bad.status.code(), Some(2), "{}", String::from_utf8_lossy(&bad.stderr));
    let bad = twinray(&["pipeline-bench", "--measure-one", "{}"], work.path());
    assert_eq!(bad.status.code(), Some(2), "{}", String::from_utf8_lossy(&bad.stderr));
}
