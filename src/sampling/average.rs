//! A pixel's `n × n` sub-pixel rays: their directions, and their colours averaged in
//! linear light and encoded back to sRGB.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;

use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::trace::frame::{Frame, FrameSphere};
use crate::trace::scanline::RowTracer;
use crate::trace::shade::Shader;

include!(concat!(env!("OUT_DIR"), "/srgb_tables.rs"));

/// The camera's steps and the sub-pixel offsets of an `n × n` grid.
///
/// **Sub-pixel directions** are formed directly from the camera's per-frame steps
/// (`F` the upper-left pixel's direction, `du`, `dv` the column and row steps), for
/// every stepping: `d = (F + dv·y) + du·x` with `x = i + o_a`, `y = j + o_b`. Error
/// bound: the offset `o` (exact for `n` = 2 and 4, one rounding of `≤ 2⁻²⁵` for 3) and
/// `i + o` round by at most `2⁻²⁴·(|i| + 1)`, moving `d` by `≤ 2⁻²⁴·S`; the two products
/// and two sums round by `≤ 4·2⁻²⁴·S` (`S = |F| + H·|dv| + W·|du|` as in `stepping.rs`):
/// `|d − ideal| ≤ 2⁻²³·3·S`, within `Stepping::Direct`'s bound.
pub(super) struct SubSteps {
    first: Vec3,
    du: Vec3,
    dv: Vec3,
    offsets: [f32; 4],
    pub(super) n: usize,
}

impl SubSteps {
    pub(super) fn new<T: TestStrategy, Sh: Shader>(frame: &Frame<'_, T, Sh>, n: u32) -> Self {
        let mut offsets = [0.0; 4];
        for (a, o) in offsets.iter_mut().enumerate().take(n as usize) {
            // (a + ½)/n − ½ = (2a + 1 − n)/(2n): one rounding (none for n = 2, 4).
            *o = (2.0 * a as f32 + 1.0 - n as f32) / (2.0 * n as f32);
        }
        let c = frame.camera;
        Self {
            first: c.first_direction(),
            du: c.pixel_step(),
            dv: c.scanline_step(),
            offsets,
            n: n as usize,
        }
    }

    /// The centre ray's direction formed the same way (for
    /// [`Sample::direction`](crate::trace::options::Sample::direction)).
    pub(super) fn center(&self, i: u32, j: u32) -> Vec3 {
        (self.first + self.dv * j as f32) + self.du * i as f32
    }
}

/// Pixel `(i, j)` with `Grid(n)`'s rays: each traced against every sphere with the
/// method's single-ray test, coloured by the row's tracer, averaged in linear light.
///
/// The sphere test is the method's single-ray test (`TestStrategy::ray`, what secondary
/// rays use: the forward-differenced test's row state belongs to the centre rays),
/// tested against every sphere and plane (a row's spans hold for its centre line only).
///
/// **Averaging in linear light.** Every ray's colour is the 8-bit colour the row
/// tracer rounds once; it is decoded to linear light by a table (IEC 61966-2-1, built
/// by `build.rs`: `round(65535·L)`), the `n²` values are summed in integers, and the
/// sum is encoded by comparing it with the 255 linear thresholds where the encoded
/// value is exactly `k + ½` levels (a bucket table picks the one threshold to compare
/// with, [`encode`]): rounding to nearest, once, with no `powf` in the pixel loop.
/// Decoding rounded samples instead of averaging the unrounded ones moves the result by
/// at most one level (the unit test `rounded_samples_within_one_level` measures it over
/// random sample sets: see its output).
#[inline(never)]
pub(super) fn average<'s, T: TestStrategy + 's, Q: SqrtFn, Sh: Shader + 's, X: RowTracer<'s, T, Sh>>(
    spheres: impl Iterator<Item = (usize, &'s FrameSphere<T, Sh>)> + Clone,
    tracer: &mut X,
    st: &SubSteps,
    i: u32,
    j: u32,
) -> Rgb888 {
    let mut sum = [0u32; 3];
    for oy in st.offsets.iter().take(st.n) {
        let base = st.first + st.dv * (j as f32 + oy);
        for ox in st.offsets.iter().take(st.n) {
            let d = base + st.du * (i as f32 + ox);
            let a = d.dot(d);
            let mut best = None;
            let mut t_max = f32::INFINITY;
            for (index, s) in spheres.clone() {
                if let Some(t) = T::ray::<Q>(&s.geom, d, a, t_max) {
                    t_max = t;
                    best = Some((index, t, s));
                }
            }
            let (_, c) = tracer.sub_sample(best, d);
            for (acc, v) in sum.iter_mut().zip([c.r(), c.g(), c.b()]) {
                *acc += decode(v);
            }
        }
    }
    let count = (st.n * st.n) as u32;
    Rgb888::new(
        encode(sum[0], count),
        encode(sum[1], count),
        encode(sum[2], count),
    )
}

/// An 8-bit sRGB level in linear light, `round(65535·L)`.
#[inline(always)]
fn decode(v: u8) -> u32 {
    u32::from(SRGB_TO_LINEAR.get(usize::from(v)).copied().unwrap_or(0))
}

/// The level nearest (in the encoded scale) to the mean of `count` (1…16) decoded
/// values summing to `sum`: the number of thresholds at or below the mean.
///
/// Exact, no search: an integer threshold `t` is at or below `16·sum/count` exactly
/// when it is at or below its floor `x`; a table gives the thresholds below `x`'s
/// bucket (2⁸ wide under 2¹⁶, 2¹⁰ above: never more than one threshold per bucket,
/// `encode_steps_at_most_once_per_bucket`), so one comparison finishes it. Equal to
/// the binary search over the thresholds for every `x` (test
/// `encode_equals_the_search_for_every_mean`).
#[inline(always)]
fn encode(sum: u32, count: u32) -> u8 {
    let x = sum * 16 / count.max(1);
    let start = if x < 1 << 16 {
        LEVELS_BELOW_LOW.get((x >> 8) as usize)
    } else {
        LEVELS_BELOW_HIGH.get((x >> 10) as usize)
    };
    let k = start.copied().unwrap_or(255);
    let next = LINEAR_THRESHOLDS.get(usize::from(k)).copied().unwrap_or(u32::MAX);
    k + u8::from(next <= x)
}

#[cfg(test)]
mod tests;
