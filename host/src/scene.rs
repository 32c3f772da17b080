//! Scene files (TOML): camera, image size, the seeded sphere field and the parity tolerance.
//! Loaded from a path or by built-in name; every value is checked before any GPU work.

use crate::error::{Error, Result};
use glam::Vec3;
use serde::Deserialize;
use std::path::Path;
use twinray_shared::layout::{CameraUniform, Sphere};

/// Scenes shipped inside the binary, by name.
pub const BUILTIN: [(&str, &str); 1] = [("spheres", include_str!("../../scenes/spheres.toml"))];
pub const DEFAULT_SCENE: &str = "spheres";

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub name: String,
    pub image: ImageSize,
    pub camera: CameraDesc,
    pub spheres: SphereField,
    pub parity: Parity,
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageSize {
    pub width: u32,
    pub height: u32,
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub up: [f32; 3],
    pub fov_y_degrees: f32,
}

/// `count` spheres with centres uniform in the box and radii uniform in the range.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereField {
    pub count: u32,
    pub seed: u64,
    pub center_min: [f32; 3],
    pub center_max: [f32; 3],
    pub radius_min: f32,
    pub radius_max: f32,
}

/// How close two shader sets' renders of this scene must be.
#[derive(Clone, Copy, Debug, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Parity {
    pub max_rmse: f64,
    pub pixel_threshold: u8,
    pub max_pixels_over_threshold: f64,
    pub max_hit_mismatches: f64,
}

/// A checked scene, ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    pub file: SceneFile,
    /// Where it came from: a path, or `builtin:NAME`.
    pub source: String,
}

/// Largest number of spheres a scene may ask for.
pub const MAX_SPHERES: u32 = 1 << 20;

impl Scene {
    /// Loads `arg` as a file path, or else as a built-in scene name; `None` is the default scene.
    pub fn load(arg: Option<&str>) -> Result<Scene> {
        let arg = arg.unwrap_or(DEFAULT_SCENE);
        let path = Path::new(arg);
        if path.exists() {
            let text = std::fs::read_to_string(path)
                .map_err(|e| Error::Scene { path: arg.into(), message: format!("cannot read: {e}") })?;
            return Scene::parse(&text, arg);
        }
        if let Some((name, text)) = BUILTIN.iter().find(|(name, _)| *name == arg) {
            return Scene::parse(text, &format!("builtin:{name}"));
        }
        let names: Vec<_> = BUILTIN.iter().map(|(n, _)| *n).collect();
        Err(Error::Scene {
            path: arg.into(),
            message: format!("no such file, and no built-in scene of that name (built-ins: {})", names.join(", ")),
        })
    }

    /// Parses and checks scene text; `source` names it in errors.
    pub fn parse(text: &str, source: &str) -> Result<Scene> {
        let file: SceneFile = toml::from_str(text)
            .map_err(|e| Error::Scene { path: source.into(), message: e.to_string().trim_end().replace('\n', " ") })?;
        file.check().map_err(|message| Error::Scene { path: source.into(), message })?;
        Ok(Scene { file, source: source.into() })
    }

    pub fn name(&self) -> &str {
        &self.file.name
    }

    /// The spheres, generated from the seed.
    pub fn spheres(&self) -> Vec<Sphere> {
        self.file.spheres.generate()
    }

    /// Camera matrices for an image of `width` x `height`.
    pub fn camera_uniform(&self, width: u32, height: u32) -> CameraUniform {
        let c = &self.file.camera;
        let view = glam::camera::rh::view::look_at_mat4(c.eye.into(), c.target.into(), c.up.into());
        let aspect = width as f32 / height as f32;
        let proj = glam::camera::rh::proj::vulkan::perspective(c.fov_y_degrees.to_radians(), aspect, 0.1, 1000.0);
        CameraUniform { view_inverse: view.inverse(), proj_inverse: proj.inverse() }
    }
}

impl SceneFile {
    fn check(&self) -> std::result::Result<(), String> {
        let finite = |name: &str, values: &[f32]| {
            if values.iter().all(|v| v.is_finite()) {
                Ok(())
            } else {
                Err(format!("{name} must be finite numbers (got {values:?})"))
            }
        };
        let c = &self.camera;
        finite("camera.eye", &c.eye)?;
        finite("camera.target", &c.target)?;
        finite("camera.up", &c.up)?;
        let forward = Vec3::from(c.target) - Vec3::from(c.eye);
        if forward.length_squared() == 0.0 {
            return Err("camera.eye and camera.target must differ".into());
        }
        if forward.cross(Vec3::from(c.up)).length_squared() == 0.0 {
            return Err("camera.up must not be zero or parallel to the view direction".into());
        }
        if !(c.fov_y_degrees > 0.0 && c.fov_y_degrees < 180.0) {
            return Err(format!("camera.fov_y_degrees must be in (0, 180) (got {})", c.fov_y_degrees));
        }
        crate::render::check_size(self.image.width, self.image.height).map_err(|e| format!("image: {e}"))?;
        self.spheres.check()?;
        let p = &self.parity;
        if !(p.max_rmse.is_finite() && p.max_rmse >= 0.0) {
            return Err(format!("parity.max_rmse must be >= 0 (got {})", p.max_rmse));
        }
        for (name, v) in
            [("max_pixels_over_threshold", p.max_pixels_over_threshold), ("max_hit_mismatches", p.max_hit_mismatches)]
        {
            if !(0.0..=1.0).contains(&v) {
                return Err(format!("parity.{name} is a fraction of pixels, in [0, 1] (got {v})"));
            }
        }
        Ok(())
    }
}

impl SphereField {
    fn check(&self) -> std::result::Result<(), String> {
        if self.count == 0 || self.count > MAX_SPHERES {
            return Err(format!("spheres.count must be in 1..={MAX_SPHERES} (got {})", self.count));
        }
        for (name, v) in [("center_min", self.center_min), ("center_max", self.center_max)] {
            if !v.iter().all(|x| x.is_finite()) {
                return Err(format!("spheres.{name} must be finite numbers (got {v:?})"));
            }
        }
        if (0..3).any(|i| self.center_min[i] > self.center_max[i]) {
            return Err("spheres.center_min must not exceed spheres.center_max".into());
        }
        if !(self.radius_min > 0.0 && self.radius_min.is_finite()) {
            return Err(format!("spheres.radius_min must be > 0 (got {})", self.radius_min));
        }
        if !(self.radius_max >= self.radius_min && self.radius_max.is_finite()) {
            return Err(format!("spheres.radius_max must be >= radius_min (got {})", self.radius_max));
        }
        Ok(())
    }

    /// The spheres, deterministic in `seed` (SplitMix64), identical on every platform.
    pub fn generate(&self) -> Vec<Sphere> {
        let mut rng = SplitMix64(self.seed);
        let (lo, hi) = (Vec3::from(self.center_min), Vec3::from(self.center_max));
        (0..self.count)
            .map(|_| {
                let center = lo + (hi - lo) * Vec3::new(rng.unit(), rng.unit(), rng.unit());
                let radius = self.radius_min + (self.radius_max - self.radius_min) * rng.unit();
                let color = Vec3::new(rng.unit(), rng.unit(), rng.unit()) * 0.8 + Vec3::splat(0.2);
                Sphere { center_radius: center.extend(radius), color: color.extend(1.0) }
            })
            .collect()
    }
}

/// SplitMix64 (Steele, Lea, Flood 2014): small, fast, and fully specified.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 24 random bits: exact in f32.
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Axis-aligned bounds of a sphere, for the BLAS.
pub fn sphere_bounds(s: &Sphere) -> (Vec3, Vec3) {
    let c = s.center_radius.truncate();
    let r = Vec3::splat(s.center_radius.w);
    (c - r, c + r)
}
