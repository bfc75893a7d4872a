//! The integer kernel's depth order and its Q16 Lab #1 shade ([`nz_q16`], [`shade`]).
//!
//! ## Depth and shade
//!
//! Where `D ≥ 0` the hit distance's numerator `T = b − √D` (`t = T/a`, the same `a` for
//! every sphere of the pixel) orders the spheres; [`isqrt`](crate::math::wide::isqrt)
//! has error `< 2^(h+1)` with the sphere's per-frame shift `h = ⌈(bits(d_max²·ρ²) − 32)/2⌉` (`D ≤ a·ρ²`: about
//! `4·|d|·ρ·2⁻¹⁶`). Lab #1 needs `n·(−w) = (ℓz − t·F)/ρ = (ℓz·a − F·T)/(a·ρ)`: formed
//! from `a` and `T` shifted right by the frame's `p` (so `a >> p < 2³¹` and
//! `T >> p < 2³²`: 32×32-bit products; the `ℓz/ρ` part is unchanged by it), then
//! divided once in 32 bits after a per-frame shift `q` ([`nz_q16`]). The shade factor's
//! error against the quantised sphere is `≤ 2ʰ⁺¹/(F·ρ)` (root, `a ≥ F²`) `+ 2ᵖ/(F·ρ)`
//! (shift) `+ 2/((F² >> p)·ρ >> q) + 2⁻¹⁶` (division, smallest divisor at the image's
//! centre), `+ (ℓz + ρ)·2ᵖ/(F²·ρ)` (the shift of `a` in `T/a`); the quantisation moves
//! the sphere by `m ≤ √3/2 + ½` (its centre's and radius's rounding, measured per
//! sphere and frame), which turns the normal by at most `m/ρ` where the hit's
//! half-chord `h` is large and by `≈ m/h` near the rim: with the rest of the budget
//! `β`, the hits with `h < g = m/β` form a ring `g²/(2ρ)` wide (λ units) along the
//! silhouette, where the shade moves with the edge. The rule takes the frame only where
//! the sum is < 2⁻⁹ (under one level of 255, with room for the `f32` result's own
//! rounding) and that ring, added to the edge bound, is within 1/16 pixel: there the
//! image is that of the sphere moved by less than 1/16 pixel. Colours are
//! `(c·k + 2¹⁵) >> 16` with `k = max(n·(−w), 0.3)` in Q16.

use embedded_graphics::pixelcolor::Rgb888;

use crate::math::wide::{div_q16, shr_u64_low, ARMV6M};

/// `n·(−w)` in Q16 from `num = ℓz·a − F·T` and `den = a·ρ > 0` (`|num|, den < 2⁶³`),
/// clamped to `[0, 2¹⁶]`.
///
/// Both are shifted right by `q` (`den >> q < 2¹⁵`), then divided once in 32 bits.
/// Error bound: `≤ 2/(den >> q) + 2⁻¹⁶` (the truncations and the
/// quotient's floor).
#[inline(always)]
pub(crate) fn nz_q16(num: i64, den: u64, q: u32) -> u32 {
    if num <= 0 {
        return 0;
    }
    // num > 0 from here.
    if num as u64 >= den {
        return 1 << 16;
    }
    let (n, d) = (shr_u64_low(num as u64, q), shr_u64_low(den, q));
    if d == 0 {
        return 0;
    }
    // n ≤ d < 2¹⁵: n·2¹⁶ < 2³¹.
    if ARMV6M {
        div_q16(n, d)
    } else {
        (n << 16) / d
    }
}

/// Lab #1's `clamp(n_z, 0.3, 1)` in Q16 (`0.3·2¹⁶ = 19660.8`, taken as 19661) and the
/// channels `round(c·k)`.
#[inline(always)]
pub(super) fn shade(rgb: [u8; 3], nz: u32) -> Rgb888 {
    const AMBIENT_Q16: u32 = 19_661;
    let k = nz.max(AMBIENT_Q16);
    let ch = |c: u8| ((u32::from(c) * k + (1 << 15)) >> 16) as u8;
    Rgb888::new(ch(rgb[0]), ch(rgb[1]), ch(rgb[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One step of the xorshift64 generator the random tests draw from.
    fn xorshift(x: &mut u64) {
        *x ^= *x << 13;
        *x ^= *x >> 7;
        *x ^= *x << 17;
    }

    /// `nz_q16` within `2/(den >> q) + 2⁻¹⁶` of the exact quotient, over the divisor's
    /// whole range and shifts that leave it 15 down to 6 bits.
    #[test]
    fn nz_bound() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200_000 {
            xorshift(&mut x);
            let den = ((x >> 3) >> (x % 50)).max(1) as i64;
            let frac = (x % 10_007) as f64 / 10_007.0;
            let num = (den as f64 * frac) as i64;
            let bits = 64 - den.leading_zeros();
            for keep in [15, 11, 6] {
                let q = bits.saturating_sub(keep);
                let d = (den >> q) as f64;
                let got = f64::from(nz_q16(num, den as u64, q)) / 65536.0;
                let exact = num as f64 / den as f64;
                let bound = 2.0 / d + 1.0 / 65536.0;
                assert!(
                    (got - exact).abs() <= bound,
                    "{num}/{den} q {q}: {got} vs {exact}"
                );
            }
        }
        assert_eq!(nz_q16(-5, 10, 0), 0);
        assert_eq!(nz_q16(i64::MIN, 10, 0), 0);
        assert_eq!(nz_q16(11, 10, 0), 1 << 16);
        assert_eq!(nz_q16(10, 10, 0), 1 << 16);
    }
}
