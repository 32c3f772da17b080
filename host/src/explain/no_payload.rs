//! Which stage wrote no payload. Ray generation poisons the payload before each trace and
//! counts the rays whose hit or miss stage left it so (`Written::no_payload_rays`); which stage
//! took each ray is not something ray generation can see, so the f64 reference says where the
//! ray went: the closest-hit stage of the object it hits, or the miss stage. This runs only
//! when a set failed so: a clean render traces nothing here.

use super::rays::Camera;
use crate::reference::scene::SceneReference;
use crate::reference::stage::{lines, stage_of, verdict};
use crate::render::{NoPayloadPixel, RenderOutput};
use crate::scene::Scene;
use std::collections::BTreeMap;

/// Most pixels whose first such ray is traced by the reference; beyond it, an even subset
/// stands for the rest, and the line says so.
const MOST_PIXELS: usize = 4096;

/// The lines naming the stages that wrote no payload in `out`, a render of `scene` with `set`:
/// each pixel's rays counted against the stage its first such ray went to. Empty when every
/// payload was written; an error line when the reference cannot be built.
pub fn render_lines(scene: &Scene, out: &RenderOutput, set: &str) -> Vec<String> {
    if out.no_payload.is_empty() {
        return Vec::new();
    }
    let reference = match SceneReference::new(scene) {
        Ok(r) => r,
        Err(e) => {
            return vec![format!(
                "which stage wrote no payload in {set} is unknown: the f64 reference of {}: {e}",
                scene.name()
            )]
        }
    };
    let data = scene.build();
    let camera = Camera::new(scene, (out.width, out.height));
    let step = out.no_payload.len().div_ceil(MOST_PIXELS);
    let mut counts = BTreeMap::new();
    for p in out.no_payload.iter().step_by(step) {
        let NoPayloadPixel { pixel, first_sample, rays } = *p;
        let ray = camera.sample((pixel % out.width, pixel / out.width), first_sample).ray;
        *counts.entry(stage_of(&data, &verdict(&reference, &ray))).or_insert(0) += u64::from(rays) * step as u64;
    }
    let how = if step == 1 {
        "each pixel's rays by where the f64 reference sends its first such ray".to_string()
    } else {
        format!("estimated from every {step}th such pixel, by where the f64 reference sends its first such ray")
    };
    lines(&counts, set, &how)
}
