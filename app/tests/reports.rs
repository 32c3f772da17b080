//! bench/reports/ as a reader finds it: at most ten folders, each answering one question with
//! its claim, its command and its runs, every archive named in its README and none missing,
//! no lab material, and the one table script making the scene table from the committed runs.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn reports() -> PathBuf {
    twinray_tests::repo_root().join("bench/reports")
}

fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    out.sort();
    out
}

fn files_under(dir: &Path, out: &mut Vec<PathBuf>) {
    for p in entries(dir) {
        if p.is_dir() {
            files_under(&p, out);
        } else {
            out.push(p);
        }
    }
}

#[test]
fn every_report_folder_answers_one_question_with_its_command_and_runs() {
    let folders: Vec<PathBuf> = entries(&reports()).into_iter().filter(|p| p.is_dir()).collect();
    assert!(!folders.is_empty() && folders.len() <= 10, "{} folders in bench/reports", folders.len());
    let index = std::fs::read_to_string(reports().join("README.md")).unwrap();
    for folder in &folders {
        let name = folder.file_name().unwrap().to_string_lossy().into_owned();
        assert!(index.contains(&format!("({name}/README.md)")), "bench/reports/README.md does not list {name}/");
        let readme = std::fs::read_to_string(folder.join("README.md")).unwrap_or_default();
        assert!(readme.starts_with("# ") && readme.lines().next().unwrap().ends_with('?'), "{name}: no question");
        for part in ["**Claim.**", "**Command.**", "## Runs"] {
            assert!(readme.contains(part), "{name}/README.md has no {part}");
        }
        let archives: BTreeSet<String> = entries(&folder.join("runs"))
            .iter()
            .filter(|p| p.is_file())
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        for archive in &archives {
            assert!(archive.ends_with(".tar.xz"), "{name}/runs/{archive}: not one packed run");
            assert!(readme.contains(&format!("runs/{archive}")), "{name}/README.md does not say what {archive} holds");
        }
        for named in readme.split("`runs/").skip(1).filter_map(|r| r.split('`').next()) {
            assert!(
                folder.join("runs").join(named).exists(),
                "{name}/README.md names runs/{named}, which is not there"
            );
        }
        let mut files = Vec::new();
        files_under(folder, &mut files);
        for f in files {
            let ext = f.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_default();
            assert!(!["py", "patch", "spv"].contains(&ext.as_str()), "lab material in the reports: {}", f.display());
        }
    }
}

#[test]
fn the_table_script_makes_the_scene_table_from_its_runs() {
    let root = twinray_tests::repo_root();
    let out = Command::new("python3")
        .arg("bench/table.py")
        .args(["ratios", "bench/reports/scene-table/runs/y1", "bench/reports/scene-table/runs/y2"])
        .current_dir(&root)
        .output()
        .expect("python3");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // 18 scenes at 1 and 16 spp, as the scene table's README shows them.
    assert_eq!(text.lines().filter(|l| l.starts_with("| ") && !l.starts_with("| scene")).count(), 36, "{text}");
    let readme = std::fs::read_to_string(root.join("bench/reports/scene-table/README.md")).unwrap();
    for line in text.lines().filter(|l| l.starts_with("| ") || l.contains(" of ")) {
        assert!(readme.contains(line), "the README's table is not the script's: {line}");
    }
}
