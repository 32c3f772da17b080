//! The shading of one primary sample remade on the CPU from what a set's stages handed back:
//! the light samples the ray generation stage takes at the hit (the shared
//! `lighting::sample_of`, `offset::offset_hit`), the shadow rays it traces, and the colour it
//! adds up, in its order and with its f32 arithmetic.

use crate::scene::PipelinePlan;
use glam::{Vec3, Vec4Swizzles};
use twinray_shared::bindings::{EXPLAIN_SHADOW, MATERIAL_EMISSIVE, MATERIAL_SHADED, NO_HIT, SHADOW_SAMPLER_STRATIFIED};
use twinray_shared::layout::{ExplainRay, FrameUniform, HitPayload, Light};
use twinray_shared::{lighting, offset};

/// One light sample at a primary hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// The light's index in the scene's lights.
    pub light: u32,
    /// Its cell (i, j) of the light's n x n.
    pub cell: (u32, u32),
    /// Where on the light it aims (a directional light: `reach.y` along its direction).
    pub target: Vec3,
    /// The shadow ray: from the offset hit point, a unit direction, and how far it goes.
    pub origin: Vec3,
    pub direction: Vec3,
    pub distance: f32,
    /// The shading normal's cosine with the direction: the stage traces no ray and adds
    /// nothing where it is not positive.
    pub cosine: f32,
    pub irradiance: Vec3,
    /// Whether the stage traces a shadow ray for it (the light casts shadows, the surface faces
    /// it).
    pub traced: bool,
}

impl LightSample {
    /// The shadow ray as `explain` traces it.
    pub fn ray(&self) -> ExplainRay {
        ExplainRay {
            origin: self.origin.extend(0.0),
            direction: self.direction.extend(self.distance),
            kind: glam::UVec4::new(EXPLAIN_SHADOW, 0, 0, 0),
        }
    }
}

/// Whether the stage shades `hit` with lights: it is a hit, and neither an emitter nor a
/// surface its closest hit shaded (whose colour is its radiance).
pub fn lit_by_lights(hit: &HitPayload) -> bool {
    hit.ids.w != NO_HIT && hit.ids.z != MATERIAL_EMISSIVE && hit.ids.z != MATERIAL_SHADED
}

/// Every light sample the ray generation stage takes at `hit` (primary sample `sample` of
/// pixel `pixel_index`), in its order: light by light, then j, then i.
pub fn light_samples(
    (frame, lights, plan): (&FrameUniform, &[Light], &PipelinePlan),
    hit: &HitPayload,
    pixel_index: u32,
    sample: u32,
) -> Vec<LightSample> {
    if !lit_by_lights(hit) {
        return Vec::new();
    }
    let point = hit.position.xyz();
    let normal = hit.shading_normal.xyz();
    let origin = offset::offset_hit(point, hit.geometric_normal.xyz(), hit.position.w);
    let stratified = plan.shadow_sampler == SHADOW_SAMPLER_STRATIFIED;
    let mut out = Vec::new();
    for (l, light) in lights.iter().enumerate().take(frame.light_count as usize) {
        let l = l as u32;
        let n = lighting::samples_per_side(light);
        let casts = plan.shadows && light.shadows != 0;
        for j in 0..n {
            for i in 0..n {
                let randoms = (frame.seed, pixel_index, sample);
                let s = lighting::sample_of(light, (l, i, j, n), stratified, randoms, point, frame.reach.y);
                let cosine = normal.dot(s.direction);
                out.push(LightSample {
                    light: l,
                    cell: (i, j),
                    target: point + s.direction * s.distance,
                    origin,
                    direction: s.direction,
                    distance: s.distance,
                    cosine,
                    irradiance: s.irradiance,
                    traced: casts && cosine > 0.0,
                });
            }
        }
    }
    out
}

/// The colour the stage adds for `hit` with its light samples, of which those `lit` (one per
/// sample; only traced ones are asked) reach their light: the background or an emitter's
/// radiance as it is, else the albedo times the light that arrives, summed in the stage's order,
/// plus the radiance the surface emits.
pub fn radiance(hit: &HitPayload, samples: &[LightSample], lit: impl Fn(usize) -> bool) -> Vec3 {
    if !lit_by_lights(hit) {
        return hit.color.xyz();
    }
    let mut sum = Vec3::ZERO;
    for (k, s) in samples.iter().enumerate() {
        if s.cosine > 0.0 && (!s.traced || lit(k)) {
            sum += s.irradiance * s.cosine;
        }
    }
    hit.color.xyz() * sum + hit.emission()
}
