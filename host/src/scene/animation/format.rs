//! `[animation]` as a scene file writes it (`docs/scene-format.md`, "Animation"), as serde
//! reads it. `resolve.rs` checks it against the scene and turns it into an [`Animation`].
//!
//! [`Animation`]: super::Animation

use serde::Deserialize;

fn default_fps() -> f32 {
    24.0
}

fn up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}

/// `[animation]`: how many frames, how fast, and what moves.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnimationDesc {
    /// Frames 0..frames, frame k at time k / fps seconds.
    pub frames: u32,
    #[serde(default = "default_fps")]
    pub fps: f32,
    /// Keyframed properties, applied first.
    #[serde(default)]
    pub tracks: Vec<TrackDesc>,
    /// Shorthand motions, applied after the tracks, in file order.
    #[serde(default)]
    pub motions: Vec<MotionDesc>,
}

/// One property of one target, keyframed.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackDesc {
    /// `"camera"`, `"object N"` or `"light N"` (counted from 0 in file order).
    pub target: String,
    /// Which property (see the docs' table per target).
    pub property: String,
    #[serde(default)]
    pub interpolation: Interpolation,
    /// At least one; times strictly increasing.
    pub keys: Vec<KeyDesc>,
}

/// A value at a time (seconds).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyDesc {
    pub time: f32,
    pub value: Value,
}

/// A keyframe value: one number (intensity, field of view, a uniform scale) or three.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum Value {
    Scalar(f32),
    Vector([f32; 3]),
}

impl Value {
    /// The three numbers of the value, a scalar repeated.
    pub fn axes(self) -> [f32; 3] {
        match self {
            Value::Scalar(s) => [s; 3],
            Value::Vector(v) => v,
        }
    }
}

/// How a track moves between two keys.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Interpolation {
    /// At constant speed.
    #[default]
    Linear,
    /// Easing in and out of each key: smoothstep, 3u^2 - 2u^3 of the linear fraction u.
    Smooth,
}

/// A common motion, written once: about an axis, up and down, or turning on the spot.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum MotionDesc {
    /// A turn about the line through `center` along `axis` every `period` seconds,
    /// right-handed, starting `phase` degrees in; the k-th of a grid's K objects starts
    /// `phase_step` x k degrees further and turns with period x (1 + `period_spread` x k / K),
    /// so neighbours drift apart.
    Orbit {
        target: String,
        #[serde(default)]
        center: [f32; 3],
        #[serde(default = "up")]
        axis: [f32; 3],
        period: f32,
        #[serde(default)]
        phase: f32,
        #[serde(default)]
        phase_step: f32,
        #[serde(default)]
        period_spread: f32,
    },
    /// `height` x |sin(180 t / period + phase)| along `axis`: one bounce per `period` seconds.
    Bounce {
        target: String,
        height: f32,
        period: f32,
        #[serde(default = "up")]
        axis: [f32; 3],
        #[serde(default)]
        phase: f32,
        #[serde(default)]
        phase_step: f32,
        #[serde(default)]
        period_spread: f32,
    },
    /// `degrees_per_second` added to the rotation (x, y, z Euler angles) over time.
    Spin { target: String, degrees_per_second: [f32; 3] },
}

impl MotionDesc {
    /// The target as written.
    pub fn target(&self) -> &str {
        match self {
            MotionDesc::Orbit { target, .. } | MotionDesc::Bounce { target, .. } | MotionDesc::Spin { target, .. } => {
                target
            }
        }
    }

    /// The kind as written.
    pub fn kind(&self) -> &'static str {
        match self {
            MotionDesc::Orbit { .. } => "orbit",
            MotionDesc::Bounce { .. } => "bounce",
            MotionDesc::Spin { .. } => "spin",
        }
    }
}
