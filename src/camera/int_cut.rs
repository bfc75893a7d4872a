//! A silhouette's per-row cut in integer arithmetic ([`IntCut`]), for the integer kernel.

use super::span::{rows_around, Ellipse, Silhouette};
use crate::math::wide::{isqrt32, mul_i32_wide, mul_wide};

/// A silhouette's per-row cut in integer arithmetic, for the integer kernel.
///
/// On a chip without an FPU the `f32` cut ([`Silhouette::row_span`]) is a dozen
/// soft-float calls per sphere and row (`docs/firmware.md`, "The integer kernel",
/// measures them on a Cortex-M0), this one a few 32-bit multiplies and one integer
/// square root.
///
/// ## Why it culls nothing a hit can reach
///
/// Its columns contain those of `row_span`'s formula evaluated **exactly** on the
/// stored `f32` coefficients — `xc ± (hw + pad)` with `xc = xc0 + kx·dy`,
/// `hw² = h0·(1 + 2⁻¹⁶) − q·dy²`, `pad = 1 + (|xc0| + |kx·dy| + hw)·2⁻²⁰`,
/// `dy = j − y0` — and that interval holds every column the enlarged silhouette holds:
/// the coefficients' own `f32` rounding (relative `2⁻²⁴`, `xc0` within `2⁻⁴`) is far
/// inside the slack `2⁻¹⁶·h0` and the pad's column, which were sized to cover it and
/// the per-row `f32` rounding besides. What they do not cover (`y0f`'s rounding, up to
/// `2⁻²⁵` rows, on an ellipse less than `2⁻⁸` rows tall; the `f64` coefficients' own
/// rounding) is far inside the spare margin of the integer kernel's silhouette, which
/// is enlarged by at least 1/8 pixel to cover 1/16. Every step below rounds outward:
/// - `dy·2¹²` lies in `(dy₁₂ − 1, dy₁₂]` with `dy₁₂ = 2¹²·j − ⌊2¹²·y0⌋` (exact), so
///   `m = dy₁₂ − 1` (or `−dy₁₂`) bounds `2¹²·|dy|` from below;
/// - `q·dy² ≥ ⌊q·2²⁴⌋·m²/2⁴⁸`, floored again to `2⁻³²`, and `h0·(1 + 2⁻¹⁶)` is taken
///   rounded up to `2⁻⁸`: an upper bound of `hw²`, rounded up to `2⁻⁶` and its root
///   up to `2⁻³` ([`isqrt32`](crate::math::wide::isqrt32), exact, plus one where not a
///   square);
/// - the centre `xc0 + kx·dy` from `xc0` and `kx` rounded to `2⁻¹⁶` and `dy₁₂`:
///   within `e = 2⁻¹⁷ + 2⁻¹⁷·|dy| + (|kx| + 2⁻¹⁷)·2⁻¹² + 2⁻¹⁶` (the last the shift's
///   floor), taken at the largest `|dy|` of the cut's rows
///   ([`Silhouette::int_cut_rows`]) and added to the pad with the pad's relative part
///   at its largest;
/// - `lo = ⌊xc − hw − pad⌋`, `hi = ⌊xc + hw + pad⌋ + 1`.
///
/// The coefficients come from the `f32` ones' bits in integer arithmetic (no soft
/// `f64` on a chip without an FPU): the roundings below are exact, and the pad is an
/// integer upper bound of its formula, term by term (at most 3/65536 above the formula
/// rounded up; `int_cut_coefficients_are_their_definitions`).
///
/// Where the ranges that keep its coefficients in 32 bits and its products in 64 do
/// not hold (`q ≥ 2⁸`, `h0·(1 + 2⁻¹⁶) ≥ 2²⁴ − 1`, `|kx|, |xc0|, |dy| ≥ 2¹⁵`, `|y0| > 2¹⁸`) or a
/// coefficient is not finite, every column ([`IntCut::All`]): slower, never wrong.
/// Test: `int_cut_holds_the_exact_row_span` (in `camera/span/tests.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum IntCut {
    /// Every column of every row.
    All,
    /// The cut's fixed-point coefficients (their roundings: [`IntCut`]).
    Ellipse {
        /// `⌊2¹²·y0⌋`.
        y12: i32,
        /// `⌊2²⁴·q⌋`.
        q24: u32,
        /// `⌈2⁸·h0·(1 + 2⁻¹⁶)⌉`.
        h8: u32,
        /// `round(2¹⁶·xc0)`, `round(2¹⁶·kx)` and `⌈2¹⁶·(pad + e)⌉` at the largest `|dy|`
        /// (or a few units above: [`IntCut`]).
        xc16: i32,
        kx16: i32,
        pad16: i32,
    },
}

impl Silhouette {
    /// The integer cut of this silhouette and the rows `[j0, j1)` of `0..height`
    /// outside which its [`IntCut::row_span`] is `None`.
    ///
    /// The rows are found by binary search on the cut's own fixed-point test (no
    /// floating point per row): its `hw²` bound is non-increasing in `m`, and `m` falls
    /// then rises with `j`, so the rows passing it are an interval around the centre
    /// row. They hold every row the exact formula reaches ([`IntCut`]'s rounding is
    /// outward), so every row a hit can reach. The cut's pad is then taken at those
    /// rows' largest `|dy|`. Outside the fixed-point ranges, every column: of the rows
    /// [`Self::rows`] finds (soft `f32`, but rare), or of the rows the test found.
    pub(crate) fn int_cut_rows(&self, height: u32) -> ((u32, u32), IntCut) {
        let Some(Ellipse {
            y0i,
            y0f,
            q,
            h0,
            xc0,
            kx,
        }) = self.get()
        else {
            return ((0, height), IntCut::All);
        };
        // The comparisons also reject NaN and infinities.
        if !(q > 0.0 && q < 256.0 && h0 < 16_777_216.0 && y0i.abs() <= 262_144.0 && y0f.abs() <= 1.0) {
            return (self.rows(height), IntCut::All);
        }
        if h0 < 0.0 {
            // No row: hw² < 0 at every dy.
            return ((0, 0), IntCut::All);
        }
        // h8 = ⌈2⁸·h0·(1 + 2⁻¹⁶)⌉ = ⌈m·(2¹⁶ + 1)·2ᵉ⁻⁸⌉ for h0 = m·2ᵉ (m < 2²⁴).
        let (m, e) = scaled(h0, 0);
        let h8 = ceil_shift((m << 16) + m, e - 8);
        // h0·(1 + 2⁻¹⁶) < 2²⁴ − 1, the range the row test's products are argued for.
        let Ok(h8) = u32::try_from(h8) else {
            return (self.rows(height), IntCut::All);
        };
        if h8 >= 4_294_967_040 {
            return (self.rows(height), IntCut::All);
        }
        // y0i is whole (|y0i| ≤ 2¹⁸): ⌊2¹²·y0⌋ = 2¹²·y0i + ⌊2¹²·y0f⌋.
        let (m, e) = scaled(y0f, 12);
        let y0f12 = if y0f < 0.0 {
            -(ceil_shift(m, e) as i64)
        } else {
            floor_shift(m, e) as i64
        };
        let (m, e) = scaled(q, 24);
        let rows = Rows {
            y12: (y0i as i32) * 4096 + y0f12 as i32,
            q24: floor_shift(m, e) as u32,
            h8,
        };
        let (j0, j1) = rows.interval(height);
        if j0 >= j1 {
            return ((j0, j1), IntCut::All);
        }
        if !(kx.abs() < 32_768.0 && xc0.abs() < 32_768.0) {
            return ((j0, j1), IntCut::All);
        }
        // 2¹²·|j − y0| ≤ |2¹²·j − y12| + 1 (2¹²·y0 in [y12, y12 + 1)): the rows' largest
        // |dy| in 2⁻¹² rows, rounded up.
        let d12 = |j: u32| (i64::from(j) * 4096 - i64::from(rows.y12)).unsigned_abs() + 1;
        let dy12 = d12(j0).max(d12(j1));
        if dy12 >= 32_768 * 4096 {
            return ((j0, j1), IntCut::All);
        }
        let ((xc16, x_up), (kx16, k_up)) = (round_and_up(xc0), round_and_up(kx));
        // hw ≤ √(h8/2⁸) ≤ ⌈√h8⌉/2⁴.
        let r = isqrt32(h8);
        let hw4 = u64::from(r + u32::from(r * r < h8));
        // 2¹⁶·(pad + e) = 2¹⁶ + (|xc0| + |kx·dy| + hw)·2⁻⁴ + ½ + ½·|dy| + 2⁴·|kx| + 2⁻¹³ + 1,
        // times 2³² and bounded from above term by term (|xc0| ≤ x_up·2⁻¹⁶,
        // |kx| ≤ k_up·2⁻¹⁶, |dy| ≤ dy12·2⁻¹², hw ≤ hw4·2⁻⁴): below 2⁵⁹.
        let t32 = (1u64 << 48)
            + (x_up << 12)
            + mul_wide(k_up as u32, dy12 as u32)
            + (hw4 << 24)
            + (1 << 31)
            + (dy12 << 19)
            + (k_up << 20)
            + (1 << 19)
            + (1 << 32);
        // ⌈2¹⁶·(pad + e)⌉ at most: below 16 pixels, or every column.
        let pad16 = (t32 >> 32) + u64::from(t32 as u32 != 0);
        if pad16 >= 16 << 16 {
            return ((j0, j1), IntCut::All);
        }
        let cut = IntCut::Ellipse {
            y12: rows.y12,
            q24: rows.q24,
            h8: rows.h8,
            xc16,
            kx16,
            pad16: pad16 as i32,
        };
        ((j0, j1), cut)
    }
}

/// `|x|·2ᵏ = m·2ᵉ` exactly, as `(m, e)` with `m < 2²⁴` (`x` finite).
#[inline(always)]
fn scaled(x: f32, k: i32) -> (u64, i32) {
    let bits = x.to_bits() & 0x7fff_ffff;
    let (exp, mant) = ((bits >> 23) as i32, u64::from(bits & 0x7f_ffff));
    if exp == 0 {
        (mant, k - 149)
    } else {
        (mant | 1 << 23, exp - 150 + k)
    }
}

/// `⌊m·2ᵉ⌋` (`m < 2⁴²`; the callers' ranges keep it below 2⁶⁴, else `u64::MAX`).
#[inline(always)]
fn floor_shift(m: u64, e: i32) -> u64 {
    match e {
        0..=63 => m << e,
        64.. => u64::MAX,
        -63..0 => m >> -e,
        _ => 0,
    }
}

/// `⌈m·2ᵉ⌉` (`m < 2⁴²`; the callers' ranges keep it below 2⁶⁴, else `u64::MAX`).
#[inline(always)]
fn ceil_shift(m: u64, e: i32) -> u64 {
    match e {
        0..=63 => m << e,
        64.. => u64::MAX,
        -63..0 => (m >> -e) + u64::from(m & ((1 << -e) - 1) != 0),
        _ => u64::from(m != 0),
    }
}

/// `round(2¹⁶·x)` (halves away from zero, as `f64::round`) and `⌈2¹⁶·|x|⌉`, for
/// `|x| < 2¹⁵`.
#[inline(always)]
fn round_and_up(x: f32) -> (i32, u64) {
    let (m, e) = scaled(x, 16);
    // ⌊2¹⁶·|x| + ½⌋ = ⌊(m + 2⁻ᵉ⁻¹)·2ᵉ⌋ where e < 0 (below 2³¹).
    let rounded = match e {
        0.. => floor_shift(m, e),
        -63..0 => (m + (1 << (-e - 1))) >> -e,
        _ => 0,
    } as i32;
    (if x < 0.0 { -rounded } else { rounded }, ceil_shift(m, e))
}

/// The cut's row test: its coefficients `⌊2¹²·y0⌋`, `⌊2²⁴·q⌋` and
/// `⌈2⁸·h0·(1 + 2⁻¹⁶)⌉` (`|y0| ≤ 2¹⁸ + 1`).
#[derive(Clone, Copy)]
struct Rows {
    y12: i32,
    q24: u32,
    h8: u32,
}

impl Rows {
    /// Row `j`'s `dy₁₂ = 2¹²·j − ⌊2¹²·y0⌋` and `2³²·hw²` bounded from above, or `None`
    /// where that bound is below zero (no column).
    #[inline(always)]
    fn hw2(self, j: u32) -> Option<(i64, u64)> {
        // 2¹²·dy in (dy12 − 1, dy12]; m ≤ 2¹²·|dy| < 2³¹ (j < 2¹⁶, |y0| ≤ 2¹⁸ + 1).
        let dy12 = (i64::from(j) << 12) - i64::from(self.y12);
        let m = (if dy12 > 0 { dy12 - 1 } else { -dy12 }) as u32;
        let m2 = mul_wide(m, m);
        // ⌊q24·m²/2¹⁶⌋ ≤ 2³²·q·dy² (q24·m² < 2⁹⁴).
        let q_dy2 = ((u128::from(mul_wide(self.q24, (m2 >> 32) as u32)) << 32)
            + u128::from(mul_wide(self.q24, m2 as u32)))
            >> 16;
        // 2³²·hw² at most 2²⁴·h8 − q_dy2 (below zero: no column).
        let hw2 = (u128::from(self.h8) << 24).checked_sub(q_dy2)? as u64;
        Some((dy12, hw2))
    }

    /// The rows of `0..height` whose test passes: an interval, since `m` falls to its
    /// least at the last row with `dy₁₂ ≤ 0` or the first with `dy₁₂ > 0` and rises
    /// on both sides, and the bound falls as `m` rises.
    fn interval(self, height: u32) -> (u32, u32) {
        let past = |j: u32| (i64::from(j) << 12) > i64::from(self.y12);
        rows_around(height, &past, &|j| self.hw2(j).is_some())
    }
}

impl IntCut {
    /// The columns `[lo, hi)` of row `j` (clamped to `[0, width)`) whose rays can hit
    /// the sphere; `None` if none can.
    #[inline]
    pub(crate) fn row_span(&self, j: u32, width: u32) -> Option<(u32, u32)> {
        let IntCut::Ellipse {
            y12,
            q24,
            h8,
            xc16,
            kx16,
            pad16,
        } = *self
        else {
            return Some((0, width));
        };
        let (dy12, hw2) = Rows { y12, q24, h8 }.hw2(j)?;
        // 2⁶·hw² rounded up.
        let v = (hw2 >> 26) + u64::from(hw2 & ((1 << 26) - 1) != 0);
        let Ok(v) = u32::try_from(v) else {
            return Some((0, width));
        };
        // ⌈√v⌉ = 2³·hw rounded up, as 2¹⁶·hw.
        let r = isqrt32(v);
        let hw16 = i64::from(r + u32::from(r * r < v)) << 13;
        // |dy12| < 2²⁸ (the rows' |dy| < 2¹⁵): an i32.
        let xc = i64::from(xc16) + (mul_i32_wide(kx16, dy12 as i32) >> 12);
        let w = i64::from(width);
        let pad16 = i64::from(pad16);
        let lo = ((xc - hw16 - pad16) >> 16).clamp(0, w) as u32;
        let hi = (((xc + hw16 + pad16) >> 16) + 1).clamp(0, w) as u32;
        (lo < hi).then_some((lo, hi))
    }
}
