//! `[camera]` of the scene format: a perspective camera, or an orthographic one.

use serde::Deserialize;

/// `[camera]`: where it is, where it looks, and its vertical field of view, or for an
/// orthographic camera the height of what it sees.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub up: [f32; 3],
    #[serde(default = "default_fov")]
    pub fov_y_degrees: f32,
    /// An orthographic camera: the height, in scene units, of the view it sees (its width
    /// follows the image's aspect); its rays are parallel, each from its point of the plane
    /// through `eye` facing `target`. `None`: a perspective camera of `fov_y_degrees`.
    #[serde(default)]
    pub orthographic_height: Option<f32>,
}

fn default_fov() -> f32 {
    45.0
}

impl CameraDesc {
    /// A perspective camera at `eye` looking at `target`.
    pub fn perspective(eye: [f32; 3], target: [f32; 3], up: [f32; 3], fov_y_degrees: f32) -> CameraDesc {
        CameraDesc { eye, target, up, fov_y_degrees, orthographic_height: None }
    }
}
