//! What the image renderers (`raygen`, `raygen_query` and `render_compute`) keep for one pixel
//! while they trace and shade its samples, and write when they are done. Each renderer writes
//! its own loop: a primary ray per sample, traced, checked, shaded, added.

use spirv_std::glam::{UVec2, Vec3};
use spirv_std::Image;
use twinray_shared::bindings::{HIT_IDS_PER_PIXEL, NO_HIT, SHADOW_SAMPLER_STRATIFIED};
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

/// A pixel a renderer samples: where it lies, the image's size, and its index. It does not
/// change while its samples are traced: the renderers keep what does (the sample's index, the
/// sum of the colours, the samples left poisoned, the shadow rays) in locals of their loop,
/// and hand them to [`Pixel::write`] as [`Totals`] at the end. Kept in this struct instead,
/// rust-gpu carried the whole struct through the loop as one value alive across every trace,
/// and frames at 1 spp on an H100 were 1.7% (instances) to 5.3% (meshes) slower.
#[derive(Clone, Copy)]
pub struct Pixel {
    pub pixel: UVec2,
    pub size: UVec2,
    /// Its index in the image, row by row: where its hit ids are, and its random sequence.
    pub index: u32,
}

/// What a pixel's `side`² samples came to: the sum of the colours of those shaded, the samples
/// whose hit or miss stage left the payload poisoned (`bindings::no_payload_word`), and the
/// shadow rays they traced.
pub struct Totals {
    pub sum: Vec3,
    pub no_payload: u32,
    pub shadow_rays: u32,
}

impl Pixel {
    /// Pixel `pixel` of an image of `size`.
    #[inline(always)]
    pub fn new(pixel: UVec2, size: UVec2) -> Self {
        Pixel { pixel, size, index: pixel.y * size.x + pixel.x }
    }

    /// The primary ray of sample `sample` (row by row) of `side` x `side`, through its cell of
    /// the pixel, jittered when there is more than one sample (one goes through the centre).
    /// `side` is a specialisation constant, so the driver divides by a constant.
    #[inline(always)]
    pub fn ray(&self, frame: &FrameUniform, sample: u32, side: u32) -> Ray {
        let (r1, r2) = if side > 1 {
            (random::random(frame.seed, self.index, sample, 0), random::random(frame.seed, self.index, sample, 1))
        } else {
            (0.5, 0.5)
        };
        let offset = camera::sample_offset(sample % side, sample / side, side, r1, r2);
        camera::primary_ray(frame, self.pixel, self.size, offset)
    }

    /// Keeps what the first sample's ray hit in the pixel's first two hit-id words: the ids
    /// the payload came back with, or `NO_HIT` where it came back poisoned (`unwritten`).
    #[inline(always)]
    pub fn first_hit(&self, payload: &HitPayload, unwritten: bool, hit_ids: &mut [u32]) {
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

    /// Writes the pixel: the mean colour of its `side`² samples (NaN if any came back
    /// poisoned), and its last two hit-id words, the shadow rays and the poisoned samples.
    #[inline(always)]
    pub fn write(&self, image: &Target, hit_ids: &mut [u32], totals: Totals, side: u32) {
        let base = hit_id_base(self.index);
        // SAFETY: base + 3 < hit_ids.len(): the host sizes the buffer to the launch.
        unsafe {
            *hit_ids.get_unchecked_mut(base + 2) = totals.shadow_rays;
            *hit_ids.get_unchecked_mut(base + 3) = totals.no_payload;
        }
        let color = if totals.no_payload == 0 { totals.sum / (side * side) as f32 } else { Vec3::splat(f32::NAN) };
        // SAFETY: the pixel lies inside the image, which the host sizes to the launch.
        unsafe { image.write(self.pixel, color.extend(1.0)) };
    }
}

/// Where pixel `index`'s hit-id words start in the hit-id buffer.
#[inline(always)]
fn hit_id_base(index: u32) -> usize {
    (HIT_IDS_PER_PIXEL * index) as usize
}
