//! What a shader set's spec asks of the live loop: which built-in sets it names (rebuilt from
//! sources when a checkout has them) and which folders and files of modules it reads (watched).
//! Specs stay text: each render's child process parses them afresh, so a module broken by a
//! save is that render's error, not the server's.

use std::collections::BTreeMap;
use std::path::PathBuf;
use twinray_shared::catalog::Language;

/// Folders of fresh modules, by the name of the built-in set they replace.
pub type Built = BTreeMap<&'static str, PathBuf>;

/// The items of a spec: the base (key `None`) and each `KEY=VALUE`, trimmed.
fn items(spec: &str) -> Vec<(Option<&str>, &str)> {
    spec.split(',')
        .map(str::trim)
        .enumerate()
        .map(|(i, part)| match part.split_once('=') {
            Some((k, v)) if i > 0 => (Some(k.trim()), v.trim()),
            _ => (None, part),
        })
        .collect()
}

fn language(word: &str) -> Option<Language> {
    Language::ALL.into_iter().find(|l| l.name().eq_ignore_ascii_case(word))
}

/// The built-in sets `spec` names, each once.
pub fn languages(spec: &str) -> Vec<Language> {
    let named: Vec<Language> = items(spec).iter().filter_map(|(_, v)| language(v)).collect();
    Language::ALL.into_iter().filter(|l| named.contains(l)).collect()
}

/// `spec` with every built-in set found in `built` replaced by its folder of fresh modules.
pub fn rewrite(spec: &str, built: &Built) -> String {
    let value = |v: &str| match language(v).and_then(|l| built.get(l.name())) {
        Some(dir) => dir.display().to_string(),
        None => v.to_string(),
    };
    let parts: Vec<String> = items(spec)
        .into_iter()
        .map(|(k, v)| match k {
            Some(k) => format!("{k}={}", value(v)),
            None => value(v),
        })
        .collect();
    parts.join(",")
}

/// The folders and module files `spec` reads from disk: a save to one re-renders.
pub fn watched(spec: &str) -> Vec<PathBuf> {
    items(spec).into_iter().filter(|(_, v)| language(v).is_none()).map(|(_, v)| PathBuf::from(v)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn built_in_sets_become_their_fresh_folders_and_the_rest_is_kept() {
        let built = Built::from([("glsl", PathBuf::from("/b/glsl"))]);
        assert_eq!(rewrite("glsl", &built), "/b/glsl");
        assert_eq!(rewrite("rust, intersection = glsl", &built), "rust,intersection=/b/glsl");
        assert_eq!(rewrite("/my/set,raygen=x.spv", &built), "/my/set,raygen=x.spv");
        assert_eq!(languages("rust,intersection=GLSL,miss=rust"), Language::ALL);
        assert!(languages("/my/set").is_empty());
        assert_eq!(watched("rust,sphere_intersection=/a/s.spv,miss=/m"), [PathBuf::from("/a/s.spv"), "/m".into()]);
    }
}
