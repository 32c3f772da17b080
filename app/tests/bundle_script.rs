//! bench/nvidia-run.sh, the script `cargo xtask bundle` ships: valid sh, and every flag it
//! passes to twinray is one the command accepts (it runs far from here, without network, so
//! a typo would cost a whole trip).

use twinray_tests::cli::twinray;
use twinray_tests::repo_root as repo;

#[test]
fn the_bundle_script_parses_and_uses_only_real_flags() {
    let script = repo().join("bench/nvidia-run.sh");
    let status = std::process::Command::new("sh").arg("-n").arg(&script).status().unwrap();
    assert!(status.success(), "sh -n {}", script.display());
    // Continuation lines joined: one line per shell statement.
    let text = std::fs::read_to_string(&script).unwrap().replace("\\\n", " ");
    let dir = tempfile::tempdir().unwrap();
    for command in ["bench", "stability"] {
        let help = String::from_utf8(twinray(&[command, "--help"], dir.path()).stdout).unwrap();
        let line = text.lines().find(|l| l.contains(&format!("$bin {command} "))).expect("the command in the script");
        for flag in line.split_whitespace().filter(|w| w.starts_with("--")) {
            assert!(help.contains(flag), "{command} has no {flag}");
        }
    }
}
