//! Progress of long GPU work, reported to whoever asked for it: the command line shows a bar;
//! a library user may install their own sink, or none (then reports go nowhere).

use std::sync::OnceLock;

/// Receives (what, done, total) as long work advances.
pub type Sink = Box<dyn Fn(&str, u64, u64) + Send + Sync>;

static SINK: OnceLock<Sink> = OnceLock::new();

/// Installs the process's progress sink; a second call leaves the first in place.
pub fn set_sink(sink: Sink) {
    let _ = SINK.set(sink);
}

/// Reports that `done` of `total` steps of `what` are finished.
pub fn report(what: &str, done: u64, total: u64) {
    if let Some(sink) = SINK.get() {
        sink(what, done, total);
    }
}
