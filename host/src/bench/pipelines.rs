//! `twinray pipeline-bench`: how long creating a scene's ray tracing pipelines takes, for the
//! two whole sets and for all 16 per-stage mixes, made whole or linked from libraries, with
//! creation joined by one thread or by N, from a cold or a warm pipeline cache. Each
//! configuration gets a fresh device, so nothing compiled by one reaches another except
//! through the cache file it is given (and the driver's own disk cache: turn that off for
//! cold figures, `MESA_SHADER_CACHE_DISABLE=true`, `__GL_SHADER_DISK_CACHE=0`).

use crate::error::Result;
use crate::render::libraries::Libraries;
use crate::render::pipeline::ScenePipeline;
use crate::scene::Scene;
use crate::shaders::ShaderSet;
use crate::util::stats::median;
use crate::vk::context::{Context, ContextOptions, PipelineKind};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Stages a per-stage mix takes from either language.
const STAGES: [&str; 4] = ["raygen", "miss", "intersection", "closest_hit"];

/// The 16 per-stage mixes: each stage from Rust or GLSL (the first is all Rust, the last all
/// GLSL).
pub fn all_mixes() -> Result<Vec<ShaderSet>> {
    (0..16u32)
        .map(|bits| {
            let glsl: Vec<String> = STAGES
                .iter()
                .enumerate()
                .filter(|(i, _)| bits >> i & 1 == 1)
                .map(|(_, s)| format!("{s}=glsl"))
                .collect();
            std::iter::once("rust".to_string()).chain(glsl).collect::<Vec<_>>().join(",").parse()
        })
        .collect()
}

/// One configuration's creation time.
#[derive(Clone, Debug, Serialize)]
pub struct CreationRow {
    pub pipelines: PipelineKind,
    pub threads: usize,
    /// "cold" (no pipeline cache) or "warm" (the cache file a first run wrote).
    pub cache: &'static str,
    /// Pipelines made: 2 (rust, glsl) or 16 (every mix).
    pub sets: usize,
    /// Median wall milliseconds of making them all, over the repeats.
    pub ms: f64,
    pub repeats: Vec<f64>,
    /// Libraries compiled for them (0 when made whole).
    pub libraries: usize,
}

/// Wall milliseconds to make one pipeline per set for `scene` on a fresh context made with
/// `options`, and the libraries compiled; the context is closed after.
fn time_once(options: &ContextOptions, scene: &Scene, sets: &[ShaderSet]) -> Result<(f64, usize)> {
    let ctx = Context::new(options)?;
    let plan = scene.build().plan;
    let libraries = Libraries::default();
    let start = Instant::now();
    let pipelines = sets
        .iter()
        .map(|set| ScenePipeline::new(&ctx, set, &plan, "raygen", &libraries))
        .collect::<Result<Vec<_>>>()?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let compiled = libraries.compiled();
    drop(pipelines);
    drop(libraries);
    ctx.close()?;
    Ok((ms, compiled))
}

/// Every configuration, `repeats` times each; `base` gives validation and device; `cache_dir`
/// holds the warm runs' cache files (one per configuration).
pub fn run(
    base: &ContextOptions,
    scene: &Scene,
    threads: &[usize],
    repeats: usize,
    cache_dir: &Path,
    mut progress: impl FnMut(&str),
) -> Result<Vec<CreationRow>> {
    let whole =
        [ShaderSet::uniform(crate::shaders::Language::Rust), ShaderSet::uniform(crate::shaders::Language::Glsl)];
    let mixes = all_mixes()?;
    // Untimed: what the first pipelines of a process pay once (the driver's compiler starting
    // up) would otherwise fall on the first configuration alone.
    time_once(&ContextOptions { pipeline_cache: None, ..base.clone() }, scene, &whole)?;
    let mut rows = Vec::new();
    for kind in [PipelineKind::Monolithic, PipelineKind::Libraries] {
        // Libraries and links are created directly, not as deferred operations (see
        // `vk::pipeline`): joining threads cannot change their time.
        let counts = if kind == PipelineKind::Libraries { &threads[..1] } else { threads };
        for &n in counts {
            for sets in [&whole[..], &mixes[..]] {
                for cache in ["cold", "warm"] {
                    progress(&format!("{kind:?}, {n} threads, {} sets, {cache}", sets.len()));
                    let dir = cache_dir.join(format!("{kind:?}-{n}-{}", sets.len()));
                    let options = ContextOptions {
                        pipelines: Some(kind),
                        pipeline_threads: Some(n),
                        pipeline_cache: (cache == "warm").then(|| dir.clone()),
                        ..base.clone()
                    };
                    if cache == "warm" {
                        // The run that fills the cache file.
                        time_once(&options, scene, sets)?;
                    }
                    let mut times = Vec::with_capacity(repeats);
                    let mut libraries = 0;
                    for _ in 0..repeats.max(1) {
                        let (ms, compiled) = time_once(&options, scene, sets)?;
                        times.push(ms);
                        libraries = compiled;
                    }
                    rows.push(CreationRow {
                        pipelines: kind,
                        threads: n,
                        cache,
                        sets: sets.len(),
                        ms: median(&times).unwrap_or(0.0),
                        repeats: times,
                        libraries,
                    });
                }
            }
        }
    }
    Ok(rows)
}

/// The rows as a Markdown table, with each configuration's speed-up over monolithic, one
/// thread, cold, for the same number of sets.
pub fn table(rows: &[CreationRow]) -> String {
    let mut s = String::from(
        "Libraries and links are created directly (on the H100, deferred creation of them crashed), so only whole pipelines are timed with several joining threads.\n\n| pipelines | threads | cache | sets | ms (median) | libraries compiled | against monolithic, 1 thread, cold |\n|---|---:|---|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let base = rows
            .iter()
            .find(|b| {
                b.pipelines == PipelineKind::Monolithic && b.threads == 1 && b.cache == "cold" && b.sets == r.sets
            })
            .or_else(|| rows.iter().find(|b| b.sets == r.sets))
            .map_or(f64::NAN, |b| b.ms);
        s += &format!(
            "| {:?} | {} | {} | {} | {:.1} | {} | {:.2}x |\n",
            r.pipelines,
            r.threads,
            r.cache,
            r.sets,
            r.ms,
            r.libraries,
            base / r.ms
        );
    }
    s
}

#[cfg(test)]
mod tests {
    #[test]
    fn sixteen_distinct_mixes_from_all_rust_to_all_glsl() {
        let mixes: Vec<String> = super::all_mixes().unwrap().iter().map(|s| s.to_string()).collect();
        assert_eq!(mixes.len(), 16);
        let mut unique = mixes.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), 16, "{mixes:?}");
        assert_eq!(mixes[0], "rust");
    }
}
