//! Deterministic random numbers: the PCG hash of Jarzynski and Olano (JCGT 2020), chained over
//! (seed, pixel, sample, dimension), so the same scene and seed give the same image in both
//! languages: the integer operations are exact everywhere.

/// PCG-RXS-M-XS hash of one 32-bit word.
pub fn pcg(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// Uniform in [0, 1): 24 random bits, exact in f32.
pub fn random(seed: u32, pixel: u32, sample: u32, dimension: u32) -> f32 {
    let h = pcg(dimension.wrapping_add(pcg(sample.wrapping_add(pcg(pixel.wrapping_add(pcg(seed)))))));
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// SplitMix64 (Steele, Lea, Flood 2014), on the host: small, fast, fully specified. It places
/// the spheres of a sphere field and shuffles the orders of timing placements.
#[cfg(not(target_arch = "spirv"))]
pub struct SplitMix64(pub u64);

#[cfg(not(target_arch = "spirv"))]
impl SplitMix64 {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 24 random bits: exact in f32.
    pub fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_and_range() {
        // Computed independently (Python, arbitrary-precision integers masked to 32 bits).
        assert_eq!(pcg(0), 129_708_002);
        assert_eq!(pcg(1), 2_831_084_092);
        let mut sum = 0.0;
        for i in 0..10_000 {
            let x = random(7, i, 3, 1);
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        assert!((sum / 10_000.0 - 0.5).abs() < 0.01, "mean {}", sum / 10_000.0);
    }
}
