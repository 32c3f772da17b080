//! The first place a pixel's rays part, in words: between two sets (or one set and the
//! reference), sample by sample in the stage's order: what the primary ray hit, the colour its
//! stages described, its t, then each shadow ray; then the pixel itself. Where a set is wrong,
//! the reference says which, and the stage is named as `bisect` names it.

use super::pixel::{PixelRays, SetRays, SetSample};
use crate::probe::report::Outcome;
use crate::reference::scene::SceneVerdict;
use crate::reference::stage::stage_of;
use crate::render::to_rgba8;
use crate::scene::SceneData;
use glam::{Vec3, Vec4Swizzles};
use serde::Serialize;
use twinray_shared::bindings::{MASK_OCCLUDER, NO_HIT};

/// Relative t difference past which two sets' hits on the same object are said to part: far
/// above f32 rounding of a well-conditioned t (1e-7), below what moves a lit pixel by a step.
pub const T_PARTS: f32 = 1e-4;

/// Where the rays part, and what the evidence says.
#[derive(Clone, Debug, Serialize)]
pub struct Parting {
    /// The primary sample (index among the M x M), if a ray parts.
    pub sample: Option<u32>,
    /// Within it, the light sample (index in its order), if a shadow ray parts.
    pub light_sample: Option<usize>,
    /// The stage the evidence points at ("glsl's sphere_intersection"), if any.
    pub stage: Option<String>,
    /// The finding in words.
    pub text: String,
}

/// The first place the rays of `px` part (between its two sets, or its one set and the
/// reference).
pub fn first_parting(px: &PixelRays) -> Parting {
    let (sets, data) = (&px.sets, &px.data);
    let m2 = px.samples.len();
    for (k, verdict) in px.reference.iter().enumerate() {
        let at = |stage: Option<String>, text: String| Parting {
            sample: Some(k as u32),
            light_sample: None,
            stage,
            text: format!("sample {k} (of {m2}): {text}"),
        };
        if let Some(set) = sets.iter().find(|s| s.samples[k].outcome == Outcome::NoPayload) {
            let stage = format!("{}'s {}", set.label, stage_of(data, verdict));
            let text = format!(
                "{stage} wrote no payload: the payload came back as ray generation poisoned it ({})",
                verdict_words(data, verdict)
            );
            return at(Some(stage), text);
        }
        let parted = match sets.as_slice() {
            [a, b] => primary_parts(data, (a, &a.samples[k]), (b, &b.samples[k]), verdict, px.background),
            [a] => (!matches!(a.samples[k].outcome, Outcome::Agrees | Outcome::Ambiguous)).then(|| {
                let (stage, why) = blame(data, a, &a.samples[k], verdict);
                let said =
                    format!("{}; {}", hit_words(data, &a.label, &a.samples[k].hit), verdict_words(data, verdict));
                (stage, format!("{said}, not ambiguous: {why}"))
            }),
            _ => None,
        };
        if let Some((stage, text)) = parted {
            return at(stage, text);
        }
        if let Some(p) = shadow_parts(px, k) {
            return Parting { sample: Some(k as u32), text: format!("sample {k} (of {m2}): {}", p.text), ..p };
        }
    }
    pixel_parting(sets)
}

/// Angle past which two sets' normals at the same hit are said to part (radians): far above
/// f32 rounding of a normal (1e-7), below what moves a lit pixel by a step.
pub const NORMAL_PARTS: f32 = 1e-3;

/// The angle between two unit vectors, in radians (robust near 0).
fn angle(a: Vec3, b: Vec3) -> f32 {
    2.0 * (a - b).length().atan2((a + b).length())
}

/// The stage that computes the geometric normal of `object`'s hits: a procedural shape's
/// intersection stage (its hit attribute), or a mesh's closest-hit stage (from its vertices).
fn normal_stage(data: &SceneData, object: u32) -> String {
    match data.hit_group_of(object) {
        Some(g) => g.intersection_module().unwrap_or(g.closest_hit_module()).to_string(),
        None => "intersection stage".into(),
    }
}

/// Where two sets' answers for one primary ray part: (stage, words), or `None`.
fn primary_parts(
    data: &SceneData,
    (a, sa): (&SetRays, &SetSample),
    (b, sb): (&SetRays, &SetSample),
    verdict: &SceneVerdict,
    background: Vec3,
) -> Option<(Option<String>, String)> {
    let (ha, hb) = (&sa.hit, &sb.hit);
    let said = format!("{}; {}", hit_words(data, &a.label, ha), hit_words(data, &b.label, hb));
    if ha.ids.w != hb.ids.w && (ha.ids.w == NO_HIT || hb.ids.w == NO_HIT) || ha.ids.xy() != hb.ids.xy() {
        let judged = match verdict {
            SceneVerdict::Ambiguous => {
                return Some((None, format!("{said}; the reference calls the ray ambiguous (within 16 ULPs of a silhouette, rim, tie or t_min): either answer is right")));
            }
            _ => verdict_words(data, verdict),
        };
        let wrong = [(a, sa), (b, sb)].into_iter().find(|(_, s)| s.outcome != Outcome::Agrees);
        let (stage, why) =
            wrong.map_or((None, "both stand against it".to_string()), |(set, s)| blame(data, set, s, verdict));
        return Some((stage, format!("{said}; {judged}, not ambiguous: {why}")));
    }
    if (ha.color.xyz() - hb.color.xyz()).abs().max_element() > 1e-6 {
        let (ca, cb) = (ha.color.xyz(), hb.color.xyz());
        let stage = if ha.ids.w == NO_HIT { "miss".to_string() } else { closest_hit(data, ha.ids.x) };
        let text = format!(
            "{said}; the colour their {stage} stage described differs: {} {} against {} {}",
            a.label,
            rgb(ca),
            b.label,
            rgb(cb)
        );
        if ha.ids.w != NO_HIT {
            return Some((Some(format!("{}'s or {}'s {stage}", a.label, b.label)), text));
        }
        // A miss shows the scene's background: a set that shows another is wrong.
        let wrong: Vec<String> = [(a, ca), (b, cb)]
            .iter()
            .filter(|(_, c)| *c != background)
            .map(|(s, _)| format!("{}'s miss", s.label))
            .collect();
        return Some((Some(wrong.join(" and ")), format!("{text}; the scene's background is {}", rgb(background))));
    }
    let (ta, tb) = (ha.position.w, hb.position.w);
    if ha.ids.w != NO_HIT && (ta - tb).abs() > T_PARTS * ta.abs().max(tb.abs()) {
        let mut text = format!(
            "{said}; the t differ by {:.2e} relative; {}",
            (ta - tb).abs() / ta.abs(),
            verdict_words(data, verdict)
        );
        let worse = match verdict {
            SceneVerdict::Hit { t, .. } => {
                let err = |x: f32| (f64::from(x) - t).abs() / t;
                text += &format!(" ({} off it by {:.2e}, {} by {:.2e} relative)", a.label, err(ta), b.label, err(tb));
                Some(if err(ta) > err(tb) { (a, ha) } else { (b, hb) })
            }
            _ => None,
        };
        let stage = worse.map(|(set, h)| format!("{}'s {}", set.label, intersection(data, h.ids.x)));
        return Some((stage, text));
    }
    let (na, nb) = (ha.geometric_normal.xyz(), hb.geometric_normal.xyz());
    if ha.ids.w != NO_HIT && angle(na, nb) > NORMAL_PARTS {
        let mut text =
            format!("{said}; their geometric normals {} and {} differ by {:.2e} rad", xyz(na), xyz(nb), angle(na, nb));
        let mut stage = None;
        if let SceneVerdict::Hit { normal, .. } = verdict {
            let truth = normal.as_vec3();
            let (ea, eb) = (angle(na, truth), angle(nb, truth));
            text += &format!(
                "; the reference's is {} ({} off it by {ea:.2e} rad, {} by {eb:.2e})",
                xyz(truth),
                a.label,
                b.label
            );
            let (set, h) = if ea > eb { (a, ha) } else { (b, hb) };
            stage = Some(format!("{}'s {}", set.label, normal_stage(data, h.ids.x)));
        }
        return Some((stage, text));
    }
    None
}

/// Where one set's shadow rays of sample `k` first part from the other's (or, for one set,
/// from the reference's answer for the same ray).
fn shadow_parts(px: &PixelRays, k: usize) -> Option<Parting> {
    let (sets, data) = (&px.sets, &px.data);
    let first = &sets.first()?.samples[k];
    for (j, light) in first.lights.iter().enumerate() {
        let answers: Vec<(&SetRays, Option<bool>, Option<SceneVerdict>)> = sets
            .iter()
            .map(|s| {
                let sample = &s.samples[k];
                (s, sample.occluded.get(j).copied().flatten(), sample.shadow_verdicts.get(j).copied().flatten())
            })
            .collect();
        let differ = match answers.as_slice() {
            [(_, a, _), (_, b, _)] => a != b,
            [(_, Some(a), Some(v))] => decided(v).is_some_and(|truth| truth != *a),
            _ => false,
        };
        if !differ {
            continue;
        }
        let said: Vec<String> = answers
            .iter()
            .map(|(set, occluded, verdict)| {
                let got = match occluded {
                    Some(true) => "is occluded".to_string(),
                    Some(false) => "reaches the light".to_string(),
                    None => match set.samples[k].lights.get(j) {
                        Some(l) if l.cosine <= 0.0 => {
                            format!("is not traced: its surface faces away (cosine {:.4})", l.cosine)
                        }
                        _ => "is not traced".to_string(),
                    },
                };
                let truth = verdict.map_or(String::new(), |v| format!(" (the reference: {})", shadow_words(data, &v)));
                format!("{}'s shadow ray {got}{truth}", set.label)
            })
            .collect();
        let wrong = answers.iter().find(|(_, o, v)| v.and_then(|v| decided(&v)).is_some_and(|truth| Some(truth) != *o));
        let stage = wrong.map(|(set, occluded, verdict)| match (occluded, verdict) {
            (Some(false), Some(SceneVerdict::Hit { object, .. })) => {
                format!("{}'s {}", set.label, intersection(data, *object as u32))
            }
            _ => {
                // A shadow the reference does not find: the occluders the ray crosses (holes and
                // all) are the suspects, the nearest first.
                let l = &set.samples[k].lights[j];
                let (o, d) = (l.origin.as_dvec3(), l.direction.as_dvec3());
                let suspects = px.truth.crossings(o, d, (0.0, f64::from(l.distance)), MASK_OCCLUDER);
                match suspects.first() {
                    Some((object, _)) => format!("{}'s {}", set.label, intersection(data, *object as u32)),
                    None => format!("{}'s intersection or any-hit stage of an occluder", set.label),
                }
            }
        });
        let text = format!(
            "light {} shadow sample ({}, {}) aiming at {}: {}",
            light.light,
            light.cell.0,
            light.cell.1,
            xyz(light.target),
            said.join("; ")
        );
        return Some(Parting { sample: None, light_sample: Some(j), stage, text });
    }
    None
}

/// Relative difference past which a set's pixel is not what its rays add up to: the CPU and
/// the GPU add the same f32 terms in the same order, but a driver may fuse a multiply and an add
/// (1e-7 relative each); a ray generation stage that traces or weighs one sample otherwise moves
/// a pixel by far more (a planted off-by-one sample index: 1.3e-3).
pub const REMADE_PARTS: f32 = 1e-4;

/// The largest difference of two colours relative to the larger (at least 1).
fn relative(a: Vec3, b: Vec3) -> f32 {
    ((a - b).abs() / a.abs().max(b.abs()).max(Vec3::ONE)).max_element()
}

/// When no ray parts: each set's pixel against what its rays add up to, then the pixels.
fn pixel_parting(sets: &[SetRays]) -> Parting {
    let steps = |a: Vec3, b: Vec3| {
        let (a, b) = (to_rgba8(&[a.to_array()]), to_rgba8(&[b.to_array()]));
        (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0)
    };
    let none = |stage: Option<String>, text: String| Parting { sample: None, light_sample: None, stage, text };
    for s in sets {
        let off = relative(s.image, s.remade);
        if off > REMADE_PARTS {
            return none(
                Some(format!("{}'s raygen", s.label)),
                format!(
                    "all rays agree, but {}'s image holds {} where its rays add up to {} ({off:.2e} relative): its ray generation stage traces or shades otherwise than the shared code",
                    s.label, rgb(s.image), rgb(s.remade)
                ),
            );
        }
    }
    match sets {
        [a, b] if a.image == b.image => none(None, "all rays agree, and the pixels are identical".into()),
        [a, b] => none(
            None,
            format!(
                "all rays agree; the pixels differ by {:.2e} relative ({} 8-bit step(s)) from rounding in shading",
                relative(a.image, b.image),
                steps(a.image, b.image)
            ),
        ),
        _ => none(None, "every ray agrees with the reference (or is ambiguous)".into()),
    }
}

/// What the reference's answer says of occlusion: `None` when ambiguous.
fn decided(v: &SceneVerdict) -> Option<bool> {
    match v {
        SceneVerdict::Ambiguous => None,
        SceneVerdict::Miss => Some(false),
        SceneVerdict::Hit { .. } => Some(true),
    }
}

/// The stage behind one set's wrong primary answer, judged by `verdict`: (stage, words).
fn blame(data: &SceneData, set: &SetRays, s: &SetSample, verdict: &SceneVerdict) -> (Option<String>, String) {
    let label = &set.label;
    let h = &s.hit;
    let named = |object: u32| format!("{label}'s {}", intersection(data, object));
    match (s.outcome, verdict) {
        (Outcome::FalseMiss, SceneVerdict::Hit { object, .. }) => {
            let stage = named(*object as u32);
            (Some(stage.clone()), format!("{stage} missed {}", object_name(data, *object as u32)))
        }
        (Outcome::FalseHit, _) => {
            let stage = named(h.ids.x);
            (Some(stage.clone()), format!("{stage} reported a hit the reference does not find"))
        }
        (Outcome::WrongObject, SceneVerdict::Hit { object, t, .. }) if f64::from(h.position.w) < *t => {
            let stage = named(h.ids.x);
            (Some(stage.clone()), format!("{stage} reported a hit in front of {}", object_name(data, *object as u32)))
        }
        (Outcome::WrongObject, SceneVerdict::Hit { object, .. }) => {
            let stage = named(*object as u32);
            (Some(stage.clone()), format!("{stage} missed {}", object_name(data, *object as u32)))
        }
        _ => (None, format!("{label} stands against the reference")),
    }
}

/// "sphere #2": the object's hit group and index.
pub fn object_name(data: &SceneData, object: u32) -> String {
    match data.hit_group_of(object) {
        Some(group) => format!("{} #{object}", group.name()),
        None => format!("object #{object}"),
    }
}

/// The intersection stage of `object`'s hit group: its module, or the driver's triangle test
/// (and for cutouts, the any-hit stage that decides holes).
pub fn intersection(data: &SceneData, object: u32) -> String {
    let Some(group) = data.hit_group_of(object) else { return "intersection stage".into() };
    let test = group.intersection_module().map_or("the driver's triangle test".to_string(), str::to_string);
    match group.any_hit_module() {
        Some(any_hit) => format!("{test} (or {any_hit})"),
        None => test,
    }
}

/// The closest-hit module of `object`'s hit group.
fn closest_hit(data: &SceneData, object: u32) -> String {
    data.hit_group_of(object).map_or("closest-hit".into(), |g| g.closest_hit_module().to_string())
}

/// "rust hits sphere #0 at t 4.21830" or "glsl misses".
pub fn hit_words(data: &SceneData, label: &str, h: &twinray_shared::layout::HitPayload) -> String {
    if h.ids.w == NO_HIT {
        format!("{label} misses")
    } else {
        format!("{label} hits {} (primitive {}) at t {}", object_name(data, h.ids.x), h.ids.y, h.position.w)
    }
}

/// "the reference hits sphere #0 at 4.2182966" or "the reference misses".
pub fn verdict_words(data: &SceneData, v: &SceneVerdict) -> String {
    match v {
        SceneVerdict::Miss => "the reference misses".into(),
        SceneVerdict::Hit { object, t, .. } => {
            format!("the reference hits {} at t {t:.9}", object_name(data, *object as u32))
        }
        SceneVerdict::Ambiguous => "the reference calls it ambiguous".into(),
    }
}

/// A shadow ray's reference answer in words.
pub fn shadow_words(data: &SceneData, v: &SceneVerdict) -> String {
    match v {
        SceneVerdict::Miss => "nothing in the way".into(),
        SceneVerdict::Hit { object, t, .. } => format!("{} in the way at t {t:.7}", object_name(data, *object as u32)),
        SceneVerdict::Ambiguous => "ambiguous: either answer is right".into(),
    }
}

pub fn rgb(c: Vec3) -> String {
    format!("({:.6}, {:.6}, {:.6})", c.x, c.y, c.z)
}

pub fn xyz(c: Vec3) -> String {
    format!("({}, {}, {})", c.x, c.y, c.z)
}
