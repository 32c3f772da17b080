//! The sRGB transfer function (IEC 61966-2-1), both ways: 8-bit texels that models store
//! sRGB-encoded are decoded to linear values, and the linear radiance twinray renders is encoded
//! for PNGs, which every viewer reads as sRGB. And what an 8-bit image does with radiance above
//! 1 (`--tone-map`).

use std::sync::OnceLock;

/// The linear value of an sRGB-encoded 8-bit channel.
pub fn decode(v: u8) -> f32 {
    let c = f32::from(v) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB-encoded 8-bit channel of a linear value, clipped to [0, 1] first.
pub fn encode(c: f32) -> u8 {
    let c = c.clamp(0.0, 1.0);
    unorm(if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 })
}

/// A value in [0, 1] as an 8-bit channel, rounded to nearest (clipped first).
pub fn unorm(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// What an 8-bit image (PNG) does with radiance above 1, before the sRGB encoding. The linear
/// outputs (`--out FILE.exr`) and every parity metric keep the radiance as rendered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum ToneMap {
    /// Each channel clipped to 1: what is at most 1 is shown as it is.
    #[default]
    Clip,
    /// Each channel c as c / (1 + c) (Reinhard's simple operator): nothing clips, and
    /// everything is darker.
    Reinhard,
}

impl ToneMap {
    /// `c` (linear) mapped into [0, 1].
    pub fn apply(self, c: f32) -> f32 {
        match self {
            ToneMap::Clip => c.clamp(0.0, 1.0),
            ToneMap::Reinhard => (c.max(0.0) / (1.0 + c.max(0.0))).min(1.0),
        }
    }
}

static TONE_MAP: OnceLock<ToneMap> = OnceLock::new();

/// Sets the tone map of every PNG of radiance this process writes (the global `--tone-map`);
/// the first call wins.
pub fn set_tone_map(tone: ToneMap) {
    let _ = TONE_MAP.set(tone);
}

/// The tone map set by [`set_tone_map`]; [`ToneMap::Clip`] if none was.
pub fn tone_map() -> ToneMap {
    TONE_MAP.get().copied().unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoding_matches_the_standard_and_inverts_decoding() {
        // 0.3 linear grey is 149 in sRGB, not 77 (0.3 x 255): what viewers expect.
        assert_eq!(encode(0.3), 149);
        assert_eq!((encode(0.0), encode(1.0), encode(2.0), encode(-1.0)), (0, 255, 255, 0));
        for v in 0..=255u8 {
            assert_eq!(encode(decode(v)), v);
        }
    }

    #[test]
    fn tone_maps_keep_values_in_range() {
        assert_eq!((ToneMap::Clip.apply(0.25), ToneMap::Clip.apply(3.0)), (0.25, 1.0));
        assert_eq!((ToneMap::Reinhard.apply(1.0), ToneMap::Reinhard.apply(0.0)), (0.5, 0.0));
        assert!(ToneMap::Reinhard.apply(1e30) <= 1.0 && ToneMap::Reinhard.apply(-1.0) == 0.0);
    }
}
