//! An animated PNG (APNG) written frame by frame as frames are rendered: to a temporary file
//! beside the target, renamed when the last frame is in, so a failure leaves nothing behind.
//! Viewers without APNG support show the first frame.

use crate::error::{Error, Result};
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// An APNG being written.
pub struct AnimatedPng {
    writer: Option<png::Writer<BufWriter<File>>>,
    tmp: PathBuf,
    path: PathBuf,
}

impl AnimatedPng {
    /// Starts `path`: `frames` RGBA8 frames of `width` x `height`, shown `fps` per second,
    /// looping forever.
    pub fn create(path: &Path, (width, height): (u32, u32), frames: u32, fps: f32) -> Result<AnimatedPng> {
        let tmp = super::output::temp_path(path);
        let file = File::create(&tmp).map_err(|source| Error::Io { what: "creating", path: tmp.clone(), source })?;
        let fail = |e: png::EncodingError| Error::Input(format!("writing {}: {e}", path.display()));
        let mut encoder = png::Encoder::new(BufWriter::new(file), width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        encoder.set_animated(frames, 0).map_err(fail)?;
        // The delay as a fraction of a second: milliseconds, at least 1.
        let delay_ms = (1000.0 / fps).round().clamp(1.0, f32::from(u16::MAX)) as u16;
        encoder.set_frame_delay(delay_ms, 1000).map_err(fail)?;
        let writer = encoder.write_header().map_err(fail)?;
        Ok(AnimatedPng { writer: Some(writer), tmp, path: path.to_path_buf() })
    }

    /// Appends the next frame.
    pub fn add(&mut self, rgba: &[u8]) -> Result<()> {
        let writer =
            self.writer.as_mut().ok_or_else(|| Error::Input("an animated PNG written after its end".into()))?;
        writer.write_image_data(rgba).map_err(|e| Error::Input(format!("writing {}: {e}", self.path.display())))
    }

    /// Writes the end and moves the file into place; every frame must have been added.
    pub fn finish(mut self) -> Result<()> {
        let finished = match self.writer.take() {
            Some(writer) => writer.finish().map_err(|e| Error::Input(format!("writing {}: {e}", self.path.display()))),
            None => Ok(()),
        };
        let moved = finished.and_then(|()| {
            std::fs::rename(&self.tmp, &self.path).map_err(|source| Error::Io {
                what: "renaming a finished animated PNG to",
                path: self.path.clone(),
                source,
            })
        });
        if moved.is_err() {
            let _ = std::fs::remove_file(&self.tmp);
        }
        moved
    }
}

impl Drop for AnimatedPng {
    fn drop(&mut self) {
        // Unfinished (an error on the way): leave no partial file.
        if self.writer.is_some() {
            self.writer = None;
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}
