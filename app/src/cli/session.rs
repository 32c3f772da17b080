//! What every command that renders shares: the Vulkan context from the global options, and
//! image size and trace counts from the flags.

use crate::args::{FrameArgs, GlobalArgs, ValidateMode, ViewpointArgs};
use anyhow::{Context as _, Result};
use std::sync::Arc;
use twinray_host::scene::check_size;
use twinray_host::util::output::cache_dir;
use twinray_host::{Context, ContextOptions, Error, RenderOptions, Scene, ShaderSet, Validation};

pub fn context(global: &GlobalArgs) -> Result<Arc<Context>> {
    Context::new(&options(global)).context("setting up Vulkan")
}

/// The context options the global flags ask for.
pub fn options(global: &GlobalArgs) -> ContextOptions {
    ContextOptions {
        validation: match global.validate {
            None => Validation::Off,
            Some(ValidateMode::Core) => Validation::Required,
            Some(ValidateMode::Gpu) => Validation::GpuAssisted,
        },
        device_filter: global.device.clone(),
        pipeline_cache: if global.no_pipeline_cache {
            None
        } else {
            Some(global.pipeline_cache.clone().unwrap_or_else(|| cache_dir("pipelines")))
        },
        pipelines: global.pipeline,
        pipeline_threads: global.threads.map(|n| n as usize),
        gpu_timeout: global.gpu_timeout.unwrap_or(twinray_host::vk::context::DEFAULT_GPU_TIMEOUT),
        robust_access: !global.no_robust_access,
        shared_blases: !global.no_shared_blases,
    }
}

/// The still scene `arg` names (a file or a built-in name), at the frame and from the camera
/// `viewpoint` asks for.
/// Its shapes may be of the kinds of the crates `sets` were built from.
pub fn load_still(arg: Option<&str>, viewpoint: &ViewpointArgs, sets: &[&ShaderSet]) -> Result<Scene, Error> {
    let scene = Scene::load_with(arg, &ShaderSet::own_kinds(sets))?;
    let frames = scene.frame_count();
    let frame = viewpoint.frame.unwrap_or(0);
    if frame >= frames {
        let last = frames - 1;
        return Err(Error::Input(format!(
            "--frame {frame} is past the end of {} ({frames} frame(s): 0 to {last})",
            scene.name()
        )));
    }
    let scene = if scene.animation.is_some() { scene.at_frame(frame)? } else { scene };
    scene.with_camera(viewpoint.eye, viewpoint.look_at)
}

/// `--frames` renders a sequence, which a still image's flags cannot choose from.
pub fn refuse_viewpoint_with_frames(viewpoint: &ViewpointArgs) -> Result<(), Error> {
    if viewpoint.given() {
        return Err(Error::Input("--frame, --eye and --look-at choose a still image: leave out --frames".into()));
    }
    Ok(())
}

/// (warm-up, timed traces, placements) when not given: `render` wants an image quickly,
/// `compare` a GPU-time ratio with its interval over placements.
pub const RENDER_TRACES: (u32, u32, u32) = (0, 1, 1);
pub const COMPARE_TRACES: (u32, u32, u32) = (2, 10, twinray_host::render::DEFAULT_PLACEMENTS);

/// Size from the flags, or the scene's, checked against twinray's limits; trace counts from the
/// flags or the defaults given.
pub fn render_options(
    scene: &Scene,
    frame: &FrameArgs,
    (warmup, runs, placements): (u32, u32, u32),
) -> Result<RenderOptions, Error> {
    let width = frame.width.unwrap_or(scene.file.image.width);
    let height = frame.height.unwrap_or(scene.file.image.height);
    check_size(width, height).map_err(Error::Input)?;
    Ok(RenderOptions {
        width,
        height,
        warmup: frame.warmup.unwrap_or(warmup),
        runs: frame.runs.unwrap_or(runs),
        placements: frame.placements.unwrap_or(placements),
        first_placement: 0,
    })
}

/// Shows the library's progress reports (long runs of timed traces) as a bar on stderr; the
/// bar draws only on a terminal, so scripted output is unchanged.
pub fn show_progress() {
    let bar: std::sync::Mutex<Option<indicatif::ProgressBar>> = std::sync::Mutex::new(None);
    twinray_host::util::progress::set_sink(Box::new(move |what, done, total| {
        let Ok(mut slot) = bar.lock() else { return };
        let b = slot.get_or_insert_with(|| {
            let b = indicatif::ProgressBar::new(total);
            if let Ok(style) = indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} {msg} {elapsed_precise}") {
                b.set_style(style);
            }
            b
        });
        b.set_length(total);
        b.set_message(what.to_string());
        b.set_position(done);
        if done >= total {
            b.finish_and_clear();
            *slot = None;
        }
    }));
}

pub fn create_dir(dir: &std::path::Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io { what: "creating", path: dir.to_path_buf(), source })
}
