//! `twinray crosscheck`: twinray's converged references against Mitsuba 3's renders of the
//! same scenes, so that the reference every accuracy figure is measured against is itself
//! checked by a renderer nobody here wrote (docs/shading-model.md).

pub mod compare;
pub mod convert;
pub mod report;
pub mod run;
mod textures;

use compare::{compose, diff_image, figures, Composed, Figures};
use serde::Serialize;
use std::path::Path;
use twinray_host::error::{Error, Result};
use twinray_host::render::to_picture;
use twinray_host::util::output::write_png;

/// One scene's result.
#[derive(Clone, Debug, Serialize)]
pub struct SceneCheck {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub twinray_spp: u32,
    pub mitsuba_spp: u32,
    #[serde(flatten)]
    pub figures: Figures,
    /// What Mitsuba draws with another shape than twinray's.
    pub notes: Vec<String>,
}

/// Compares twinray's `radiance` and `uncovered` (1 - coverage) with the Mitsuba renders in
/// `mitsuba_dir`; writes `twinray.png`, `mitsuba.png` and `diff.png` into `out` when given.
pub fn check(
    radiance: &[[f32; 3]],
    uncovered: &[f32],
    twinray_spp: u32,
    mitsuba_dir: &Path,
    out: Option<&Path>,
) -> Result<SceneCheck> {
    let (manifest, lights, emitters) = run::read_mitsuba(mitsuba_dir)?;
    if radiance.len() != (manifest.width as usize) * (manifest.height as usize) {
        return Err(Error::Input(format!(
            "{}: Mitsuba rendered {}x{}, which is not twinray's image size",
            mitsuba_dir.display(),
            manifest.width,
            manifest.height
        )));
    }
    let mitsuba = compose(&lights, &emitters, manifest.background);
    let figures = figures(radiance, uncovered, &mitsuba);
    if let Some(out) = out {
        write_images(out, (manifest.width, manifest.height), radiance, &mitsuba, figures.mean)?;
    }
    Ok(SceneCheck {
        scene: manifest.scene,
        width: manifest.width,
        height: manifest.height,
        twinray_spp,
        mitsuba_spp: manifest.spp,
        figures,
        notes: manifest.notes,
    })
}

fn write_images(out: &Path, (w, h): (u32, u32), twinray: &[[f32; 3]], mitsuba: &Composed, mean: f64) -> Result<()> {
    std::fs::create_dir_all(out).map_err(|source| Error::Io { what: "creating", path: out.into(), source })?;
    write_png(&out.join("twinray.png"), w, h, &to_picture(twinray))?;
    write_png(&out.join("mitsuba.png"), w, h, &to_picture(&mitsuba.radiance))?;
    write_png(&out.join("diff.png"), w, h, &diff_image(twinray, mitsuba, mean))
}
