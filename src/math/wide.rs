//! Integer arithmetic the integer kernel and the silhouettes' integer cuts share.
//!
//! The exact `u32` square root, the Q16 division without a divide instruction, and the
//! wide products and shifts, written out on ARMv6-M (Cortex-M0/M0+) without library
//! calls — the same bits as the operators, which every other target uses; and the
//! exact `f64` product of two normal `f32` (or a zero), which the silhouettes' dot
//! products are made of.

/// `SQRT_TABLE[k] = ⌊√((k + 64)·2²⁴)⌋` (the last entry, `2¹⁶`, kept as `2¹⁶ − 1`):
/// [`isqrt32`]'s estimate of `√n` at `n`'s top eight bits, `n >> 24` in `[64, 256)`
/// (its successor, up to 256, for the interpolation).
// Evaluated at compile time: an index out of range would fail the build.
#[allow(clippy::indexing_slicing)]
pub(crate) const SQRT_TABLE: [u16; 193] = {
    let mut t = [0u16; 193];
    let mut k = 0;
    while k < 193 {
        // ⌊√x⌋ by bisection on [0, 2¹⁷): lo² ≤ x < hi².
        let x = (k as u64 + 64) << 24;
        let (mut lo, mut hi) = (0u64, 1u64 << 17);
        while hi - lo > 1 {
            let m = (lo + hi) / 2;
            if m * m <= x {
                lo = m;
            } else {
                hi = m;
            }
        }
        t[k] = if lo > 0xffff { 0xffff } else { lo as u16 };
        k += 1;
    }
    t
};

/// `⌊√v⌋` of a `u32`, exactly, in a few steps whatever `v`.
///
/// The digit-by-digit root takes sixteen rounds of compare and subtract
/// (`docs/firmware.md`, "The integer kernel", gives its cost on a Cortex-M0). Here `v` is
/// normalised to `n = v·4ᵉ` in `[2³⁰, 2³²)`, `√n` estimated from
/// [`SQRT_TABLE`] at `n`'s top eight bits, linearly interpolated on its next eight,
/// `r = ⌊s/2ᵉ⌋`, then `r` counted up while `(r + 1)² ≤ v`.
///
/// Why it is exact: every step of the estimate rounds down — the table's entries are
/// floors, the chord between two entries lies below the concave root, the
/// interpolation drops `n`'s low sixteen bits and floors its product, the shift floors
/// — so `s ≤ √n` and `r ≤ s/2ᵉ ≤ √v`, i.e. `r ≤ ⌊√v⌋`; the count-up then reaches `⌊√v⌋`
/// exactly. It runs at most twice (the estimate is never more than 2 below, over every
/// `u32`: test `isqrt32_is_exact_everywhere`). No product overflows: `r ≤ 2¹⁶ − 1`, so
/// `r² < 2³²`, and the interpolation's `(hi − lo)·255 < 2¹⁶`.
#[inline(always)]
pub(crate) fn isqrt32(v: u32) -> u32 {
    if v == 0 {
        return 0;
    }
    let (mut n, mut e) = (v, 0u32);
    if n < 1 << 16 {
        n <<= 16;
        e += 8;
    }
    if n < 1 << 24 {
        n <<= 8;
        e += 4;
    }
    if n < 1 << 28 {
        n <<= 4;
        e += 2;
    }
    if n < 1 << 30 {
        n <<= 2;
        e += 1;
    }
    // n >> 24 in [64, 256): the index is in [0, 192), its successor at most 192.
    let k = ((n >> 24) - 64) as usize;
    let entry = |i: usize| SQRT_TABLE.get(i).copied().map_or(0, u32::from);
    let (lo, hi) = (entry(k), entry(k + 1));
    let s = lo + ((hi.saturating_sub(lo) * ((n >> 16) & 255)) >> 8);
    let mut r = s >> e;
    // r ≤ ⌊√v⌋ (doc): count up while (r + 1)² ≤ v, i.e. while v − r² > 2r.
    let mut rem = v - r * r;
    while rem > 2 * r {
        rem -= 2 * r + 1;
        r += 1;
    }
    r
}

/// An approximate `√v`: `v` shifted right by `2h`, its exact [`isqrt32`], shifted
/// back, for `v < 2³²⁺²ʰ`.
///
/// Error bound: `0 ≤ √v − isqrt(v, h) < 2^(h+1)`.
#[inline(always)]
pub(crate) fn isqrt(v: u128, h: u32) -> u64 {
    shl_u64(isqrt32(shr_u128_low(v, 2 * h)), h)
}

// Shifts of 64- and 128-bit integers by a distance known only at run time, from
// 32-bit words: on the Cortex-M0 the `>>`/`<<` operators are library calls
// (`__aeabi_llsr`, `__aeabi_llsl`), four of them per hit pixel. Each is exact: the same
// bits as the operator. Used on ARMv6-M only ([`ARMV6M`]): RV32 and the Cortex-M3/M4
// shift register pairs inline, in fewer instructions, so elsewhere each is the operator.

/// `(x >> s) as u32`, `s < 64`.
#[inline(always)]
pub(crate) fn shr_u64_low(x: u64, s: u32) -> u32 {
    if ARMV6M {
        shr_u64_low_words(x, s)
    } else {
        (x >> s) as u32
    }
}

/// `(v >> s) as u32`, `s < 128`.
#[inline(always)]
pub(crate) fn shr_u128_low(v: u128, s: u32) -> u32 {
    if ARMV6M {
        shr_u128_low_words(v, s)
    } else {
        (v >> s) as u32
    }
}

/// `u64::from(x) << s`, `s < 64`.
#[inline(always)]
pub(crate) fn shl_u64(x: u32, s: u32) -> u64 {
    if ARMV6M {
        shl_u64_words(x, s)
    } else {
        u64::from(x) << s
    }
}

/// [`shr_u64_low`] from 32-bit words.
///
/// `(hi << 1) << (31 − s)` is `hi << (32 − s)`
/// without a shift by 32 at `s = 0` (where the high word contributes nothing).
#[inline(always)]
pub(crate) fn shr_u64_low_words(x: u64, s: u32) -> u32 {
    let (lo, hi) = (x as u32, (x >> 32) as u32);
    if s >= 32 {
        hi >> (s & 31)
    } else {
        (lo >> s) | ((hi << 1) << (31 - s))
    }
}

/// [`shr_u128_low`] from 32-bit words.
#[inline(always)]
pub(crate) fn shr_u128_low_words(v: u128, s: u32) -> u32 {
    let word = |k: u32| -> u32 {
        match k {
            0 => v as u32,
            1 => (v >> 32) as u32,
            2 => (v >> 64) as u32,
            3 => (v >> 96) as u32,
            _ => 0,
        }
    };
    let (k, r) = (s / 32, s % 32);
    if r == 0 {
        word(k)
    } else {
        (word(k) >> r) | (word(k + 1) << (32 - r))
    }
}

/// [`shl_u64`] from 32-bit words.
#[inline(always)]
pub(crate) fn shl_u64_words(x: u32, s: u32) -> u64 {
    let (lo, hi) = if s >= 32 {
        (0, x << (s & 31))
    } else if s == 0 {
        (x, 0)
    } else {
        (x << s, x >> (32 - s))
    };
    (u64::from(hi) << 32) | u64::from(lo)
}

/// `x·y` as a `u64`: on ARMv6-M from four 16-bit products ([`mul_wide_halves`]);
/// elsewhere the operator.
#[inline(always)]
pub(crate) fn mul_wide(x: u32, y: u32) -> u64 {
    if ARMV6M {
        mul_wide_halves(x, y)
    } else {
        u64::from(x) * u64::from(y)
    }
}

/// [`mul_wide`] from 16-bit halves, exactly, for every `x`, `y`.
///
/// The Cortex-M0's `MULS` keeps the low 32 bits of a product, and a `u64` multiply is a
/// library call there (`__aeabi_lmul`, a full 64×64-bit product). With `x = x₁·2¹⁶ + x₀`,
/// `y = y₁·2¹⁶ + y₀`, the four half products fit a `u32` each; the two cross products'
/// sum carries into bit 48, and its low half added to the low word carries into the
/// high word. Used on ARMv6-M only ([`ARMV6M`]): RV32 (`MULHU`) and the
/// Cortex-M3/M4 (`UMULL`) have the 64-bit product in one or two instructions.
#[inline(always)]
pub(crate) fn mul_wide_halves(x: u32, y: u32) -> u64 {
    let (x1, x0) = (x >> 16, x & 0xffff);
    let (y1, y0) = (y >> 16, y & 0xffff);
    let (mid, mid_carry) = (x1 * y0).overflowing_add(x0 * y1);
    let (lo, carry) = (x0 * y0).overflowing_add(mid << 16);
    let hi = x1 * y1 + (mid >> 16) + (u32::from(mid_carry) << 16) + u32::from(carry);
    (u64::from(hi) << 32) | u64::from(lo)
}

/// `f64::from(a) * f64::from(b)`: on ARMv6-M from the significands' 24×24-bit integer
/// product ([`mul_f32_exact_words`]; there an `f64` multiply is a software routine,
/// its cost in `docs/firmware.md`); elsewhere the operator.
///
/// The product is exact: two 24-bit significands make at most 48 bits, within `f64`'s
/// 53, and two `f32` exponents stay inside `f64`'s normal range. So both ways give the
/// same bits.
#[inline(always)]
pub(crate) fn mul_f32_exact(a: f32, b: f32) -> f64 {
    if ARMV6M {
        mul_f32_exact_words(a, b)
    } else {
        f64::from(a) * f64::from(b)
    }
}

/// [`mul_f32_exact`] from 32-bit words, the same bits for every `a`, `b`.
///
/// For normal `a` and `b`, the significands `ma, mb ∈ [2²³, 2²⁴)` give
/// `a·b = ±ma·mb·2^(ea + eb − 300)` (`ea`, `eb` the biased exponents) with
/// `ma·mb ∈ [2⁴⁶, 2⁴⁸)`: its top bit is bit `46 + top`, so the `f64`'s exponent is
/// `ea + eb − 254 + top ∈ [−252, 255]` (normal) and its fraction the bits below the top
/// one, shifted up to 52 bits — no bit is lost, so no rounding. A zero times a finite
/// number is a zero signed as the product; a subnormal, infinite or NaN operand takes
/// the operator.
///
/// Out of line: inlined at each of a dot product's three products, its registers
/// spill into the caller's frame and deepen the integer plan's stack on the Cortex-M0
/// (the measured stacks: `docs/firmware.md`).
#[inline(never)]
pub(crate) fn mul_f32_exact_words(a: f32, b: f32) -> f64 {
    let (x, y) = (a.to_bits(), b.to_bits());
    let (ea, eb) = ((x >> 23) & 0xff, (y >> 23) & 0xff);
    let sign = u64::from((x ^ y) & 0x8000_0000) << 32;
    // Biased exponents 1..=254 are the normal numbers.
    if ea.wrapping_sub(1) >= 254 || eb.wrapping_sub(1) >= 254 {
        // A zero times a finite number (common: a vector along an axis) is a zero of
        // the two signs' product.
        if (x << 1 == 0 && eb != 255) || (y << 1 == 0 && ea != 255) {
            return f64::from_bits(sign);
        }
        return f64::from(a) * f64::from(b);
    }
    let (ma, mb) = ((x & 0x7f_ffff) | 0x80_0000, (y & 0x7f_ffff) | 0x80_0000);
    let p = mul_wide(ma, mb);
    // Constant shifts only: a variable one is a library call on ARMv6-M.
    let (top, frac) = if p >> 47 != 0 { (1, p << 5) } else { (0, p << 6) };
    let exp = u64::from(ea + eb + top + 1023 - 254);
    f64::from_bits(sign | (exp << 52) | (frac & ((1 << 52) - 1)))
}

/// `x·y` of two `i32` as an `i64`: on ARMv6-M from the magnitudes' 32×32-bit product
/// ([`mul_i32_wide_halves`]; an `i64` multiply there is `__aeabi_lmul`, a full
/// 64×64-bit product); elsewhere the operator.
#[inline(always)]
pub(crate) fn mul_i32_wide(x: i32, y: i32) -> i64 {
    if ARMV6M {
        mul_i32_wide_halves(x, y)
    } else {
        i64::from(x) * i64::from(y)
    }
}

/// [`mul_i32_wide`] from [`mul_wide_halves`] of the magnitudes, the sign applied
/// after.
///
/// Exact for every `x`, `y`: `|x·y| ≤ 2⁶²`.
#[inline(always)]
pub(crate) fn mul_i32_wide_halves(x: i32, y: i32) -> i64 {
    let p = mul_wide_halves(x.unsigned_abs(), y.unsigned_abs()) as i64;
    if (x < 0) != (y < 0) {
        -p
    } else {
        p
    }
}

/// `x·y` of two `i64` as an `i128`: on ARMv6-M from the magnitudes' 32-bit halves
/// ([`mul_i64_wide_halves`]; the operator there is a chain of `__aeabi_lmul` calls);
/// elsewhere the operator.
#[inline(always)]
pub(crate) fn mul_i64_wide(x: i64, y: i64) -> i128 {
    if ARMV6M {
        mul_i64_wide_halves(x, y)
    } else {
        i128::from(x) * i128::from(y)
    }
}

/// [`mul_i64_wide`] from four [`mul_wide_halves`] of the magnitudes' 32-bit halves
/// (`x₁y₁·2⁶⁴ + (x₁y₀ + x₀y₁)·2³² + x₀y₀`, summed in `u128`), the sign applied after.
///
/// Exact for every `x`, `y`: `|x·y| ≤ 2¹²⁶`.
#[inline(always)]
pub(crate) fn mul_i64_wide_halves(x: i64, y: i64) -> i128 {
    let (xu, yu) = (x.unsigned_abs(), y.unsigned_abs());
    let (x1, x0) = ((xu >> 32) as u32, xu as u32);
    let (y1, y0) = ((yu >> 32) as u32, yu as u32);
    let mid = u128::from(mul_wide_halves(x1, y0)) + u128::from(mul_wide_halves(x0, y1));
    let p = (u128::from(mul_wide_halves(x1, y1)) << 64) + (mid << 32) + u128::from(mul_wide_halves(x0, y0));
    let p = p as i128;
    if (x < 0) != (y < 0) {
        -p
    } else {
        p
    }
}

/// Whether the target is ARMv6-M (Cortex-M0, M0+): no divide instruction, no
/// 32×32→64-bit multiply, no 64-bit shifts but by library calls.
///
/// Told apart by its
/// missing compare-and-swap atomics (ARMv7-M and ARMv8-M Baseline have both those
/// and compare-and-swap). There [`div_q16`], the wide products ([`mul_wide`],
/// [`mul_i32_wide`], [`mul_i64_wide`]) and the word-wise shifts replace the operators
/// (same results; elsewhere the operators are cheaper).
pub(crate) const ARMV6M: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// `R[k] = ⌊2²³/(k + 257)⌋`, the reciprocals of [`div_q16`] (`< 2¹⁵`): a lower bound
/// of `2²⁹/D` for every `D` in `[(k + 256)·2⁶, (k + 257)·2⁶)`.
// Evaluated at compile time: an index out of range would fail the build.
#[allow(clippy::indexing_slicing)]
pub(crate) const RECIPROCALS: [u16; 256] = {
    let mut r = [0u16; 256];
    let mut k = 0;
    while k < 256 {
        r[k] = ((1u32 << 23) / (k as u32 + 257)) as u16;
        k += 1;
    }
    r
};

/// `⌊n·2¹⁶/d⌋` for `n ≤ d`, `1 ≤ d < 2¹⁵`, exactly, without a divide instruction
/// (the Cortex-M0's `__aeabi_uidiv` is a shift-and-subtract loop): two 32-bit
/// multiplies by a table reciprocal, then at most two corrections.
///
/// Why it is exact: `d` and `n` are doubled until `D = d·2ᵉ ≥ 2¹⁴` (the quotient is
/// unchanged; `m = n·2ᵉ ≤ D < 2¹⁵`). With `R ≤ 2²⁹/D` from the table,
/// `q₀ = ⌊m·R/2¹³⌋ ≤ Q = m·2¹⁶/D` and, `R ≥ (2²⁹/D)·256/257 − 1`, `Q − q₀ ≤ 260`
/// (`Q ≤ 2¹⁶`, `m < 2¹⁵`), so the remainder `r = m·2¹⁶ − q₀·D < 261·D < 2²⁴`. Then
/// `q₁ = ⌊⌊r/2⁷⌋·R/2²²⌋ ≤ r/D` and `r/D − q₁ < 2.03`: at most two subtractions of `D`
/// remain, done by the loop, which only ever counts up to the true quotient (every
/// estimate is a lower bound). No product reaches 2³² (`m·R < 2³⁰`,
/// `⌊r/2⁷⌋·R < 2³¹`). Outside its range (`d ≥ 2¹⁵`, which the kernel's shifts rule out) it
/// divides. Test: `div_q16_is_exact` (every `d`, the extreme and spread `n`; every
/// `(n, d)` in the ignored, release-mode `div_q16_is_exact_everywhere`).
#[inline(always)]
pub(crate) fn div_q16(n: u32, d: u32) -> u32 {
    if d == 0 || d >= 1 << 15 || n > d {
        return (n << 16).checked_div(d).unwrap_or(0);
    }
    let (mut m, mut dd) = (n, d);
    while dd < 1 << 14 {
        dd <<= 1;
        m <<= 1;
    }
    // dd in [2¹⁴, 2¹⁵): the index is (dd >> 6) − 256 in [0, 256).
    // (A missing entry, impossible here, would leave the whole quotient to the loop.)
    let inv = RECIPROCALS
        .get(((dd >> 6) & 255) as usize)
        .copied()
        .map_or(0, u32::from);
    let q0 = (m * inv) >> 13;
    let mut r = (m << 16) - q0 * dd;
    let q1 = ((r >> 7) * inv) >> 22;
    r -= q1 * dd;
    let mut q = q0 + q1;
    while r >= dd {
        r -= dd;
        q += 1;
    }
    q
}

#[cfg(test)]
mod tests;
