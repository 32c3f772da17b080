//! The shadow-sampler study of soft-shadow scenes: stratified jittered against independent
//! random shadow samples of rect lights, at equal sample counts (N x N per light, one primary
//! sample at each pixel's centre) and so at equal rays, with GPU time for the comparison at
//! equal time. Errors are against a reference that converges the shadows at pixel centres.

use super::metrics;
use serde::Serialize;
use std::path::Path;
use std::sync::Arc;
use twinray_host::error::{Error, Result};
use twinray_host::reference::image::{converged, Converge};
use twinray_host::render::{render, RayCounts, RenderOptions};
use twinray_host::scene::file::ShadowSampler;
use twinray_host::scene::Scene;
use twinray_host::sets::ShaderSet;
use twinray_host::util::stats::Spread;
use twinray_host::vk::context::Context;

/// One measurement of the study.
#[derive(Clone, Debug, Serialize)]
pub struct SamplerRow {
    pub scene: String,
    pub sampler: &'static str,
    /// Shadow samples per rect light and shading point (N x N).
    pub shadow_spp: u32,
    pub gpu_ms: Option<Spread>,
    pub rays: RayCounts,
    pub rmse: f64,
    pub flip: f64,
}

/// What the study needs beyond the scene.
pub struct Study<'a> {
    pub set: &'a ShaderSet,
    pub size: (u32, u32),
    /// Shadow samples per light to measure, squares up to 256.
    pub counts: &'a [u32],
    pub reference_spp: u32,
    pub cache: &'a Path,
    pub warmup: u32,
    pub runs: u32,
}

/// The sampler study of one soft-shadow scene: each sampler at each shadow sample count.
pub fn study(ctx: &Arc<Context>, scene: &Scene, s: &Study, progress: &dyn Fn(&str)) -> Result<Vec<SamplerRow>> {
    progress(&format!("{}: shadow reference at {} samples", scene.name(), s.reference_spp));
    let truth = converged(ctx, scene, s.set, s.size, (s.reference_spp, Converge::Shadows), s.cache)?;
    let mut rows = Vec::new();
    for &count in s.counts {
        for sampler in [ShadowSampler::Stratified, ShadowSampler::Random] {
            progress(&format!("{}: {} shadows, {count} samples", scene.name(), sampler.name()));
            let mut variant = scene.clone();
            variant.file.image.samples = 1;
            variant.file.shadow_sampler = sampler;
            variant.set_shadow_samples(side_of(count)?);
            let opts = RenderOptions {
                width: s.size.0,
                height: s.size.1,
                warmup: s.warmup,
                runs: s.runs,
                placements: 1,
                first_placement: 0,
            };
            let out = render(ctx, &variant, s.set, &opts)?;
            out.written.require(
                &s.set.to_string(),
                "pixels",
                &format!("{} with {} shadows", scene.name(), sampler.name()),
            )?;
            let errors = metrics::errors(&out.linear, &truth.linear, s.size);
            rows.push(SamplerRow {
                scene: scene.name().to_string(),
                sampler: sampler.name(),
                shadow_spp: count,
                gpu_ms: out.spread(),
                rays: out.rays,
                rmse: errors.rmse,
                flip: errors.flip,
            });
        }
    }
    Ok(rows)
}

/// Samples per side of a bench sample count: a square up to 16 x 16.
pub fn side_of(spp: u32) -> Result<u32> {
    (1..=16u32)
        .find(|m| m * m == spp)
        .ok_or_else(|| Error::Input(format!("sample counts must be squares up to 256 (1, 4, 9, .., 256), got {spp}")))
}
