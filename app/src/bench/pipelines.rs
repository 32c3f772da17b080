//! `twinray pipeline-bench`: how long creating a scene's ray tracing pipelines takes, for the
//! two whole sets and for every per-stage mix of the stages the scene uses (16 for four), made whole or linked from libraries, with
//! creation joined by one thread or by N, from a cold or a warm pipeline cache. Each
//! configuration gets a fresh device, so nothing compiled by one reaches another except
//! through the cache file it is given (and the driver's own disk cache: turn that off for
//! cold figures, `MESA_SHADER_CACHE_DISABLE=true`, `__GL_SHADER_DISK_CACHE=0`).

use serde::Serialize;
use std::path::Path;
use std::time::Instant;
use twinray_host::error::Result;
use twinray_host::render::layout::LayoutDraw;
use twinray_host::render::libraries::Libraries;
use twinray_host::render::pipeline::{used_stages, ScenePipeline};
use twinray_host::scene::Scene;
use twinray_host::sets::{Language, ShaderSet, Stage, MODULES};
use twinray_host::util::stats::median;
use twinray_host::vk::context::{Context, ContextOptions, PipelineKind};

/// The 2^n per-stage mixes of `stages`: each from Rust or GLSL (the first is all Rust, the last
/// all GLSL).
pub fn all_mixes(stages: &[Stage]) -> Result<Vec<ShaderSet>> {
    let (rust, glsl) = (ShaderSet::uniform(Language::Rust), ShaderSet::uniform(Language::Glsl));
    let mixes = (0..1u32 << stages.len()).map(|bits| {
        let from_glsl: Vec<&str> = MODULES
            .iter()
            .filter(|m| stages.iter().enumerate().any(|(i, s)| bits >> i & 1 == 1 && m.stage == *s))
            .map(|m| m.name)
            .collect();
        rust.with_modules_from(&glsl, &from_glsl)
    });
    Ok(mixes.collect())
}

/// One configuration of pipeline creation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct Config {
    pub pipelines: PipelineKind,
    pub threads: usize,
    /// From the cache file that a first, untimed run of the same configuration wrote.
    pub warm: bool,
    /// Every mix of the stages the scene uses, else the two whole sets.
    pub mixes: bool,
}

impl Config {
    /// Every configuration, in the order the table lists them. Libraries and links are created
    /// directly, not as deferred operations (see `vk::pipeline`): joining threads cannot change
    /// their time, so they run with the first count only.
    pub fn all(threads: &[usize]) -> Vec<Config> {
        let mut out = Vec::new();
        for pipelines in [PipelineKind::Monolithic, PipelineKind::Libraries] {
            let counts = if pipelines == PipelineKind::Libraries { &threads[..1] } else { threads };
            for &threads in counts {
                for mixes in [false, true] {
                    for warm in [false, true] {
                        out.push(Config { pipelines, threads, warm, mixes });
                    }
                }
            }
        }
        out
    }

    /// Its own cache folder under `root`.
    pub fn cache_dir(&self, root: &Path) -> std::path::PathBuf {
        root.join(format!("{:?}-{}-{}", self.pipelines, self.threads, if self.mixes { "mixes" } else { "sets" }))
    }

    fn describe(&self) -> String {
        let sets = if self.mixes { "every mix" } else { "2 sets" };
        format!("{:?}, {} threads, {sets}, {}", self.pipelines, self.threads, self.cache())
    }

    fn cache(&self) -> &'static str {
        if self.warm {
            "warm"
        } else {
            "cold"
        }
    }
}

/// One configuration's creation time.
#[derive(Clone, Debug, Serialize)]
pub struct CreationRow {
    pub pipelines: PipelineKind,
    pub threads: usize,
    /// "cold" (no pipeline cache) or "warm" (the cache file a first run wrote).
    pub cache: &'static str,
    /// Pipelines made: 2 (rust, glsl) or every mix (16 of four stages).
    pub sets: usize,
    /// Median wall milliseconds of making them all, over the repeats.
    pub ms: f64,
    pub repeats: Vec<f64>,
    /// Libraries compiled for them (0 when made whole).
    pub libraries: usize,
}

/// What one timed creation gave: wall milliseconds and libraries compiled.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct Measured {
    pub ms: f64,
    pub libraries: usize,
    /// Pipelines made.
    pub sets: usize,
}

/// Makes `config`'s pipelines for `scene` once, on a fresh context from `base` (whose
/// validation and device filter it keeps), with the cache folder `cache_root` gives it when
/// warm; the context is closed after.
pub fn measure(base: &ContextOptions, scene: &Scene, config: &Config, cache_root: &Path) -> Result<Measured> {
    let options = ContextOptions {
        pipelines: Some(config.pipelines),
        pipeline_threads: Some(config.threads),
        pipeline_cache: config.warm.then(|| config.cache_dir(cache_root)),
        ..base.clone()
    };
    let plan = scene.build().plan;
    let sets = if config.mixes {
        all_mixes(&used_stages(&plan, plan.render_raygen()))?
    } else {
        vec![
            ShaderSet::uniform(twinray_host::sets::Language::Rust),
            ShaderSet::uniform(twinray_host::sets::Language::Glsl),
        ]
    };
    let ctx = Context::new(&options)?;
    let libraries = Libraries::default();
    let linking = (ctx.pipeline_kind() == PipelineKind::Libraries).then_some(&libraries);
    let start = Instant::now();
    let pipelines = sets
        .iter()
        .map(|set| ScenePipeline::new(&ctx, set, &plan, (plan.render_raygen(), LayoutDraw::Sbt), linking))
        .collect::<Result<Vec<_>>>()?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let compiled = libraries.compiled();
    drop(pipelines);
    drop(libraries);
    ctx.close()?;
    Ok(Measured { ms, libraries: compiled, sets: sets.len() })
}

/// Every configuration of `configs`, `repeats` times each, each time through `measure_one`
/// (in this process, or in a process of its own: NVIDIA's driver 580 stops making instances
/// after about 30 in one process). A warm configuration is first run once untimed, to write
/// its cache file.
pub fn run(
    configs: &[Config],
    repeats: usize,
    mut measure_one: impl FnMut(&Config) -> Result<Measured>,
    mut progress: impl FnMut(&str),
) -> Result<Vec<CreationRow>> {
    // Untimed: what the first pipelines of a process pay once (the driver's compiler starting
    // up) would otherwise fall on the first configuration alone.
    if let Some(first) = configs.first() {
        measure_one(&Config { warm: false, ..*first })?;
    }
    let mut rows = Vec::new();
    for config in configs {
        progress(&config.describe());
        if config.warm {
            measure_one(config)?;
        }
        let measured = (0..repeats.max(1)).map(|_| measure_one(config)).collect::<Result<Vec<_>>>()?;
        let times: Vec<f64> = measured.iter().map(|m| m.ms).collect();
        rows.push(CreationRow {
            pipelines: config.pipelines,
            threads: config.threads,
            cache: config.cache(),
            sets: measured.last().map_or(0, |m| m.sets),
            ms: median(&times).unwrap_or(0.0),
            repeats: times,
            libraries: measured.last().map_or(0, |m| m.libraries),
        });
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
        use twinray_host::sets::Stage::*;
        let stages = [Raygen, Miss, Intersection, ClosestHit];
        let mixes: Vec<String> = super::all_mixes(&stages).unwrap().iter().map(|s| s.to_string()).collect();
        assert_eq!(mixes.len(), 16);
        let mut unique = mixes.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), 16, "{mixes:?}");
        assert_eq!(mixes[0], "rust");
    }
}
