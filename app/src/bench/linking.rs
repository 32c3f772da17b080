//! Whether a pipeline linked from libraries traces as fast as the same pipeline made whole:
//! per scene and set, the two pipelines render over one upload, timed interleaved in every
//! build order as `compare` times two sets, and their images and hit ids are compared bit for
//! bit.

use serde::Serialize;
use std::sync::Arc;
use twinray_host::error::{Error, Result};
use twinray_host::render::{render_made, RenderOptions};
use twinray_host::scene::Scene;
use twinray_host::sets::ShaderSet;
use twinray_host::util::interval::RatioInterval;
use twinray_host::util::stats::Spread;
use twinray_host::vk::context::{Context, PipelineKind};

/// One scene and set, whole against linked.
#[derive(Clone, Debug, Serialize)]
pub struct LinkingRow {
    pub scene: String,
    pub set: String,
    pub width: u32,
    pub height: u32,
    pub whole: Option<Spread>,
    pub linked: Option<Spread>,
    /// Linked time over whole, with its 95% interval over placements.
    pub ratio: Option<RatioInterval>,
    /// Images and hit ids bit-identical.
    pub identical: bool,
}

/// Each scene with each set, whole and linked; `size` gives each scene's image size and
/// trace counts.
pub fn trace_linking(
    ctx: &Arc<Context>,
    scenes: &[Scene],
    sets: &[ShaderSet],
    size: impl Fn(&Scene) -> RenderOptions,
    mut progress: impl FnMut(&str),
) -> Result<Vec<LinkingRow>> {
    if !ctx.info.pipeline_library {
        return Err(Error::Unsupported(format!("{} lacks VK_KHR_pipeline_library: nothing to link", ctx.info.name)));
    }
    let mut rows = Vec::new();
    for scene in scenes {
        let opts = size(scene);
        progress(&format!("{} {}x{}", scene.name(), opts.width, opts.height));
        for set in sets {
            let made = [(set.clone(), PipelineKind::Monolithic), (set.clone(), PipelineKind::Libraries)];
            let [whole, linked]: [_; 2] = render_made(ctx, scene, &made, &opts)?
                .try_into()
                .map_err(|_| Error::Unsupported("a render of two pipelines returned another count".into()))?;
            for out in [&whole, &linked] {
                out.written.require(&set.to_string(), "pixels", &format!("{} linked against whole", scene.name()))?;
            }
            let (w, l) = (whole.spread(), linked.spread());
            rows.push(LinkingRow {
                scene: scene.name().to_string(),
                set: set.to_string(),
                width: opts.width,
                height: opts.height,
                whole: w,
                linked: l,
                ratio: linked.ratio_to(&whole),
                identical: whole.rgba == linked.rgba && whole.hit_ids == linked.hit_ids,
            });
        }
    }
    Ok(rows)
}

/// The rows as a Markdown table.
pub fn linking_table(rows: &[LinkingRow]) -> String {
    let mut s = String::from(
        "| scene | size | set | whole ms (IQR) | linked ms (IQR) | linked / whole (95% CI) | images and hit ids |\n|---|---|---|---:|---:|---:|---|\n",
    );
    let ms = |s: Option<Spread>| s.map_or("n/a".into(), |s| format!("{:.3} ({:.3})", s.median, s.iqr()));
    for r in rows {
        s += &format!(
            "| {} | {}x{} | {} | {} | {} | {} | {} |\n",
            r.scene,
            r.width,
            r.height,
            r.set,
            ms(r.whole),
            ms(r.linked),
            r.ratio.map_or("n/a".into(), |r| format!("{:.3} ({:.3} to {:.3})", r.ratio, r.low, r.high)),
            if r.identical { "identical" } else { "DIFFER" }
        );
    }
    s
}
