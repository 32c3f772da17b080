//! The built-in probe cases: every file of `probes/` and its folders, embedded by
//! `host/build.rs`, so that the cases the docs name run from an installed `twinray`, where no
//! checkout's `probes/` is at hand.

use super::case::ProbeCase;
use crate::error::{Error, Result};
use crate::sets::own::CrateKinds;
use std::path::Path;

include!(concat!(env!("OUT_DIR"), "/builtin_probes.rs"));

/// The built-in case `name` names: its path in probes/, with or without `probes/` before it
/// and `.toml` after it (`far-sphere`, `probes/far-sphere.toml`,
/// `stability/sphere-far-1e5`).
pub fn find(name: &str) -> Option<(&'static str, &'static str)> {
    let name = name.replace('\\', "/");
    let name = name.strip_prefix("./").unwrap_or(&name);
    let name = name.strip_prefix("probes/").unwrap_or(name);
    let name = name.strip_suffix(".toml").unwrap_or(name);
    BUILTIN_PROBES.iter().copied().find(|(n, _)| *n == name)
}

/// The built-in cases of the folder `dir` names (`probes/stability`, `stability`), each as the
/// path `open` takes for it (`probes/stability/NAME.toml`); `None` where it names none.
pub fn folder(dir: &Path) -> Option<Vec<std::path::PathBuf>> {
    let dir = dir.to_str()?.replace('\\', "/");
    let dir = dir.trim_end_matches('/');
    let dir = dir.strip_prefix("./").unwrap_or(dir);
    let dir = dir.strip_prefix("probes/").unwrap_or(dir);
    let prefix = format!("{dir}/");
    let cases: Vec<_> = BUILTIN_PROBES
        .iter()
        .filter_map(|(n, _)| n.strip_prefix(&prefix).filter(|rest| !rest.contains('/')).map(|_| n))
        .map(|n| std::path::PathBuf::from(format!("probes/{n}.toml")))
        .collect();
    (!cases.is_empty()).then_some(cases)
}

/// The case in the file `arg`, or, where no such file is, the built-in case it names.
/// Its scene may name the kinds of the crates' `own` shapes.
pub fn open(arg: &Path, own: &[&'static CrateKinds]) -> Result<ProbeCase> {
    if arg.exists() {
        return ProbeCase::load_with(arg, own);
    }
    let Some((name, text)) = arg.to_str().and_then(find) else {
        let names: Vec<&str> = BUILTIN_PROBES.iter().map(|(n, _)| *n).filter(|n| !n.contains('/')).collect();
        return Err(Error::Input(format!(
            "probe case {}: no such file, nor a built-in case ({}, and stability/NAME for the hard cases)",
            arg.display(),
            names.join(", ")
        )));
    };
    // A built-in case names no file of its own but by an absolute path: there is no folder.
    ProbeCase::parse_with(text, &format!("probes/{name}.toml (built in)"), std::path::PathBuf::new(), own)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_of_probes_is_built_in_and_found_as_the_docs_name_it() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("probes");
        let on_disk = std::fs::read_dir(&root)
            .unwrap()
            .filter(|e| e.as_ref().is_ok_and(|e| e.path().extension().is_some_and(|x| x == "toml")));
        let top = BUILTIN_PROBES.iter().filter(|(n, _)| !n.contains('/')).count();
        assert_eq!(top, on_disk.count(), "a case of probes/ is not built in");
        assert!(BUILTIN_PROBES.iter().filter(|(n, _)| n.starts_with("stability/")).count() >= 24);
        for arg in ["far-sphere", "probes/far-sphere.toml", "./probes/far-sphere.toml", "far-sphere.toml"] {
            assert_eq!(find(arg).map(|(n, _)| n), Some("far-sphere"), "{arg}");
        }
        assert_eq!(find("stability/sphere-far-1e5").map(|(n, _)| n), Some("stability/sphere-far-1e5"));
        let suite = folder(Path::new("probes/stability")).expect("the hard cases are built in");
        assert_eq!(folder(Path::new("./stability/")), Some(suite.clone()));
        assert!(suite.contains(&std::path::PathBuf::from("probes/stability/sphere-far-1e5.toml")));
        assert!(folder(Path::new("probes/nothing")).is_none());
        assert!(find("far-sphere.tomlx").is_none() && find("sphere-far-1e5").is_none());
        // Parsed without a folder (see `open`): a file a case names must not be relative.
        for (name, text) in BUILTIN_PROBES {
            for line in text.lines().filter(|l| l.trim_start().starts_with("file")) {
                assert!(line.contains("= \"/"), "{name}: {line}");
            }
        }
    }

    #[test]
    fn a_name_that_is_neither_a_file_nor_built_in_lists_the_built_in_cases() {
        let e = open(Path::new("no/such/case.toml"), &[]).err().expect("refused").to_string();
        assert!(e.contains("no/such/case.toml") && e.contains("far-sphere") && e.contains("stability/NAME"), "{e}");
    }
}
