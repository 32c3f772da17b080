//! Every ray of one pixel, in each set and in the f64 reference: the primary samples made on
//! the CPU (`rays`), traced through each set's real stages (`trace`); the light samples each
//! set's stage takes at its own hit, remade on the CPU (`shading`) and their shadow rays traced
//! through its stages too; each ray judged by the reference; and the pixel as each set's image
//! holds it, next to what its rays add up to.

use super::rays::{Camera, PrimarySample};
use super::shading::{self, LightSample};
use super::surface::{surface, Hit, Surface};
use super::trace;
use crate::error::{Error, Result};
use crate::probe::report::{outcome, Outcome};
use crate::reference::scene::{SceneReference, SceneVerdict};
use crate::render::{render_sets, RenderOptions};
use crate::scene::{Scene, SceneData};
use crate::sets::ShaderSet;
use crate::vk::context::Context;
use glam::{UVec4, Vec3};
use std::sync::Arc;
use twinray_shared::bindings::{EXPLAIN_PRIMARY, MASK_OCCLUDER};
use twinray_shared::layout::{ExplainRay, HitPayload};

/// One set's answer for one primary sample.
#[derive(Clone, Debug)]
pub struct SetSample {
    /// The payload its hit or miss stage left.
    pub hit: HitPayload,
    /// How it stands against the reference's verdict for the ray.
    pub outcome: Outcome,
    /// The light samples its ray generation stage takes at that hit, in order.
    pub lights: Vec<LightSample>,
    /// Per light sample: whether its shadow ray was occluded (`None`: no ray traced).
    pub occluded: Vec<Option<bool>>,
    /// Per light sample: the reference's answer for that very shadow ray (`None`: not traced).
    pub shadow_verdicts: Vec<Option<SceneVerdict>>,
    /// The colour the sample adds, as the stage adds it up.
    pub radiance: Vec3,
    /// What its hit is on (`None` on a miss, or with no payload).
    pub surface: Option<Surface>,
}

/// One set's rays of the pixel.
#[derive(Clone, Debug)]
pub struct SetRays {
    pub label: String,
    pub samples: Vec<SetSample>,
    /// The pixel in the set's image (linear).
    pub image: Vec3,
    /// What its samples add up to, as the stage averages them.
    pub remade: Vec3,
}

/// The explanation of one pixel.
pub struct PixelRays {
    pub scene: String,
    pub pixel: (u32, u32),
    pub size: (u32, u32),
    pub samples: Vec<PrimarySample>,
    /// The reference's verdict for each primary sample, and what its hit is on.
    pub reference: Vec<SceneVerdict>,
    pub reference_surfaces: Vec<Option<Surface>>,
    pub sets: Vec<SetRays>,
    /// The scene's GPU data and pipeline plan (what names objects and stages).
    pub data: SceneData,
    /// The f64 reference of the scene.
    pub truth: SceneReference,
    /// The scene's background: what the miss stage shows.
    pub background: Vec3,
}

/// Traces every ray of `pixel` of `scene` (a still scene, or one frame of an animation) at
/// `size` with each of `sets`, and judges them with the f64 reference. It works in the GPU's
/// coordinates (the scene moved to its local origin, `scene::origin`), as the image was made:
/// a hit point moved back to the scene's own would round at the magnitude of its coordinates,
/// and the shadow rays remade from it would no longer be the image's.
pub fn explain_pixel(
    ctx: &Arc<Context>,
    scene: &Scene,
    sets: &[(String, ShaderSet)],
    size: (u32, u32),
    pixel: (u32, u32),
) -> Result<PixelRays> {
    let scene = &*scene.on_gpu();
    let camera = Camera::new(scene, size);
    let samples = camera.primary_samples(pixel)?;
    let reference = SceneReference::new(scene).map_err(|e| Error::Input(format!("{}: {e}", scene.name())))?;
    let frame = scene.frame_uniform(size.0, size.1);
    let verdicts: Vec<SceneVerdict> = samples
        .iter()
        .map(|s| {
            let (o, d) = (s.ray.origin.truncate().as_dvec3(), s.ray.direction.truncate().as_dvec3());
            reference.trace(o, d, f64::from(s.ray.origin.w), f64::from(s.ray.direction.w))
        })
        .collect();
    let only_sets: Vec<ShaderSet> = sets.iter().map(|(_, s)| s.clone()).collect();
    let images = render_sets(ctx, scene, &only_sets, &RenderOptions::once(size.0, size.1, 0, 1))?;
    let pixel_index = pixel.1 * size.0 + pixel.0;
    let data = scene.build();
    let primary: Vec<ExplainRay> = samples
        .iter()
        .map(|s| ExplainRay {
            origin: s.ray.origin.truncate().extend(0.0),
            direction: s.ray.direction.truncate().extend(0.0),
            kind: UVec4::new(EXPLAIN_PRIMARY, 0, 0, 0),
        })
        .collect();
    let mut out = Vec::new();
    for ((label, set), image) in sets.iter().zip(&images) {
        let hits = trace::trace(ctx, (scene, &data.plan), set, size, &primary)?;
        let lights: Vec<Vec<LightSample>> = hits
            .iter()
            .zip(&samples)
            .map(|(r, s)| {
                // A poisoned payload has no surface to light.
                let lit = !r.hit.unwritten(true);
                let lights = shading::light_samples((&frame, &data.lights, &data.plan), &r.hit, pixel_index, s.index);
                if lit {
                    lights
                } else {
                    Vec::new()
                }
            })
            .collect();
        let shadow_rays: Vec<ExplainRay> = lights.iter().flatten().filter(|l| l.traced).map(|l| l.ray()).collect();
        let mut answers =
            trace::trace(ctx, (scene, &data.plan), set, size, &shadow_rays)?.into_iter().map(|r| r.occluded.x != 0);
        let mut set_samples = Vec::new();
        for ((result, lights), verdict) in hits.iter().zip(lights).zip(&verdicts) {
            let occluded: Vec<Option<bool>> =
                lights.iter().map(|l| if l.traced { answers.next() } else { None }).collect();
            let shadow_verdicts = lights.iter().map(|l| l.traced.then(|| shadow_verdict(&reference, l))).collect();
            let radiance = shading::radiance(&result.hit, &lights, |k| occluded[k] == Some(false));
            let h = &result.hit;
            let hit = !h.unwritten(true) && h.ids.w != twinray_shared::bindings::NO_HIT;
            let at = Hit {
                object: h.ids.x as usize,
                triangle: Some(h.ids.y as usize),
                point: h.position.truncate().as_dvec3(),
                direction: samples[set_samples.len()].ray.direction.truncate().as_dvec3(),
                t: f64::from(h.position.w),
            };
            set_samples.push(SetSample {
                surface: if hit { surface(scene, &data, frame.cone.x, &at) } else { None },
                hit: result.hit,
                outcome: if result.hit.unwritten(true) {
                    Outcome::NoPayload
                } else {
                    outcome(*verdict, true, result.hit.ids)
                },
                lights,
                occluded,
                shadow_verdicts,
                radiance,
            });
        }
        let sum = set_samples.iter().fold(Vec3::ZERO, |sum, s| sum + s.radiance);
        let remade = sum / set_samples.len() as f32;
        let image = Vec3::from(image.linear[pixel_index as usize]);
        out.push(SetRays { label: label.clone(), samples: set_samples, image, remade });
    }
    let background = frame.background.truncate();
    let reference_surfaces = samples
        .iter()
        .zip(&verdicts)
        .map(|(s, v)| {
            let SceneVerdict::Hit { object, t, .. } = *v else { return None };
            let (o, d) = (s.ray.origin.truncate().as_dvec3(), s.ray.direction.truncate().as_dvec3());
            let reach = (f64::from(s.ray.origin.w), f64::from(s.ray.direction.w));
            let (triangle, _) = reference.shape_hit(object, o, d, reach)?;
            let at = Hit { object, triangle: Some(triangle), point: o + d * t, direction: d, t };
            surface(scene, &data, frame.cone.x, &at)
        })
        .collect();
    Ok(PixelRays {
        scene: scene.name().to_string(),
        pixel,
        size,
        samples,
        reference: verdicts,
        reference_surfaces,
        sets: out,
        data,
        truth: reference,
        background,
    })
}

/// The reference's answer for a shadow ray: a hit is an occluder in the way.
fn shadow_verdict(reference: &SceneReference, light: &LightSample) -> SceneVerdict {
    let (o, d) = (light.origin.as_dvec3(), light.direction.as_dvec3());
    reference.trace_masked(o, d, (0.0, f64::from(light.distance)), MASK_OCCLUDER)
}
