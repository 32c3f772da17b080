//! The arguments of the commands that look into one image, as clap reads them: which still
//! image (`--frame`, `--eye`, `--look-at`, shared with `render` and `compare`), `explain` and
//! `view`.

use clap::Args;
use std::path::PathBuf;
use twinray::ShaderSet;

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

#[derive(Args)]
pub struct ExplainArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    pub scene: Option<String>,
    /// The pixel: column X and row Y from the top left, as compare's images number them.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub pixel: (u32, u32),
    /// Set A.
    #[arg(long, default_value = "rust")]
    pub a: ShaderSet,
    /// Set B; without it, set A alone against the f64 reference.
    #[arg(long)]
    pub b: Option<ShaderSet>,
    #[command(flatten)]
    pub viewpoint: ViewpointArgs,
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// What the report calls sets A and B, as A,B [default: their specs, or "set A" and
    /// "set B" where a spec is long].
    #[arg(long, value_name = "A,B", value_parser = parse_names)]
    pub names: Option<(String, String)>,
    /// Also show the pixel of a converged reference image of SPP samples per pixel, rendered
    /// by set A (or read from the cache `twinray reference` keeps).
    #[arg(long, value_name = "SPP")]
    pub converged: Option<u32>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// "A,B" as two names, neither empty.
fn parse_names(text: &str) -> Result<(String, String), String> {
    match text.split_once(',') {
        Some((a, b)) if !a.trim().is_empty() && !b.trim().is_empty() && a.trim() != b.trim() => {
            Ok((a.trim().to_string(), b.trim().to_string()))
        }
        _ => Err(format!("names are A,B: two different names (got {text:?})")),
    }
}

/// "X,Y" as two pixel coordinates.
fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("a pixel is X,Y with two whole numbers (got {text:?})");
    let (x, y) = text.split_once(',').ok_or_else(bad)?;
    Ok((x.trim().parse().map_err(|_| bad())?, y.trim().parse().map_err(|_| bad())?))
}

#[derive(Args)]
pub struct ViewArgs {
    /// Scene file (TOML), glTF model (.gltf, .glb), OBJ model (.obj), or the name of a built-in scene [default: spheres].
    pub scene: Option<String>,
    /// Set A: rust, glsl, a folder of modules, or a mix (as for compare).
    #[arg(long, default_value = "rust")]
    pub a: String,
    /// Set B.
    #[arg(long, default_value = "glsl")]
    pub b: String,
    /// Port to listen on (0: any free port, printed).
    #[arg(long, default_value_t = 7878)]
    pub port: u16,
    /// Address to listen on. Anything but loopback lets other machines see the renders and
    /// make this one render: prefer `ssh -L` [default: 127.0.0.1].
    #[arg(long, value_name = "ADDR", default_value = "127.0.0.1")]
    pub bind: std::net::IpAddr,
    /// A twinray checkout whose shader sources rebuild the built-in sets (rust, glsl) on every
    /// save [default: the checkout the current folder is in, if any; else their embedded
    /// modules, not rebuilt].
    #[arg(long, value_name = "DIR")]
    pub sources: Option<PathBuf>,
    /// Image width in pixels [default: the scene's].
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's].
    #[arg(long)]
    pub height: Option<u32>,
    /// Width of the quick render shown first after every change, before the full size.
    #[arg(long, default_value_t = 320, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub preview_width: u32,
}
