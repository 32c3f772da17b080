//! The frames of a moving scene: TLAS modes, what a rendered frame holds, and frame ranges as
//! the command line writes them. `moving.rs` renders them.

use super::output::RenderOutput;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::vk::accel::TlasFlags;
use serde::Serialize;
use std::ops::Range;

/// How the TLAS is remade when objects move (`--tlas`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum TlasKind {
    /// A full build every frame, preferring fast trace.
    Rebuild,
    /// A full build every frame, preferring fast build.
    FastBuild,
    /// An in-place update (refit) every frame, with a full build every `rebuild_every` frames.
    Update,
}

/// How the TLAS follows moving objects from frame to frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct TlasMode {
    pub kind: TlasKind,
    /// For `Update`: a full build every this many frames of the sequence (0: only the first).
    pub rebuild_every: u32,
}

/// What `--tlas` and `--rebuild-every` give when left out.
pub const DEFAULT_TLAS: TlasMode = TlasMode { kind: TlasKind::Update, rebuild_every: 30 };

impl TlasMode {
    /// As the command line writes it: "update (rebuild every 30)".
    pub fn name(self) -> String {
        match self.kind {
            TlasKind::Rebuild => "rebuild".into(),
            TlasKind::FastBuild => "fast-build".into(),
            TlasKind::Update if self.rebuild_every == 0 => "update".into(),
            TlasKind::Update => format!("update (rebuild every {})", self.rebuild_every),
        }
    }

    pub(super) fn flags(self) -> TlasFlags {
        match self.kind {
            TlasKind::Rebuild => TlasFlags::FastTrace,
            TlasKind::FastBuild => TlasFlags::FastBuild,
            TlasKind::Update => TlasFlags::Updatable,
        }
    }

    /// The AS work of the `i`-th frame of a sequence (counted from 0) when objects move.
    pub(super) fn work(self, i: u32) -> AsWork {
        let rebuild =
            i == 0 || self.kind != TlasKind::Update || (self.rebuild_every > 0 && i.is_multiple_of(self.rebuild_every));
        if rebuild {
            AsWork::Build
        } else {
            AsWork::Update
        }
    }
}

/// The acceleration-structure work a frame did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AsWork {
    /// A full TLAS build.
    Build,
    /// An in-place TLAS update.
    Update,
    /// Nothing: no object moved since the last frame.
    None,
}

/// One rendered frame.
pub struct Frame {
    pub index: u32,
    /// Seconds into the animation.
    pub time: f32,
    pub as_work: AsWork,
    /// GPU milliseconds of the frame's TLAS work; `None` without work or timestamps.
    pub as_ms: Option<f64>,
    /// One output per set, in the order of the sets.
    pub outputs: Vec<RenderOutput>,
}

/// A frame range must be non-empty and within the scene's frames.
pub fn check_frames(scene: &Scene, frames: &Range<u32>) -> Result<()> {
    let total = scene.frame_count();
    if frames.is_empty() || frames.end > total {
        let still = if scene.animation.is_none() { " (a still scene has one frame, 0)" } else { "" };
        return Err(Error::Input(format!(
            "frames {}..{}: {} has frames 0..{total}{still}; a range needs at least one of them",
            frames.start,
            frames.end,
            scene.name()
        )));
    }
    Ok(())
}

/// A range of frames as the command line writes it: `A..B` (B excluded), `A..=B`, `A`, or
/// `all`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameRange {
    All,
    /// First frame and one past the last.
    Span(u32, u32),
}

impl std::str::FromStr for FrameRange {
    type Err = String;

    fn from_str(text: &str) -> std::result::Result<Self, String> {
        let number = |s: &str| {
            s.trim()
                .parse::<u32>()
                .map_err(|_| format!("{text:?}: expected A..B, A..=B, A or all (frames counted from 0)"))
        };
        let text = text.trim();
        if text == "all" {
            return Ok(FrameRange::All);
        }
        let (start, end) = if let Some((a, b)) = text.split_once("..=") {
            (number(a)?, number(b)?.checked_add(1).ok_or_else(|| format!("{text:?}: too large"))?)
        } else if let Some((a, b)) = text.split_once("..") {
            (number(a)?, number(b)?)
        } else {
            let a = number(text)?;
            (a, a.saturating_add(1))
        };
        if end <= start {
            return Err(format!("{text:?}: an empty range (the end is excluded in A..B; A..=B includes it)"));
        }
        Ok(FrameRange::Span(start, end))
    }
}

impl FrameRange {
    /// The frames of `scene` this range names, checked against its frame count.
    pub fn of(self, scene: &Scene) -> Result<Range<u32>> {
        let frames = match self {
            FrameRange::All => 0..scene.frame_count(),
            FrameRange::Span(a, b) => a..b,
        };
        check_frames(scene, &frames)?;
        Ok(frames)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges_parse_as_the_command_line_writes_them() {
        let parse = |s: &str| s.parse::<FrameRange>();
        assert_eq!(parse("all"), Ok(FrameRange::All));
        assert_eq!(parse("2..5"), Ok(FrameRange::Span(2, 5)));
        assert_eq!(parse("2..=5"), Ok(FrameRange::Span(2, 6)));
        assert_eq!(parse(" 7 "), Ok(FrameRange::Span(7, 8)));
        for bad in ["5..2", "3..3", "x", "1..y", "-1..2", "..", "4294967295..=4294967295"] {
            assert!(parse(bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn update_mode_rebuilds_on_the_first_frame_and_every_n() {
        let works = |mode: TlasMode| (0..5).map(|i| mode.work(i)).collect::<Vec<_>>();
        let (b, u) = (AsWork::Build, AsWork::Update);
        assert_eq!(works(TlasMode { kind: TlasKind::Update, rebuild_every: 0 }), [b, u, u, u, u]);
        assert_eq!(works(TlasMode { kind: TlasKind::Update, rebuild_every: 2 }), [b, u, b, u, b]);
        assert_eq!(works(TlasMode { kind: TlasKind::FastBuild, rebuild_every: 2 }), [b, b, b, b, b]);
        assert_eq!(TlasMode { kind: TlasKind::Update, rebuild_every: 30 }.name(), "update (rebuild every 30)");
    }
}
