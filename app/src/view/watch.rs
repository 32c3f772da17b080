//! Saves the live loop follows: notify's events (inotify on Linux) for the folders and files a
//! view depends on, as `Trigger::Saved`. Only writes, creations, renames and removals count:
//! reading a file (a build reads every include) is an event too, and must not start a build.

use super::live::Trigger;
use notify::event::{AccessKind, AccessMode, ModifyKind};
use notify::{Event, EventKind, RecommendedWatcher, RecursiveMode, Watcher};
use std::path::{Path, PathBuf};
use tokio::sync::mpsc::UnboundedSender;

/// Watches `dirs` (with everything under them) and `files`; stops when dropped.
pub fn watch(
    dirs: Vec<PathBuf>,
    files: Vec<PathBuf>,
    triggers: UnboundedSender<Trigger>,
) -> notify::Result<RecommendedWatcher> {
    let (wanted_dirs, wanted_files) = (dirs.clone(), files.clone());
    let mut watcher = notify::recommended_watcher(move |result: notify::Result<Event>| {
        let Ok(event) = result else { return };
        if !is_save(&event.kind) {
            return;
        }
        let paths: Vec<PathBuf> = event
            .paths
            .into_iter()
            .filter(|p| !is_editor_scratch(p) && !is_build_output(p, &wanted_dirs))
            .filter(|p| wanted_files.contains(p) || wanted_dirs.iter().any(|d| p.starts_with(d)))
            .collect();
        if !paths.is_empty() {
            let _ = triggers.send(Trigger::Saved(paths));
        }
    })?;
    for dir in &dirs {
        watcher.watch(dir, RecursiveMode::Recursive)?;
    }
    // A file is watched through its folder: editors save by writing a new file and renaming
    // it over the old one, which a watch on the old file would not see.
    for file in &files {
        watcher.watch(file.parent().unwrap_or(Path::new("/")), RecursiveMode::NonRecursive)?;
    }
    Ok(watcher)
}

/// Whether an event changes what a file holds (not its metadata, not a read).
fn is_save(kind: &EventKind) -> bool {
    match kind {
        EventKind::Create(_) | EventKind::Remove(_) => true,
        EventKind::Modify(ModifyKind::Metadata(_)) => false,
        EventKind::Modify(_) => true,
        EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
        _ => false,
    }
}

/// Whether `path` is under a `target/` folder inside a watched folder: a source folder's build
/// writes its set there, and must not start a build of its own.
fn is_build_output(path: &Path, dirs: &[PathBuf]) -> bool {
    dirs.iter()
        .filter_map(|d| path.strip_prefix(d).ok())
        .any(|rest| rest.components().any(|c| c.as_os_str() == "target"))
}

/// Swap, backup and lock files editors write beside a file being edited.
fn is_editor_scratch(path: &Path) -> bool {
    let name = path.file_name().map(|n| n.to_string_lossy()).unwrap_or_default();
    name.starts_with(".#") || name.ends_with('~') || name.ends_with(".swp") || name.ends_with(".swx") || name == "4913"
}

#[cfg(test)]
mod tests {
    use super::*;
    use notify::event::{CreateKind, DataChange, MetadataKind};

    #[test]
    fn reads_and_metadata_are_not_saves() {
        assert!(is_save(&EventKind::Modify(ModifyKind::Data(DataChange::Content))));
        assert!(is_save(&EventKind::Create(CreateKind::File)));
        assert!(is_save(&EventKind::Access(AccessKind::Close(AccessMode::Write))));
        assert!(!is_save(&EventKind::Access(AccessKind::Open(AccessMode::Any))));
        assert!(!is_save(&EventKind::Access(AccessKind::Close(AccessMode::Read))));
        assert!(!is_save(&EventKind::Modify(ModifyKind::Metadata(MetadataKind::AccessTime))));
        assert!(is_editor_scratch(Path::new("/s/.miss.rmiss.swp")) && !is_editor_scratch(Path::new("/s/miss.rmiss")));
        let dirs = [PathBuf::from("/crate")];
        assert!(is_build_output(Path::new("/crate/target/twinray/set/raygen.spv"), &dirs));
        assert!(!is_build_output(Path::new("/crate/src/hit.rs"), &dirs));
    }
}
