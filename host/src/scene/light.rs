//! `[[lights]]` of the scene format: directional, point (spot lights among them) and rect
//! lights.

use serde::Deserialize;

/// A light, by `kind`.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum LightDesc {
    /// `direction` points towards the light.
    Directional {
        direction: [f32; 3],
        color: [f32; 3],
        intensity: f32,
        #[serde(default = "yes")]
        shadows: bool,
    },
    /// A point light, falling off with the square of the distance, to nothing at `range`
    /// (none: it reaches everywhere), and with `spot`, only inside a cone (glTF's
    /// KHR_lights_punctual point and spot lights: `scene::build` writes how).
    Point {
        position: [f32; 3],
        color: [f32; 3],
        intensity: f32,
        #[serde(default = "yes")]
        shadows: bool,
        #[serde(default)]
        range: Option<f32>,
        #[serde(default)]
        spot: Option<SpotDesc>,
    },
    /// A rectangle centred at `center` with edge vectors `u` and `v`, emitting from both faces.
    Rect {
        center: [f32; 3],
        u: [f32; 3],
        v: [f32; 3],
        color: [f32; 3],
        intensity: f32,
        samples: Option<u32>,
        #[serde(default = "yes")]
        shadows: bool,
    },
}

/// A point light's cone: it shines along `direction`, fully within `inner_cone_degrees` of it,
/// fading to nothing at `outer_cone_degrees` (glTF's innerConeAngle and outerConeAngle, whose
/// defaults these are).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SpotDesc {
    pub direction: [f32; 3],
    #[serde(default)]
    pub inner_cone_degrees: f32,
    #[serde(default = "quarter_turn_halved")]
    pub outer_cone_degrees: f32,
}

fn quarter_turn_halved() -> f32 {
    45.0
}

fn yes() -> bool {
    true
}
