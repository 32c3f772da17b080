//! Where the f64 reference sends a ray, as the stage that takes it: the closest-hit stage of
//! the object it hits, or the miss stage. Names the stage that wrote no payload for a ray
//! (ray generation can see that the payload came back poisoned, not which stage had it).

use super::scene::{SceneReference, SceneVerdict};
use crate::scene::SceneData;
use std::collections::BTreeMap;
use twinray_shared::layout::ProbeRay;

/// The stage a ray went to, by the reference's verdict: "procedural_closest_hit (sphere)",
/// "miss", or both where the reference cannot decide.
pub fn stage_of(data: &SceneData, verdict: &SceneVerdict) -> String {
    match verdict {
        SceneVerdict::Miss => "miss".into(),
        SceneVerdict::Hit { object, .. } => match data.hit_group_of(*object as u32) {
            Some(group) => format!("{} ({})", group.closest_hit_module(), group.name()),
            None => format!("the closest-hit stage of object {object}"),
        },
        SceneVerdict::Ambiguous => "closest-hit or miss (the ray grazes an edge)".into(),
    }
}

/// The reference's verdict on a probe-shaped ray.
pub fn verdict(reference: &SceneReference, ray: &ProbeRay) -> SceneVerdict {
    let (o, d) = (ray.origin.truncate().as_dvec3(), ray.direction.truncate().as_dvec3());
    reference.trace(o, d, f64::from(ray.origin.w), f64::from(ray.direction.w))
}

/// Rays by stage, as lines: "812 rays whose procedural_closest_hit (sphere) wrote no payload in
/// rust". `counts` holds each stage's rays.
pub fn lines(counts: &BTreeMap<String, u64>, set: &str, how: &str) -> Vec<String> {
    counts.iter().map(|(stage, rays)| format!("{rays} rays whose {stage} wrote no payload in {set} ({how})")).collect()
}
