//! Checking `[animation]` against its scene and resolving its targets: every error names the
//! field (`animation.tracks[1].keys[2].time`) and what was expected; values that stay valid
//! only at some frames (a direction interpolated through zero) are caught by posing every frame.

use super::format::{AnimationDesc, MotionDesc, TrackDesc, Value};
use super::pose::{Animation, Cycle, Motion, MotionKind, Property, Target, Track};
use crate::scene::check::{check_camera, check_light, check_placement, finite};
use crate::scene::file::{LightDesc, SceneFile};
use glam::Vec3;

/// Most frames of an animation: a typo (an extra zero or three) would render for hours.
pub const MAX_FRAMES: u32 = 100_000;
/// Highest frame rate.
pub const MAX_FPS: f32 = 1000.0;
/// Most moving values (objects, lights, the camera, one per track or motion) times frames:
/// every frame is posed and checked when the scene loads. `animate-bench`'s 100,000
/// instances over 48 frames is 4.8 million; beyond this, loading would take minutes.
pub const MAX_POSED: u64 = 50_000_000;

type Checked<T> = Result<T, String>;

/// Checks `desc` against `scene` (as written: `object N` counts its `[[objects]]`) and resolves
/// it; `grids` are the object ranges of the scene's grids once expanded.
pub fn resolve(desc: &AnimationDesc, scene: &SceneFile, grids: &[std::ops::Range<usize>]) -> Checked<Animation> {
    if !(1..=MAX_FRAMES).contains(&desc.frames) {
        return Err(format!("animation.frames must be in 1..={MAX_FRAMES} (got {})", desc.frames));
    }
    if !(desc.fps.is_finite() && desc.fps > 0.0 && desc.fps <= MAX_FPS) {
        return Err(format!("animation.fps must be in (0, {MAX_FPS}] (got {})", desc.fps));
    }
    let written = grids.first().map_or(scene.objects.len(), |g| g.start);
    let scope = Scope { scene, written, grids };
    let tracks = desc
        .tracks
        .iter()
        .enumerate()
        .map(|(i, t)| scope.track(t).map_err(|e| format!("animation.tracks[{i}]{e}")))
        .collect::<Checked<Vec<_>>>()?;
    let motions = desc
        .motions
        .iter()
        .enumerate()
        .map(|(i, m)| scope.motion(m).map_err(|e| format!("animation.motions[{i}] ({}){e}", m.kind())))
        .collect::<Checked<Vec<_>>>()?;
    let moving: u64 = tracks
        .iter()
        .map(|t| &t.target)
        .chain(motions.iter().map(|m| &m.target))
        .map(|t| if let Target::Objects(r) = t { r.len() as u64 } else { 1 })
        .sum();
    if moving.saturating_mul(u64::from(desc.frames)) > MAX_POSED {
        return Err(format!(
            "animation: {} frames of {moving} moving values is more than {MAX_POSED} to pose and check; use fewer frames or move fewer objects",
            desc.frames
        ));
    }
    let rest = Box::new(scene.clone());
    let animation = Animation { frames: desc.frames, fps: desc.fps, tracks, motions, rest, owners: None, clip: None };
    check_frames(&animation, scene)?;
    Ok(animation)
}

/// What targets can name.
struct Scope<'a> {
    scene: &'a SceneFile,
    /// Objects written as `[[objects]]`, before the grids' objects.
    written: usize,
    grids: &'a [std::ops::Range<usize>],
}

impl Scope<'_> {
    fn target(&self, text: &str, grids_allowed: bool) -> Checked<Target> {
        let index = |what: &str, count: usize| -> Checked<usize> {
            let n = text.strip_prefix(what).map(str::trim).and_then(|n| n.parse::<usize>().ok());
            match n {
                Some(n) if n < count => Ok(n),
                Some(n) => Err(format!(".target: {text:?}: no {what}{n}: the scene has {count} (counted from 0)")),
                None => Err(format!(".target: {text:?}: expected {what}N")),
            }
        };
        match text.split_whitespace().next().unwrap_or("") {
            "camera" if text.trim() == "camera" => Ok(Target::Camera),
            "object" => index("object ", self.written).map(|i| Target::Objects(i..i + 1)),
            "light" => index("light ", self.scene.lights.len()).map(Target::Light),
            "grid" if grids_allowed => index("grid ", self.grids.len()).map(|g| Target::Objects(self.grids[g].clone())),
            "grid" => Err(format!(".target: {text:?}: grids move by motions only (orbit, bounce, spin)")),
            _ => Err(format!(
                ".target: {text:?}: expected \"camera\", \"object N\", \"light N\"{}",
                if grids_allowed { " or \"grid N\"" } else { "" }
            )),
        }
    }

    fn track(&self, desc: &TrackDesc) -> Checked<Track> {
        let target = self.target(&desc.target, false)?;
        let (property, scalar) = self.property(&target, &desc.property)?;
        if desc.keys.is_empty() {
            return Err(".keys: a track needs at least one key".into());
        }
        let mut keys = Vec::with_capacity(desc.keys.len());
        for (i, key) in desc.keys.iter().enumerate() {
            let at = format!(".keys[{i}]");
            if !key.time.is_finite() {
                return Err(format!("{at}.time must be a finite number of seconds (got {})", key.time));
            }
            if let Some(&(before, _)) = keys.last() {
                if key.time <= before {
                    return Err(format!(
                        "{at}.time: {} is not after the previous key's {before}: keys must be in increasing time order",
                        key.time
                    ));
                }
            }
            let value = match (key.value, scalar) {
                (Value::Scalar(_), Some(true) | None) | (Value::Vector(_), Some(false) | None) => key.value.axes(),
                (_, Some(true)) => return Err(format!("{at}.value: {:?} takes one number", desc.property)),
                (_, Some(false)) => return Err(format!("{at}.value: {:?} takes [x, y, z]", desc.property)),
            };
            finite(&format!("{at}.value"), &value)?;
            keys.push((key.time, value));
        }
        Ok(Track { target, property, interpolation: desc.interpolation, keys })
    }

    /// The property `name` of `target`, and whether it takes one number (`None`: either).
    fn property(&self, target: &Target, name: &str) -> Checked<(Property, Option<bool>)> {
        use Property as P;
        let choices: &[(&str, P, Option<bool>)] = match target {
            Target::Camera => &[
                ("eye", P::Eye, Some(false)),
                ("target", P::LookAt, Some(false)),
                ("up", P::Up, Some(false)),
                ("fov_y_degrees", P::FieldOfView, Some(true)),
            ],
            Target::Objects(_) => &[
                ("translate", P::Translate, Some(false)),
                ("rotate", P::Rotate, Some(false)),
                ("scale", P::Scale, None),
            ],
            Target::Light(i) => light_properties(&self.scene.lights[*i]),
        };
        match choices.iter().find(|(n, ..)| *n == name) {
            Some(&(_, property, scalar)) => Ok((property, scalar)),
            None => {
                let names: Vec<_> = choices.iter().map(|c| c.0).collect();
                Err(format!(".property: {name:?} is not animatable here (choices: {})", names.join(", ")))
            }
        }
    }

    fn motion(&self, desc: &MotionDesc) -> Checked<Motion> {
        let target = self.target(desc.target(), true)?;
        let kind = match *desc {
            MotionDesc::Orbit { center, axis, period, phase, phase_step, period_spread, .. } => {
                finite(".center", &center)?;
                let cycle = cycle(period, phase, phase_step, period_spread)?;
                MotionKind::Orbit { center: center.into(), axis: unit(axis)?, cycle }
            }
            MotionDesc::Bounce { height, period, axis, phase, phase_step, period_spread, .. } => {
                finite(".height", &[height])?;
                MotionKind::Bounce {
                    height,
                    axis: unit(axis)?,
                    cycle: cycle(period, phase, phase_step, period_spread)?,
                }
            }
            MotionDesc::Spin { degrees_per_second, .. } => {
                finite(".degrees_per_second", &degrees_per_second)?;
                MotionKind::Spin { degrees_per_second: degrees_per_second.into() }
            }
        };
        let fits = match (&target, &kind) {
            (Target::Objects(_), _) => true,
            (Target::Camera, kind) => !matches!(kind, MotionKind::Spin { .. }),
            (Target::Light(i), kind) => match (&self.scene.lights[*i], kind) {
                (LightDesc::Rect { .. }, _) => true,
                (LightDesc::Point { .. }, kind) => !matches!(kind, MotionKind::Spin { .. }),
                (LightDesc::Directional { .. }, kind) => matches!(kind, MotionKind::Orbit { .. }),
            },
        };
        if !fits {
            return Err(format!(
                ": {:?} cannot {} (see the table of motions in docs/scene-format.md)",
                desc.target(),
                desc.kind()
            ));
        }
        Ok(Motion { target, kind })
    }
}

fn light_properties(light: &LightDesc) -> &'static [(&'static str, Property, Option<bool>)] {
    use Property as P;
    match light {
        LightDesc::Directional { .. } => &[
            ("direction", P::Direction, Some(false)),
            ("color", P::Color, Some(false)),
            ("intensity", P::Intensity, Some(true)),
        ],
        LightDesc::Point { .. } => &[
            ("position", P::Position, Some(false)),
            ("color", P::Color, Some(false)),
            ("intensity", P::Intensity, Some(true)),
        ],
        LightDesc::Rect { .. } => &[
            ("center", P::Center, Some(false)),
            ("rotate", P::Orientation, Some(false)),
            ("color", P::Color, Some(false)),
            ("intensity", P::Intensity, Some(true)),
        ],
    }
}

fn unit(axis: [f32; 3]) -> Checked<Vec3> {
    finite(".axis", &axis)?;
    Vec3::from(axis).try_normalize().ok_or_else(|| format!(".axis must not be zero (got {axis:?})"))
}

fn cycle(period: f32, phase: f32, phase_step: f32, period_spread: f32) -> Checked<Cycle> {
    if !(period.is_finite() && period > 0.0) {
        return Err(format!(".period must be a positive number of seconds (got {period})"));
    }
    if !(period_spread.is_finite() && (0.0..=1e6).contains(&period_spread)) {
        return Err(format!(".period_spread must be in [0, 1e6] (got {period_spread})"));
    }
    finite(".phase", &[phase])?;
    finite(".phase_step", &[phase_step])?;
    Ok(Cycle { period, phase, phase_step, period_spread })
}

/// Poses every frame and checks what moved as the scene file's own checks would: a value can
/// be valid at every key and invalid between them (a direction interpolated through zero).
fn check_frames(animation: &Animation, scene: &SceneFile) -> Checked<()> {
    let mut posed = scene.clone();
    for frame in 0..animation.frames {
        animation.pose(frame, &mut posed);
        let at = |e: String| format!("animation: frame {frame} (t = {} s): {e}", animation.time(frame));
        for target in animation.targets() {
            match target {
                Target::Camera => check_camera(&posed.camera).map_err(at)?,
                Target::Light(i) => check_light(&posed.lights[*i]).map_err(|e| at(format!("lights[{i}]: {e}")))?,
                Target::Objects(range) => {
                    for i in range.clone() {
                        check_placement(&posed.objects[i]).map_err(|e| at(format!("objects[{i}]: {e}")))?;
                    }
                }
            }
        }
    }
    Ok(())
}
