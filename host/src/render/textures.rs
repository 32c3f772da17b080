//! A scene's textures on the device: the texture array's slot 0 (one white texel, which every
//! slot past the scene's last texture repeats), then each image with its mip chain and
//! sampler, as the scene's build numbered them.

use crate::error::{Error, Result};
use crate::scene::texture::{mip_chain, Filter, SamplerDesc, TextureImage, Wrap};
use crate::vk::commands::OneShot;
use crate::vk::context::Context;
use crate::vk::texture::Texture;
use ash::vk;
use std::sync::Arc;
use twinray_shared::bindings::TEXTURE_SLOTS;

/// Uploads slot 0 and `textures` (slots 1 on).
pub(crate) fn upload_textures(
    ctx: &Arc<Context>,
    one_shot: &OneShot,
    textures: &[(Arc<TextureImage>, SamplerDesc)],
) -> Result<Vec<Texture>> {
    if textures.len() >= TEXTURE_SLOTS as usize {
        return Err(Error::Input(format!(
            "the scene has {} textures; the texture array holds {}",
            textures.len(),
            TEXTURE_SLOTS - 1
        )));
    }
    let white = [(1, 1, &[255u8; 4][..])];
    let mut out = vec![Texture::new(
        ctx,
        one_shot,
        "white",
        vk::Format::R8G8B8A8_UNORM,
        &white,
        &sampler_info(&SamplerDesc::DEFAULT, 0),
    )?];
    for (image, sampler) in textures {
        let chain = if sampler.mipmap.is_some() { mip_chain(image) } else { Vec::new() };
        let mut levels = vec![(image.width, image.height, image.rgba.as_slice())];
        levels.extend(chain.iter().map(|(w, h, t)| (*w, *h, t.as_slice())));
        let format = if image.srgb { vk::Format::R8G8B8A8_SRGB } else { vk::Format::R8G8B8A8_UNORM };
        let info = sampler_info(sampler, levels.len() as u32 - 1);
        out.push(Texture::new(ctx, one_shot, &image.name, format, &levels, &info)?);
    }
    Ok(out)
}

/// What every slot of the texture array binds: the scene's textures, then slot 0 again.
pub(crate) fn slots(textures: &[Texture]) -> Vec<(vk::ImageView, vk::Sampler)> {
    (0..TEXTURE_SLOTS as usize).map(|i| textures.get(i).unwrap_or(&textures[0])).map(|t| (t.view, t.sampler)).collect()
}

/// The Vulkan sampler of `s` over `max_level` levels after the first. No anisotropic
/// filtering: the stages filter long footprints by taps of their own, alike on every device
/// (`twinray_shared::texture::taps`).
fn sampler_info(s: &SamplerDesc, max_level: u32) -> vk::SamplerCreateInfo<'static> {
    let filter = |f: Filter| match f {
        Filter::Linear => vk::Filter::LINEAR,
        Filter::Nearest => vk::Filter::NEAREST,
    };
    let wrap = |w: Wrap| match w {
        Wrap::Repeat => vk::SamplerAddressMode::REPEAT,
        Wrap::Clamp => vk::SamplerAddressMode::CLAMP_TO_EDGE,
        Wrap::Mirror => vk::SamplerAddressMode::MIRRORED_REPEAT,
    };
    let mipmap = match s.mipmap {
        Some(Filter::Linear) => vk::SamplerMipmapMode::LINEAR,
        _ => vk::SamplerMipmapMode::NEAREST,
    };
    vk::SamplerCreateInfo::default()
        .mag_filter(filter(s.mag))
        .min_filter(filter(s.min))
        .mipmap_mode(mipmap)
        .address_mode_u(wrap(s.wrap[0]))
        .address_mode_v(wrap(s.wrap[1]))
        .address_mode_w(vk::SamplerAddressMode::REPEAT)
        .min_lod(0.0)
        .max_lod(if s.mipmap.is_some() { max_level as f32 } else { 0.0 })
}
