//! What the image renderers (`raygen`, `raygen_query` and `render_compute`) keep for one pixel
//! while they trace and shade its samples, and write when they are done. Each renderer writes
//! its own loop: a primary ray per sample, traced, checked, shaded, added.

use spirv_std::glam::{UVec2, Vec3};
use spirv_std::Image;
use twinray_shared::bindings::{no_payload_word, HIT_IDS_PER_PIXEL, NO_HIT, SHADOW_SAMPLER_STRATIFIED};
use twinray_shared::camera::{self, Ray};
use twinray_shared::features::Features;
use twinray_shared::layout::{FrameUniform, HitPayload};
use twinray_shared::random;

/// The renderers' image: the colour of each pixel, the mean of its samples.
pub type Target = Image!(2D, format = rgba32f, sampled = false);

/// How the host asked for the samples to be shaded: the renderers' specialisation constants
/// other than the samples per side (`Pixel` takes that one).
#[derive(Clone, Copy)]
pub struct Options {
    /// Whether lights that cast shadows trace shadow rays.
    pub shadows: bool,
    /// Whether a rect light's shadow samples are stratified (one per cell of its grid).
    pub stratified: bool,
    /// What the scene holds (`twinray_shared::features`).
    pub features: Features,
    /// Whether a closest hit may have shaded the surface itself (`MATERIAL_SHADED`): only in
    /// sets with a stage from disk.
    pub shaded_hits: bool,
}

impl Options {
    /// The options from the specialisation constants' values.
    #[inline(always)]
    pub fn new(shadows: u32, shadow_sampler: u32, features: u32, shaded_hits: u32) -> Self {
        Options {
            shadows: shadows != 0,
            stratified: shadow_sampler == SHADOW_SAMPLER_STRATIFIED,
            features: Features::new(features),
            shaded_hits: shaded_hits != 0,
        }
    }
}

/// A pixel a renderer samples, and how far its M x M samples have come: the one now (column
/// `sx` and row `sy` of the grid), the sum of those shaded, and the samples whose hit or miss
/// stage left the payload poisoned (`bindings::no_payload_word`). Values only: rust-gpu keeps
/// no references in a struct.
///
/// Not in here, though the loop needs them: M (`side` below), a specialisation constant,
/// which carried in the struct through the loop would be a value the driver cannot see is
/// constant; and the shadow rays traced, which counted in here would carry the whole struct
/// through every shadow loop.
pub struct Pixel {
    /// The pixel, and the size of the image it lies in.
    pub pixel: UVec2,
    pub size: UVec2,
    /// Its index in the image, row by row: where its hit ids are, and its random sequence.
    pub index: u32,
    sx: u32,
    sy: u32,
    sum: Vec3,
    no_payload: u32,
}

impl Pixel {
    /// Pixel `pixel` of an image of `size`, before its first sample.
    #[inline(always)]
    pub fn new(pixel: UVec2, size: UVec2) -> Self {
        let index = pixel.y * size.x + pixel.x;
        Pixel { pixel, size, index, sx: 0, sy: 0, sum: Vec3::ZERO, no_payload: 0 }
    }

    /// The sample's index, row by row, of `side` x `side`: its random sequence within the
    /// pixel's.
    #[inline(always)]
    pub fn sample(&self, side: u32) -> u32 {
        self.sy * side + self.sx
    }

    /// The sample's primary ray through its cell of the pixel, jittered when there is more than
    /// one sample (one sample goes through the pixel's centre).
    #[inline(always)]
    pub fn ray(&self, frame: &FrameUniform, side: u32) -> Ray {
        let sample = self.sample(side);
        let (r1, r2) = if side > 1 {
            (random::random(frame.seed, self.index, sample, 0), random::random(frame.seed, self.index, sample, 1))
        } else {
            (0.5, 0.5)
        };
        let offset = camera::sample_offset(self.sx, self.sy, side, r1, r2);
        camera::primary_ray(frame, self.pixel, self.size, offset)
    }

    /// Takes the payload the sample's primary ray came back with: whether it may be shaded, or
    /// was left poisoned by the stage that took the ray (counted, and the pixel will be NaN).
    /// The first sample's ids go to the pixel's first two hit-id words.
    #[inline(always)]
    pub fn traced(&mut self, payload: &HitPayload, hit_ids: &mut [u32], side: u32) -> bool {
        let unwritten = payload.unwritten(true);
        let sample = self.sample(side);
        if sample == 0 {
            let base = hit_id_base(self.index);
            // SAFETY: base + 1 < hit_ids.len(): the host sizes the buffer to the launch. Not
            // checked against `hit_ids.len()`, as the image is not against its size: a buffer
            // length read before the first trace is waited for by every thread as the launch
            // starts (on NVIDIA's driver 580, up to 4% of a frame at 1 spp).
            unsafe {
                *hit_ids.get_unchecked_mut(base) = if unwritten { NO_HIT } else { payload.ids.x };
                *hit_ids.get_unchecked_mut(base + 1) = if unwritten { NO_HIT } else { payload.ids.y };
            }
        }
        if unwritten {
            self.no_payload = no_payload_word(self.no_payload, sample);
        }
        !unwritten
    }

    /// Adds a shaded sample's colour.
    #[inline(always)]
    pub fn add(&mut self, color: Vec3) {
        self.sum += color;
    }

    /// Moves to the next sample, row by row; false after the last. Renderers test it at the
    /// bottom of their loop: rust-gpu tests a `while` condition again after the body, which
    /// keeps it alive across the body's traces.
    #[inline(always)]
    pub fn next(&mut self, side: u32) -> bool {
        self.sx += 1;
        if self.sx >= side {
            self.sx = 0;
            self.sy += 1;
        }
        self.sy < side
    }

    /// Writes the pixel: the mean colour of its `side`² samples (NaN if any came back
    /// poisoned), and its last two hit-id words, with the `shadow_rays` its samples traced.
    #[inline(always)]
    pub fn write(&self, image: &Target, hit_ids: &mut [u32], shadow_rays: u32, side: u32) {
        let base = hit_id_base(self.index);
        // SAFETY: base + 3 < hit_ids.len(): the host sizes the buffer to the launch.
        unsafe {
            *hit_ids.get_unchecked_mut(base + 2) = shadow_rays;
            *hit_ids.get_unchecked_mut(base + 3) = self.no_payload;
        }
        let color = if self.no_payload == 0 { self.sum / (side * side) as f32 } else { Vec3::splat(f32::NAN) };
        // SAFETY: the pixel lies inside the image, which the host sizes to the launch.
        unsafe { image.write(self.pixel, color.extend(1.0)) };
    }
}

/// Where pixel `index`'s hit-id words start in the hit-id buffer.
#[inline(always)]
fn hit_id_base(index: u32) -> usize {
    (HIT_IDS_PER_PIXEL * index) as usize
}
