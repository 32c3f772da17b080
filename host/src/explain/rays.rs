//! The rays a pixel's ray generation stage traces, made on the CPU: the camera, the jitter and
//! the seed are the shared Rust code the stages run (`twinray_shared::camera`, `random`), fed
//! the frame constants the host uploads, so each ray is the GPU's up to the rounding of the
//! two processors' arithmetic.

use crate::error::{Error, Result};
use crate::scene::Scene;
use glam::UVec2;
use twinray_shared::layout::{FrameUniform, ProbeRay};
use twinray_shared::{camera, random};

/// One primary sample of a pixel: its index among the M x M (row by row), its stratum, and the
/// ray (origin and t_min, direction and t_max, as a probe traces it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimarySample {
    pub index: u32,
    pub stratum: (u32, u32),
    pub ray: ProbeRay,
}

/// What makes a pixel's primary rays: the frame constants the host uploads for an image of
/// `size`, and the samples per side (the stage's specialisation constant).
pub struct Camera {
    frame: FrameUniform,
    samples_per_side: u32,
    size: UVec2,
}

impl Camera {
    /// The camera of `scene` (a still scene, or one frame of it) for an image of `size`.
    pub fn new(scene: &Scene, size: (u32, u32)) -> Camera {
        let samples_per_side = scene.build().plan.samples_per_side;
        Camera { frame: scene.frame_uniform(size.0, size.1), samples_per_side, size: UVec2::new(size.0, size.1) }
    }

    /// The primary samples of `pixel`, in the order the ray generation stage traces them; an
    /// error for a pixel outside the image.
    pub fn primary_samples(&self, pixel: (u32, u32)) -> Result<Vec<PrimarySample>> {
        let (size, m) = (self.size, self.samples_per_side);
        if pixel.0 >= size.x || pixel.1 >= size.y {
            let (x, y) = pixel;
            return Err(Error::Input(format!("pixel {x},{y} is outside the {}x{} image", size.x, size.y)));
        }
        Ok((0..m * m).map(|index| self.sample(pixel, index)).collect())
    }

    /// Sample `index` of `pixel` (inside the image), as the stage makes it.
    pub fn sample(&self, pixel: (u32, u32), index: u32) -> PrimarySample {
        let (size, m, frame) = (self.size, self.samples_per_side, &self.frame);
        let pixel = UVec2::new(pixel.0, pixel.1);
        let pixel_index = pixel.y * size.x + pixel.x;
        let (sx, sy) = (index % m, index / m);
        // As the stage: jitter only when there is more than one sample.
        let (r1, r2) = if m > 1 {
            (random::random(frame.seed, pixel_index, index, 0), random::random(frame.seed, pixel_index, index, 1))
        } else {
            (0.5, 0.5)
        };
        let ray = camera::primary_ray(frame, pixel, size, camera::sample_offset(sx, sy, m, r1, r2));
        let ray = ProbeRay { origin: ray.origin.extend(frame.reach.z), direction: ray.direction.extend(frame.reach.x) };
        PrimarySample { index, stratum: (sx, sy), ray }
    }

    /// The first primary sample of every pixel, row by row: the rays whose hits the image's
    /// hit ids record.
    pub fn first_samples(&self) -> Vec<ProbeRay> {
        let pixels = (0..self.size.y).flat_map(|y| (0..self.size.x).map(move |x| (x, y)));
        pixels.map(|p| self.sample(p, 0).ray).collect()
    }
}
