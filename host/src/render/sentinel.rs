//! Outputs start poisoned. Before a set's stages write the image, the hit ids or probe
//! records, every word of them is filled with [`UNWRITTEN`]; after the trace, what still holds
//! it was never written by that set, and is counted. So a stage that writes nothing (or half
//! the image) fails instead of being judged on another set's output, or on zeros.

use super::barriers::{transition, STORAGE_IMAGE, UNUSED_IMAGE};
use crate::vk::buffer::Buffer;
use crate::vk::commands::{memory_barrier, TRACING_STAGES};
use crate::vk::image::StorageImage;
use ash::vk;
pub use twinray_shared::bindings::UNWRITTEN;

const TRANSFER_WRITE: (vk::PipelineStageFlags, vk::AccessFlags) =
    (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_WRITE);

/// Records filling each of `buffers` with the sentinel, visible to the stages that trace.
pub(crate) fn poison_buffers(device: &ash::Device, cmd: vk::CommandBuffer, buffers: &[&Buffer]) {
    for buffer in buffers {
        // SAFETY: cmd is recording; the buffer was made with TRANSFER_DST and its size is a
        // multiple of 4 (whole words of the layout).
        unsafe { device.cmd_fill_buffer(cmd, buffer.raw, 0, vk::WHOLE_SIZE, UNWRITTEN) };
    }
    let traced = (TRACING_STAGES, vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE);
    memory_barrier(device, cmd, TRANSFER_WRITE, traced);
}

/// Records filling `image` with the sentinel in every channel, through `staging` (a
/// device-local buffer of the image's size, made with TRANSFER_SRC and TRANSFER_DST: a copy
/// keeps the bits exactly, where a clear of a float format may not keep a NaN's), and leaves
/// it in the layout traces write. Its earlier contents are discarded.
pub(crate) fn poison_image(device: &ash::Device, cmd: vk::CommandBuffer, image: &StorageImage, staging: &Buffer) {
    // SAFETY: cmd is recording; the staging buffer holds at least the image's bytes.
    unsafe { device.cmd_fill_buffer(cmd, staging.raw, 0, vk::WHOLE_SIZE, UNWRITTEN) };
    memory_barrier(device, cmd, TRANSFER_WRITE, (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_READ));
    let copy_target = (vk::ImageLayout::TRANSFER_DST_OPTIMAL, TRANSFER_WRITE.0, TRANSFER_WRITE.1);
    transition(device, cmd, image.raw, UNUSED_IMAGE, copy_target);
    let region = [image.whole_copy()];
    // SAFETY: cmd is recording; the image is in TRANSFER_DST_OPTIMAL; sizes match.
    unsafe { device.cmd_copy_buffer_to_image(cmd, staging.raw, image.raw, copy_target.0, &region) };
    let traced = (STORAGE_IMAGE.0, STORAGE_IMAGE.1, vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE);
    transition(device, cmd, image.raw, copy_target, traced);
}

/// Whether a 32-bit word still holds the sentinel.
pub fn unwritten(word: u32) -> bool {
    word == UNWRITTEN
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vk::image::StorageImage;

    #[test]
    fn the_sentinel_is_a_signalling_nan_and_no_id() {
        let f = f32::from_bits(UNWRITTEN);
        assert!(f.is_nan());
        assert_eq!(UNWRITTEN & (1 << 22), 0, "the quiet bit is clear: arithmetic never makes it");
        let computed = f32::INFINITY - f32::INFINITY;
        assert!(computed.is_nan() && !unwritten(computed.to_bits()) && !unwritten(f32::NAN.to_bits()));
        assert!(!unwritten(twinray_shared::bindings::NO_HIT));
    }

    /// What poisoning a set's outputs costs in setup: GPU time of filling a 1920x1080 image and
    /// its hit ids with the sentinel, as each set's output trace does first (never inside the
    /// timed traces). A measurement, run by hand on each device:
    /// `cargo test --release -p twinray-host --lib -- --ignored sentinel_setup_cost --nocapture`.
    #[test]
    #[ignore = "a measurement: prints what the sentinel costs on this machine's device"]
    fn sentinel_setup_cost() {
        use crate::render::prepare::storage_buffer;
        use crate::vk::commands::OneShot;
        use crate::vk::context::{Context, ContextOptions};
        use crate::vk::timing::Timestamps;
        let ctx = Context::new(&ContextOptions::default()).unwrap();
        let (w, h) = (1920u32, 1080u32);
        let pixels = u64::from(w) * u64::from(h);
        let image = StorageImage::new(&ctx, w, h).unwrap();
        let staging = storage_buffer(&ctx, "staging", pixels * 16).unwrap();
        let ids = storage_buffer(&ctx, "ids", pixels * 12).unwrap();
        let runs = 20;
        let Some(timer) = Timestamps::new(&ctx, runs).unwrap() else { return };
        let one_shot = OneShot::new(&ctx).unwrap();
        one_shot
            .run(|device, cmd| {
                timer.reset(cmd);
                for k in 0..runs {
                    timer.begin(cmd, k);
                    poison_image(device, cmd, &image, &staging);
                    poison_buffers(device, cmd, &[&ids]);
                    timer.end(cmd, k);
                }
                Ok(())
            })
            .unwrap();
        let ms = timer.read_ms().unwrap();
        let median = crate::util::stats::median(&ms).unwrap();
        println!("sentinel setup on {}: {median:.3} ms per set (median of {runs}) at {w}x{h}", ctx.info.name);
    }
}
