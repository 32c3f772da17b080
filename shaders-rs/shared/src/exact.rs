//! Error-free arithmetic: results rounded at their own size, not at the size of the terms
//! that cancel in them. Each routine leans on steps being done exactly as written: a product of
//! two 12-bit halves is exact, the difference of two multiples of one power of two is exact.
//! A driver may fuse and reassociate floating-point operations that are not decorated
//! `NoContraction` (SPIR-V 2.15), and a reassociated `(x + y) - y` is `x`: so the Rust set's
//! build decorates every floating-point operation of this module's functions `NoContraction`
//! (`twinray-compile`'s `exact` pass, which finds them by name; each is kept out of line for
//! that), and the GLSL twins (exact.glsl) declare their results `precise`.

use glam::Vec3;
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

/// The path every function of this module has in the SPIR-V's names (`OpName`), by which the
/// build finds the operations to decorate.
pub const NAME_PREFIX: &str = "twinray_shared::exact::";

/// `x` cut to its top 12 significant bits, and the rest: both halves have at most 12 bits, so
/// the product of two such halves is exact in f32. Integer masking, not Veltkamp's
/// `c - (c - x)`, which a compiler may contract.
#[inline(always)]
fn split(x: f32) -> (f32, f32) {
    let high = f32::from_bits(x.to_bits() & 0xFFFF_F000);
    (high, x - high)
}

/// o + d t, rounded relative to the result, not to the terms: near a surface far from the
/// origin, o and d t are large and nearly cancel, and the plain sum loses their ULPs (1e-3 at
/// 1e4) unless the driver fuses the multiply and add (NVIDIA does, lavapipe does not). The
/// product is split into exact partial products so no fusion is needed.
#[inline(never)]
pub fn point_at(o: Vec3, d: Vec3, t: f32) -> Vec3 {
    let (th, tl) = split(t);
    let axis = |o: f32, d: f32| {
        let (dh, dl) = split(d);
        (o + dh * th) + (dh * tl + dl * th) + dl * tl
    };
    Vec3::new(axis(o.x, d.x), axis(o.y, d.y), axis(o.z, d.z))
}

/// `a - b` as a sum `high + low` that rounds nothing of the order of `a` or `b`: both are cut at
/// one power of two Q, 2^-12 of the larger's binade, into a multiple of Q and the rest. The
/// multiples' difference has at most 14 significant bits and is exact; only the rests' (below
/// Q) is rounded, at 2^-36 of the larger. The cut is a truncation and the powers of two come
/// from the exponent's bits: TwoSum's `(a + b) - b`, the usual exact difference, is what a
/// driver's algebraic passes fold to `a` (lavapipe's did, in the Rust set, whose SPIR-V cannot
/// say `NoContraction`), and no pass undoes a truncation.
#[inline(always)]
fn split_difference(a: f32, b: f32) -> (f32, f32) {
    let (a_size, b_size) = (a.abs(), b.abs());
    let larger = if a_size > b_size { a_size } else { b_size };
    // The larger's biased exponent, at least 24 so that Q stays a normal number.
    let exponent = (larger.to_bits() >> 23) & 0xff;
    let exponent = if exponent > 24 { exponent } else { 24 };
    let quantum = f32::from_bits((exponent - 12) << 23);
    let inverse = f32::from_bits((266 - exponent) << 23);
    let (a_high, b_high) = ((a * inverse).trunc() * quantum, (b * inverse).trunc() * quantum);
    (a_high - b_high, (a - a_high) - (b - b_high))
}

/// [`split_difference`] of each component.
#[inline(always)]
fn split_differences(a: Vec3, b: Vec3) -> (Vec3, Vec3) {
    let (x, y, z) = (split_difference(a.x, b.x), split_difference(a.y, b.y), split_difference(a.z, b.z));
    (Vec3::new(x.0, y.0, z.0), Vec3::new(x.1, y.1, z.1))
}

/// The world-space offset `(origin - translation) + shift direction`, rounded at its own size:
/// the ray's origin moved `shift` along it, relative to an instance's translation. Far from the
/// instance both terms are large and cancel; `split_differences` and `point_at` keep what
/// plain arithmetic would round away (`transform::near_ray`).
#[inline(never)]
pub fn moved_origin(origin: Vec3, translation: Vec3, direction: Vec3, shift: f32) -> Vec3 {
    let (high, low) = split_differences(origin, translation);
    point_at(high, direction, shift) + low
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Far from the origin the plain sum is off by the terms' ULPs; `point_at` by the result's.
    #[test]
    fn point_at_is_accurate_where_its_terms_cancel() {
        let mut worst = 0.0f64;
        for k in 0..1000u32 {
            let a = k as f32 * 0.618;
            let d = Vec3::new(a.sin() * 3e-4, -1.0, a.cos() * 3e-4).normalize();
            let o = Vec3::new(12.25, 9876.5, -3.75) + Vec3::new(a.cos(), 0.0, a.sin());
            let t = (9876.0 / -d.y) * (1.0 + 1e-5 * (a.sin()));
            let got = point_at(o, d, t);
            let error = |o: f32, d: f32, got: f32| (f64::from(o) + f64::from(d) * f64::from(t) - f64::from(got)).abs();
            worst = worst.max(error(o.x, d.x, got.x)).max(error(o.y, d.y, got.y)).max(error(o.z, d.z, got.z));
        }
        // The result is a few units from the origin: its ULPs are ~1e-6 (not 1e-3).
        assert!(worst < 2e-5, "worst error {worst}");
    }

    /// The split difference loses at most 2^-36 of the larger term, where the plain one loses
    /// up to 2^-25 of it; across binades, signs and zero.
    #[test]
    fn a_split_difference_keeps_what_the_plain_one_rounds() {
        let values = [0.0f32, 1.0, -3.75, 1e-30, 12345.679, -9876.543, 3.1e4, 1.7e-3, -2.5e7, 0.1];
        let mut plain_lost = 0.0f64;
        for &a in &values {
            for &b in &values {
                for (a, b) in [(a, b), (a * 1.37, b), (a, -b * 0.61)] {
                    let (high, low) = split_difference(a, b);
                    let exact = f64::from(a) - f64::from(b);
                    let larger = f64::from(a.abs().max(b.abs()));
                    let error = (f64::from(high) + f64::from(low) - exact).abs();
                    assert!(error <= larger * 2f64.powi(-36), "{a} - {b}: off by {error:e}");
                    plain_lost = plain_lost.max((f64::from(a - b) - exact).abs() / larger.max(1e-300));
                }
            }
        }
        assert!(plain_lost > 2f64.powi(-30), "the plain difference rounded nothing: {plain_lost:e}");
    }
}
