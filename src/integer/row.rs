//! The integer kernel's rows: each sphere's forward differences started once per row
//! ([`activate`]) and stepped per pixel ([`IntRow::trace`]), into the same sinks as the
//! `f32` rows.
//!
//! ## The test (exact forward differences)
//!
//! With `b = ℓ·d`, `a = |d|²` and `c = |ℓ|² − ρ²`, the discriminant `D = b² − a·c`
//! (exactly the robust `a·ρ² − |ℓ × d|²`: the identity holds in integers) is along a
//! row a quadratic in `x`: `D = A₂x² + A₁x + A₀` with `A₂ = ℓx² − c`. It is stepped by
//! `D += Δ; Δ += 2·A₂·s²` (`s = 2ᵏ⁺¹`), exactly in `i128`, and `b += ℓx·s` in `i64`:
//! per sphere and pixel five 32-bit add-with-carry chains, no multiply. `D` and `Δ` are
//! evaluated directly at each span's first visible column, as `b² − a·c` and
//! `ℓx·s·(2b + ℓx·s) − c·(2xs + s²)` (so a pixel never depends on the clip). A hit is
//! `D ≥ 0`; the rule admits only spheres wholly in front of the eye, so every hit has
//! `t > 0`.

use core::ops::DerefMut;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::VecView;

use super::frame::{IntFrame, IntSphere};
use super::shade::{nz_q16, shade};
use crate::math::wide::{isqrt, mul_i32_wide, mul_i64_wide, mul_wide, shr_u64_low};
use crate::scene::Hit;
use crate::trace::options::Sample;
use crate::trace::scanline::{ColorRuns, PixelRow, RowSink};

/// A sphere whose span meets the current row, with its forward differences.
pub(crate) struct Active<'s> {
    lo: u32,
    len: u32,
    /// The discriminant at the next column of the span and its first difference.
    disc: i128,
    delta: i128,
    /// `b = ℓ·d` at the next column (`|b| ≤ 2⁵¹`).
    b: i64,
    sphere: &'s IntSphere,
}

/// Draws the frame's visible rows into the sink.
#[inline(never)]
pub(super) fn draw_rows<'s, K: RowSink>(
    frame: &IntFrame<'s>,
    active: &mut VecView<Active<'s>>,
    sink: &mut K,
) -> Result<(), K::Error> {
    let width = frame.i1 - frame.i0;
    for j in frame.j0..frame.j1 {
        let spans = activate(frame, j, active);
        let area = Rectangle::new(
            Point::new(
                frame.offset.x.wrapping_add(frame.i0 as i32),
                frame.offset.y.wrapping_add(j as i32),
            ),
            Size::new(width, 1),
        );
        let mut row = IntRow::new(frame, &mut **active);
        row.begin(j, spans);
        sink.row(area, row)?;
    }
    Ok(())
}

/// Row `j`'s `y` (in the pixel unit `2⁻ᵏ` half-pixels) and `α = y² + F²`
/// (`≤ |d|² ≤ 2⁵²`).
#[inline(always)]
fn row_y(frame: &IntFrame<'_>, j: u32) -> (i32, i64) {
    let h = frame.camera.size().height as i32;
    let y = (h - 1 - 2 * j as i32) << frame.k;
    let f = i64::from(frame.f);
    (y, i64::from(y) * i64::from(y) + f * f)
}

/// Row `j`'s active spheres, each with `D`, `Δ` and `b` evaluated directly at its
/// first visible column (exact), and the union of their spans.
#[inline(never)]
pub(super) fn activate<'s>(frame: &IntFrame<'s>, j: u32, active: &mut VecView<Active<'s>>) -> (u32, u32) {
    let (y, alpha) = row_y(frame, j);
    active.clear();
    let width = frame.camera.size().width;
    let (mut lo_all, mut hi_all) = (frame.i1, frame.i0);
    let s = 2i32 << frame.k;
    for sp in frame.spheres.iter() {
        if j < sp.rows.0 || j >= sp.rows.1 {
            continue;
        }
        let Some((lo, hi)) = sp.cut.row_span(j, width) else {
            continue;
        };
        let (lo, hi) = (lo.max(frame.i0), hi.min(frame.i1));
        if lo >= hi {
            continue;
        }
        lo_all = lo_all.min(lo);
        hi_all = hi_all.max(hi);
        let x = (2 * lo as i32 + 1 - width as i32) << frame.k;
        // b = ℓ·d = ℓx·x + β with β = ℓy·y + ℓz·F (|b|, |β| ≤ 2⁵¹) and a = x² + α.
        let beta = mul_i32_wide(sp.ly, y) + mul_i32_wide(sp.lz, frame.f);
        let b = mul_i32_wide(sp.lx, x) + beta;
        let a = mul_i32_wide(x, x) + alpha;
        // D = b² − a·c, and Δ = D(x + s) − D(x) = ℓx·s·(2b + ℓx·s) − c·(2xs + s²):
        // exact, the same integers as the quadratic in x the row steps.
        let disc = mul_i64_wide(b, b) - mul_i64_wide(a, sp.c);
        let delta = mul_i64_wide(sp.lx_s, 2 * b + sp.lx_s)
            - mul_i64_wide(sp.c, 2 * mul_i32_wide(x, s) + mul_i32_wide(s, s));
        let _ = active.push(Active {
            lo,
            len: hi - lo,
            disc,
            delta,
            b,
            sphere: sp,
        });
    }
    (lo_all, hi_all)
}

/// One row of the integer kernel: the frame, the row's active spheres (`A`: borrowed
/// from the frame's rows, or owned by a strip's pixels) and the row's state.
pub(super) struct IntRow<'s, 'c, A> {
    frame: &'s IntFrame<'c>,
    active: A,
    lo_all: u32,
    hi_all: u32,
    i: u32,
    end: u32,
    j: u32,
    /// The current column's `x` and its step `s`.
    x: i32,
    s: i32,
    /// The row's `α = y² + F²`: `a = |d|² = x² + α` ([`Self::a`]) is formed only at a
    /// hit, not stepped at every column.
    alpha: i64,
}

impl<'s, 'c, A: DerefMut<Target = [Active<'c>]>> IntRow<'s, 'c, A> {
    /// No row yet ([`Self::begin`] starts one).
    #[inline(always)]
    pub(super) fn new(frame: &'s IntFrame<'c>, active: A) -> Self {
        Self {
            frame,
            active,
            lo_all: 0,
            hi_all: 0,
            i: frame.i1,
            end: frame.i1,
            j: 0,
            x: 0,
            s: 2i32 << frame.k,
            alpha: 0,
        }
    }

    /// The frame, and the row's active spheres (for [`activate`]).
    pub(super) fn parts(&mut self) -> (&'s IntFrame<'c>, &mut A) {
        (self.frame, &mut self.active)
    }

    /// Row `j` at the frame's first visible column, its spheres activated
    /// ([`activate`]) with the union of their spans `spans`.
    #[inline(always)]
    pub(super) fn begin(&mut self, j: u32, (lo_all, hi_all): (u32, u32)) {
        let (_, alpha) = row_y(self.frame, j);
        let w = self.frame.camera.size().width as i32;
        let x0 = (2 * self.frame.i0 as i32 + 1 - w) << self.frame.k;
        self.lo_all = lo_all;
        self.hi_all = hi_all;
        self.i = self.frame.i0;
        self.end = self.frame.i1;
        self.j = j;
        self.x = x0;
        self.alpha = alpha;
    }

    /// The background columns before the row's traced ones and after them; the row
    /// then stands at its first traced column and ends after its last.
    #[inline(always)]
    pub(super) fn enter_traced(&mut self) -> (u32, u32) {
        let (lo, hi) = if self.lo_all < self.hi_all {
            (self.lo_all, self.hi_all)
        } else {
            (self.end, self.end)
        };
        let before = lo - self.i;
        let after = self.end - hi;
        self.skip(before);
        self.end = hi;
        (before, after)
    }

    /// The row's next traced colour, or `None` past its last traced column.
    #[inline(always)]
    pub(super) fn next_traced(&mut self) -> Option<Rgb888> {
        let i = self.i;
        if i >= self.end {
            return None;
        }
        let (_, color) = self.trace(i);
        self.step();
        Some(color)
    }

    /// The traced columns left.
    fn traced_left(&self) -> usize {
        (self.end - self.i) as usize
    }

    /// One column to the right.
    #[inline(always)]
    fn step(&mut self) {
        self.i += 1;
        self.x += self.s;
    }

    /// `n` columns to the right (the background before the spans).
    fn skip(&mut self, n: u32) {
        self.i += n;
        self.x += n as i32 * self.s;
    }

    /// `a = |d|² = x² + α` at the current column (`≤ 2⁵²`), exactly.
    #[inline(always)]
    fn a(&self) -> i64 {
        mul_i32_wide(self.x, self.x) + self.alpha
    }

    /// Column `i` (at `self.x`): the closest sphere hit (sphere, `T`) and its colour.
    ///
    /// Advances every active sphere that holds `i` by one column.
    #[inline(always)]
    fn trace(&mut self, i: u32) -> (Option<(&'c IntSphere, i64)>, Rgb888) {
        let mut best: Option<(&'c IntSphere, i64)> = None;
        for act in self.active.iter_mut() {
            if i.wrapping_sub(act.lo) < act.len {
                let sp = act.sphere;
                // The test at this column, then the step to the next (in place: no
                // copy of D and b stays live across the root).
                if act.disc >= 0 {
                    let t = act.b - isqrt(act.disc as u128, u32::from(sp.h)) as i64;
                    if best.is_none_or(|(_, bt)| t < bt) {
                        best = Some((sp, t));
                    }
                }
                act.disc += act.delta;
                act.delta += sp.dd;
                act.b += sp.lx_s;
            }
        }
        let color = match best {
            Some((sp, t)) => {
                let p = self.frame.p;
                // a and T (both > 0) shifted by p: a >> p < 2³¹, T >> p < 2³² (the
                // rule's ranges); the products are below 2⁵⁸, their difference an i64.
                let a = shr_u64_low(self.a() as u64, p);
                let t = shr_u64_low(t as u64, p);
                let num = mul_wide(a, sp.lz as u32) as i64 - mul_wide(t, self.frame.f as u32) as i64;
                shade(sp.rgb, nz_q16(num, mul_wide(a, sp.rho as u32), u32::from(sp.q)))
            }
            None => self.frame.background,
        };
        (best, color)
    }
}

impl<'c, A: DerefMut<Target = [Active<'c>]>> PixelRow for IntRow<'_, 'c, A> {
    fn samples(self) -> impl Iterator<Item = Sample> {
        IntSamples(self)
    }

    #[inline(always)]
    fn color_runs(mut self) -> ColorRuns<impl Iterator<Item = Rgb888>> {
        let (before, after) = self.enter_traced();
        ColorRuns {
            background: self.frame.background,
            before,
            traced_len: self.end - self.i,
            traced: IntColors(self),
            after,
        }
    }
}

/// A row's traced colours.
struct IntColors<'s, 'c, A>(IntRow<'s, 'c, A>);

impl<'c, A: DerefMut<Target = [Active<'c>]>> Iterator for IntColors<'_, 'c, A> {
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        self.0.next_traced()
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.0.traced_left();
        (n, Some(n))
    }
}

/// A row's samples (the trace path, [`Render::trace`](crate::Render::trace)): the
/// colour and hit of the integer kernel, the direction and `t` converted to `f32` for
/// the caller (off the drawing path).
struct IntSamples<'s, 'c, A>(IntRow<'s, 'c, A>);

impl<'c, A: DerefMut<Target = [Active<'c>]>> Iterator for IntSamples<'_, 'c, A> {
    type Item = Sample;

    fn next(&mut self) -> Option<Sample> {
        let row = &mut self.0;
        let i = row.i;
        if i >= row.end {
            return None;
        }
        let (best, color) = if i >= row.lo_all && i < row.hi_all {
            row.trace(i)
        } else {
            (None, row.frame.background)
        };
        let camera = row.frame.camera;
        let direction = camera.direction(i, row.j);
        let hit = best.map(|(sp, t)| {
            // The integer ray's t (λ units, integer d) as the caller's: the hit's
            // distance T/a·|d_int|/λ along the f32 direction.
            let a = row.a() as f64;
            let dist = (t as f64 / libm::sqrt(a) / f64::from(row.frame.lambda)) as f32;
            Hit {
                index: sp.index,
                t: dist / direction.length(),
            }
        });
        row.step();
        Some(Sample {
            pixel: Point::new(i as i32, row.j as i32),
            direction,
            hit,
            color,
            rays: 1,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.0.end - self.0.i) as usize;
        (n, Some(n))
    }
}
