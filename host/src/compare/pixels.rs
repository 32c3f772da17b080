//! The pixels a compare names for `twinray explain`: those whose colours differ most, and the
//! hit mismatches, a few of each, each with the command that explains it.

use super::diff::ImageDiff;
use crate::render::RenderOutput;
use crate::scene::Scene;
use serde::Serialize;

/// How many pixels of each kind a compare names.
pub const NAMED_PIXELS: usize = 3;

/// A pixel a compare names, and the `twinray explain` line that shows its rays.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NamedPixel {
    pub x: u32,
    pub y: u32,
    /// The largest 8-bit channel difference.
    pub steps: u8,
    /// Whether the two sets' first samples hit different things (or one missed).
    pub hit_mismatch: bool,
    pub explain: String,
}

/// Up to `NAMED_PIXELS` pixels over `threshold` steps with the largest differences, then up to
/// `NAMED_PIXELS` hit mismatches not named yet (the largest differences first; ties in reading
/// order), with their explain lines for `scene` at the renders' size with sets `a` and `b`
/// (at `frame` of a moving scene). Pixels `diff` sets apart (`ImageDiff::is_set_apart`) are not
/// hit mismatches.
pub fn named_pixels(
    scene: &Scene,
    (a, b): (&RenderOutput, &RenderOutput),
    (threshold, diff): (u8, &ImageDiff),
    sets: (&str, &str),
    frame: Option<u32>,
) -> Vec<NamedPixel> {
    let steps = |i: usize| (0..3).map(|c| a.rgba[4 * i + c].abs_diff(b.rgba[4 * i + c])).max().unwrap_or(0);
    let mismatch = |i: usize| a.hit_ids[i] != b.hit_ids[i] && !diff.is_set_apart(i);
    let mut by_steps: Vec<(u8, bool, usize)> = (0..a.hit_ids.len()).map(|i| (steps(i), mismatch(i), i)).collect();
    // Largest first; in reading order among equals.
    by_steps.sort_by(|p, q| q.0.cmp(&p.0).then(p.2.cmp(&q.2)));
    let mut named: Vec<(u8, bool, usize)> =
        by_steps.iter().filter(|p| p.0 > threshold).take(NAMED_PIXELS).copied().collect();
    let mismatches = by_steps.iter().filter(|p| p.1 && !named.iter().any(|n| n.2 == p.2)).take(NAMED_PIXELS);
    named.extend(mismatches.copied().collect::<Vec<_>>());
    let width = a.width as usize;
    named
        .into_iter()
        .map(|(steps, hit_mismatch, i)| {
            let (x, y) = ((i % width) as u32, (i / width) as u32);
            let explain = explain_line(scene, (a.width, a.height), (x, y), sets, frame);
            NamedPixel { x, y, steps, hit_mismatch, explain }
        })
        .collect()
}

/// The `twinray explain` command for pixel `(x, y)` of `scene` rendered at `size` (at `frame`).
pub fn explain_line(
    scene: &Scene,
    size: (u32, u32),
    (x, y): (u32, u32),
    (a, b): (&str, &str),
    frame: Option<u32>,
) -> String {
    let source = scene.source.strip_prefix("builtin:").unwrap_or(&scene.source);
    let mut line = format!("twinray explain {} --pixel {x},{y} --a {} --b {}", quoted(source), quoted(a), quoted(b));
    if size != (scene.file.image.width, scene.file.image.height) {
        line += &format!(" --width {} --height {}", size.0, size.1);
    }
    if let Some(k) = frame {
        line += &format!(" --frame {k}");
    }
    line
}

/// The named pixels as report lines: "  pixel 12,40 (9 steps, hit mismatch): twinray explain ..."
/// each after `indent`.
pub fn pixel_lines(pixels: &[NamedPixel], indent: &str) -> String {
    let mut s = String::new();
    for p in pixels {
        let what =
            if p.hit_mismatch { format!("{} steps, hit mismatch", p.steps) } else { format!("{} steps", p.steps) };
        s += &format!("{indent}pixel {},{} ({what}): {}\n", p.x, p.y, p.explain);
    }
    s
}

/// `text` as one shell word.
fn quoted(text: &str) -> String {
    let plain = text.chars().all(|c| c.is_ascii_alphanumeric() || "-_./,=:+@".contains(c));
    if plain && !text.is_empty() {
        text.to_string()
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
    }
}
