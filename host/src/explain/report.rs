//! `twinray explain`'s report: every ray of the pixel per set and for the reference, the pixel,
//! and the first place they part; as text, and as one JSON object.

use super::parting::{first_parting, hit_words, rgb, shadow_words, verdict_words, xyz, Parting};
use super::pixel::{PixelRays, SetSample};
use super::surface::{self, Surface};
use crate::reference::scene::SceneVerdict;
use glam::{Vec3, Vec4Swizzles};
use serde::Serialize;
use std::fmt::Write;

/// The whole report.
#[derive(Serialize)]
pub struct ExplainReport {
    pub scene: String,
    pub pixel: [u32; 2],
    pub size: [u32; 2],
    /// The frame of an animated scene (0 for a still one).
    pub frame: u32,
    pub samples: Vec<SampleReport>,
    pub sets: Vec<PixelReport>,
    /// Each set's full spec, where its label (a long spec is called "set A" or "set B") is not it.
    pub specs: Vec<String>,
    /// The pixel of a converged reference image (`--converged`), rendered by set A.
    pub converged: Option<Converged>,
    pub parting: Parting,
    /// The text report's lines for the samples (the JSON's fields, in words).
    #[serde(skip)]
    text: String,
}

#[derive(Serialize)]
pub struct Converged {
    pub spp: u32,
    pub value: [f32; 3],
}

#[derive(Serialize)]
pub struct SampleReport {
    pub index: u32,
    pub stratum: [u32; 2],
    pub origin: [f32; 3],
    pub direction: [f32; 3],
    /// "hit", "miss" or "ambiguous"; with a hit, the object, t and normal.
    pub reference: RefReport,
    pub sets: Vec<SetSampleReport>,
}

#[derive(Serialize)]
pub struct RefReport {
    pub verdict: &'static str,
    pub object: Option<usize>,
    pub t: Option<f64>,
    pub normal: Option<[f64; 3]>,
    /// What its hit is on.
    pub surface: Option<Surface>,
}

#[derive(Serialize)]
pub struct SetSampleReport {
    pub set: String,
    pub hit: bool,
    pub object: Option<u32>,
    pub primitive: Option<u32>,
    pub hit_kind: Option<u32>,
    pub t: Option<f32>,
    pub geometric_normal: Option<[f32; 3]>,
    pub shading_normal: Option<[f32; 3]>,
    /// Albedo, an emitter's radiance, or the background.
    pub color: [f32; 3],
    /// Against the reference: agrees, ambiguous, false_hit, false_miss or wrong_object.
    pub outcome: &'static str,
    pub lights: Vec<LightReport>,
    /// What the sample adds to the pixel (before the mean over samples).
    pub radiance: [f32; 3],
    /// What its hit is on.
    pub surface: Option<Surface>,
}

#[derive(Serialize)]
pub struct LightReport {
    pub light: u32,
    pub cell: [u32; 2],
    pub target: [f32; 3],
    pub origin: [f32; 3],
    pub direction: [f32; 3],
    pub distance: f32,
    pub cosine: f32,
    /// Whether a shadow ray is traced (the light casts shadows and the surface faces it).
    pub traced: bool,
    pub occluded: Option<bool>,
    /// The reference's answer for the same ray: "occluded", "clear" or "ambiguous".
    pub reference: Option<&'static str>,
}

#[derive(Serialize)]
pub struct PixelReport {
    pub set: String,
    /// The pixel in the set's image (linear).
    pub image: [f32; 3],
    /// What the set's rays add up to, as its ray generation stage averages them.
    pub rays: [f32; 3],
}

impl ExplainReport {
    /// The report of `px` (frame `frame` of its scene).
    pub fn new(px: &PixelRays, frame: u32, converged: Option<Converged>) -> ExplainReport {
        let samples = px
            .samples
            .iter()
            .enumerate()
            .map(|(k, s)| SampleReport {
                index: s.index,
                stratum: [s.stratum.0, s.stratum.1],
                origin: s.ray.origin.xyz().to_array(),
                direction: s.ray.direction.xyz().to_array(),
                reference: RefReport { surface: px.reference_surfaces[k].clone(), ..ref_report(&px.reference[k]) },
                sets: px.sets.iter().map(|set| set_sample(&set.label, &set.samples[k])).collect(),
            })
            .collect();
        let sets = px
            .sets
            .iter()
            .map(|s| PixelReport { set: s.label.clone(), image: s.image.to_array(), rays: s.remade.to_array() })
            .collect();
        let parting = first_parting(px);
        let text = sample_lines(px);
        ExplainReport {
            scene: px.scene.clone(),
            pixel: [px.pixel.0, px.pixel.1],
            size: [px.size.0, px.size.1],
            frame,
            samples,
            sets,
            specs: Vec::new(),
            converged,
            parting,
            text,
        }
    }

    /// The report in words.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        let labels: Vec<&str> = self.sets.iter().map(|p| p.set.as_str()).collect();
        let _ = writeln!(
            s,
            "explain {}: pixel {},{} of {}x{}{}, {} primary sample(s), {} against the f64 reference",
            self.scene,
            self.pixel[0],
            self.pixel[1],
            self.size[0],
            self.size[1],
            if self.frame > 0 { format!(", frame {}", self.frame) } else { String::new() },
            self.samples.len(),
            labels.join(" and ")
        );
        for spec in &self.specs {
            let _ = writeln!(s, "{spec}");
        }
        s.push_str(&self.text);
        for p in &self.sets {
            let (image, rays) = (Vec3::from(p.image), Vec3::from(p.rays));
            let _ = writeln!(s, "pixel, {}: image {}, its rays add up to {}", p.set, rgb(image), rgb(rays));
        }
        match &self.converged {
            Some(c) => {
                let _ = writeln!(s, "pixel, converged reference ({} spp): {}", c.spp, rgb(Vec3::from(c.value)));
            }
            None => s.push_str("pixel, converged reference: not asked (--converged SPP renders one)\n"),
        }
        let _ = writeln!(s, "first place they part: {}", self.parting.text);
        if let Some(stage) = &self.parting.stage {
            let _ = writeln!(s, "stage: {stage}");
        }
        s
    }
}

/// Each sample's rays in words: the ray, the reference's verdict, each set's answer, and each
/// of its light samples.
fn sample_lines(px: &PixelRays) -> String {
    let data = &px.data;
    let mut s = String::new();
    for (k, sample) in px.samples.iter().enumerate() {
        let (o, d) = (sample.ray.origin.xyz(), sample.ray.direction.xyz());
        let _ = writeln!(
            s,
            "sample {} (stratum {},{}): origin {}, direction {}",
            sample.index,
            sample.stratum.0,
            sample.stratum.1,
            xyz(o),
            xyz(d)
        );
        let _ = writeln!(s, "  {}", verdict_words(data, &px.reference[k]));
        if let Some(on) = &px.reference_surfaces[k] {
            let _ = writeln!(s, "    {}", surface::words(on));
        }
        for set in &px.sets {
            let ss = &set.samples[k];
            let h = &ss.hit;
            if ss.outcome == crate::probe::report::Outcome::NoPayload {
                // What the payload holds is the poison, or the last ray's: no answer to print.
                let _ = writeln!(s, "  {}: no payload (the stage that took the ray wrote none)", set.label);
                continue;
            }
            let normals = if h.ids.w == twinray_shared::bindings::NO_HIT {
                String::new()
            } else {
                format!(
                    ", hit kind {}, geometric normal {}, shading normal {}",
                    h.ids.w,
                    xyz(h.geometric_normal.xyz()),
                    xyz(h.shading_normal.xyz())
                )
            };
            // A closest hit that shades leaves radiance, not an albedo for ray generation to light.
            let shaded =
                h.ids.w != twinray_shared::bindings::NO_HIT && h.ids.z == twinray_shared::bindings::MATERIAL_SHADED;
            let colour = if shaded { "radiance its closest hit shaded" } else { "colour" };
            let _ = writeln!(
                s,
                "  {}{normals}, {colour} {} ({}); adds {}",
                hit_words(data, &set.label, h),
                rgb(h.color.xyz()),
                ss.outcome.name(),
                rgb(ss.radiance)
            );
            if let Some(on) = &ss.surface {
                let _ = writeln!(s, "    {}", surface::words(on));
            }
            for (j, l) in ss.lights.iter().enumerate() {
                let answer = match ss.occluded[j] {
                    Some(true) => "occluded".to_string(),
                    Some(false) => "reaches the light".to_string(),
                    None if l.cosine <= 0.0 => "faces away: no ray".to_string(),
                    None => "casts no shadow: no ray".to_string(),
                };
                let truth = ss.shadow_verdicts[j]
                    .map_or(String::new(), |v| format!(" (reference: {})", shadow_words(data, &v)));
                let _ = writeln!(
                    s,
                    "    light {} sample ({}, {}) at {}: cosine {:.6}, {answer}{truth}",
                    l.light,
                    l.cell.0,
                    l.cell.1,
                    xyz(l.target),
                    l.cosine
                );
            }
        }
    }
    s
}

fn ref_report(v: &SceneVerdict) -> RefReport {
    match v {
        SceneVerdict::Miss => RefReport { verdict: "miss", object: None, t: None, normal: None, surface: None },
        SceneVerdict::Ambiguous => {
            RefReport { verdict: "ambiguous", object: None, t: None, normal: None, surface: None }
        }
        SceneVerdict::Hit { object, t, normal } => RefReport {
            verdict: "hit",
            object: Some(*object),
            t: Some(*t),
            normal: Some(normal.to_array()),
            surface: None,
        },
    }
}

fn set_sample(label: &str, s: &SetSample) -> SetSampleReport {
    let h = &s.hit;
    let hit = h.ids.w != twinray_shared::bindings::NO_HIT;
    SetSampleReport {
        set: label.to_string(),
        hit,
        object: hit.then_some(h.ids.x),
        primitive: hit.then_some(h.ids.y),
        hit_kind: hit.then_some(h.ids.w),
        t: hit.then_some(h.position.w),
        geometric_normal: hit.then_some(h.geometric_normal.xyz().to_array()),
        shading_normal: hit.then_some(h.shading_normal.xyz().to_array()),
        color: h.color.xyz().to_array(),
        outcome: s.outcome.name(),
        lights: s
            .lights
            .iter()
            .enumerate()
            .map(|(j, l)| LightReport {
                light: l.light,
                cell: [l.cell.0, l.cell.1],
                target: l.target.to_array(),
                origin: l.origin.to_array(),
                direction: l.direction.to_array(),
                distance: l.distance,
                cosine: l.cosine,
                traced: l.traced,
                occluded: s.occluded[j],
                reference: s.shadow_verdicts[j].map(|v| match v {
                    SceneVerdict::Miss => "clear",
                    SceneVerdict::Hit { .. } => "occluded",
                    SceneVerdict::Ambiguous => "ambiguous",
                }),
            })
            .collect(),
        radiance: s.radiance.to_array(),
        surface: s.surface.clone(),
    }
}
