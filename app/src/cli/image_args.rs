//! Which still image a command looks at (`--frame`, `--eye`, `--look-at`), as clap reads
//! them: shared by `render`, `compare` and `explain`.

use clap::Args;

/// Which still image of a scene: a frame of a moving scene, seen from where the scene puts
/// the camera or from elsewhere (what `twinray view`'s frame slider and camera ask for).
#[derive(Args, Clone, Default)]
pub struct ViewpointArgs {
    /// The frame of an animated scene (0 to its frame count - 1), rendered as a still image
    /// [default: 0].
    #[arg(long, value_name = "K")]
    pub frame: Option<u32>,
    /// Put the camera's eye here, in world space, instead of where the scene puts it.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true)]
    pub eye: Option<[f32; 3]>,
    /// Aim the camera at this point instead of the scene's camera target.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true)]
    pub look_at: Option<[f32; 3]>,
}

impl ViewpointArgs {
    /// Whether any flag was given (they make a still image, so `--frames` refuses them).
    pub fn given(&self) -> bool {
        self.frame.is_some() || self.eye.is_some() || self.look_at.is_some()
    }
}

/// "X,Y,Z" as a point of three finite numbers.
fn parse_point(text: &str) -> Result<[f32; 3], String> {
    let bad = || format!("a point is X,Y,Z with three finite numbers (got {text:?})");
    let values: Vec<f32> = text.split(',').map(|v| v.trim().parse().map_err(|_| bad())).collect::<Result<_, _>>()?;
    let point: [f32; 3] = values.try_into().map_err(|_| bad())?;
    if point.iter().all(|v| v.is_finite()) {
        Ok(point)
    } else {
        Err(bad())
    }
}
