//! The scanline loop: per row, cut every sphere's silhouette with the scanline (the
//! row's active spheres and their spans), then trace the row's pixels — form the ray,
//! find the closest hit among the active spheres, shade — as the sink pulls them.
//!
//! This is the only per-pixel code of the renderer. It adds, compares and calls the
//! strategy types; everything it reads was computed once per frame (`frame.rs`) or
//! once per row (here, before the pixel iterator starts).

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::frame::{Frame, FrameSphere};
use crate::intersect::{Scale, TestStrategy};
use crate::math::SqrtFn;
use crate::render::Sample;
use crate::scene::Hit;
use crate::shade::Shader;
use crate::sink::RowSink;
use crate::stepping::{RowStep, Stepper};
use crate::vec3::Vec3;

/// Draws the frame's visible rows into the sink, one row (one iterator) at a time.
pub(crate) fn draw_rows<const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader>(
    frame: &Frame<'_, T, Sh>,
    sink: &mut K,
) -> Result<(), K::Error> {
    let mut stepper = S::new(frame.camera);
    let width = frame.i1 - frame.i0;
    let mut active: Vec<Active<'_, T, Sh>, N> = Vec::new();
    for j in frame.j0..frame.j1 {
        let row_step = stepper.start_row(j, frame.i0);
        let (lo_all, hi_all) = activate(frame, &mut stepper, j, &mut active);
        // Visible rows and columns fit in the target's i32 coordinates.
        let area = Rectangle::new(
            Point::new(
                frame.offset.x.wrapping_add(frame.i0 as i32),
                frame.offset.y.wrapping_add(j as i32),
            ),
            Size::new(width, 1),
        );
        let row = RowPixels::<S, T, Q, Sh> {
            stepper: row_step,
            active: &mut active,
            lo_all,
            hi_all,
            w: frame.camera.w(),
            background: frame.background,
            scale: frame.scale,
            i: frame.i0,
            end: frame.i1,
            j,
            sqrt: PhantomData,
        };
        sink.row(area, row)?;
    }
    Ok(())
}

/// Per row: the spheres whose span meets row `j` (into `active`, in scene order), each
/// with its test's row state, and the union `[lo_all, hi_all)` of their visible spans.
///
/// Out of line: its locals are dead before the row's pixels are traced, so they do not
/// add to the pixel loop's stack.
#[inline(never)]
fn activate<'s, const N: usize, S: Stepper, T: TestStrategy, Sh: Shader>(
    frame: &Frame<'s, T, Sh>,
    stepper: &mut S,
    j: u32,
    active: &mut Vec<Active<'s, T, Sh>, N>,
) -> (u32, u32) {
    active.clear();
    let image_width = frame.camera.size().width;
    let (mut lo_all, mut hi_all) = (frame.i1, frame.i0);
    for (index, fs) in frame.spheres.iter().enumerate() {
        // The span in the whole image (where a test's row state starts, whatever the
        // clip), then its visible part.
        let Some((span_lo, span_hi)) = fs.silhouette.row_span(j, 0, image_width) else {
            continue;
        };
        let (lo, hi) = (span_lo.max(frame.i0), span_hi.min(frame.i1));
        if lo >= hi {
            continue;
        }
        lo_all = lo_all.min(lo);
        hi_all = hi_all.max(hi);
        let state = T::row_start(&fs.geom, &fs.test, span_lo, lo, |i| {
            stepper.start_row(j, i).next_direction()
        });
        // Cannot fail: at most N spheres.
        let _ = active.push(Active {
            index,
            lo,
            len: hi - lo,
            sphere: fs,
            state,
        });
    }
    (lo_all, hi_all)
}

/// One row as a sink takes it: every pixel as a [`Sample`] (direction, hit, colour),
/// or only the colours as runs.
pub(crate) trait PixelRow {
    /// The row's pixels, left to right.
    fn samples(self) -> impl Iterator<Item = Sample>;
    /// The row's colours: background up to the union of the active spans, the traced
    /// colours inside it, background after it. Outside the union no sphere can be hit,
    /// so those pixels are not traced at all (the stepping still advances over them, so
    /// a traced pixel's direction is the one `samples` forms).
    fn color_runs(self) -> ColorRuns<impl Iterator<Item = Rgb888>>;
}

/// A row's colours as three runs (see [`PixelRow::color_runs`]).
pub(crate) struct ColorRuns<I> {
    pub background: Rgb888,
    /// Background pixels before `traced`…
    pub before: u32,
    /// …the traced colours (exactly `traced_len` of them)…
    pub traced: I,
    pub traced_len: u32,
    /// …and background pixels after them.
    pub after: u32,
}

/// A sphere whose span meets the current row.
struct Active<'s, T: TestStrategy, Sh: Shader> {
    /// Index in the scene.
    index: usize,
    /// Columns `[lo, lo + len)` whose rays can hit it (as a length: one unsigned
    /// compare per pixel tests both ends).
    lo: u32,
    len: u32,
    sphere: &'s FrameSphere<T, Sh>,
    /// The test's per-row state (forward differences).
    state: T::State,
}

/// The pixels of one scanline, traced as the sink pulls them.
struct RowPixels<'r, 's, S: Stepper, T: TestStrategy, Q, Sh: Shader> {
    stepper: S::Row,
    active: &'r mut [Active<'s, T, Sh>],
    /// Union of the active spans: outside it a pixel is background without a test.
    lo_all: u32,
    hi_all: u32,
    w: Vec3,
    background: Rgb888,
    /// The frame's length scale: a hit's `t` is reported in the scene's units.
    scale: Scale,
    i: u32,
    end: u32,
    j: u32,
    sqrt: PhantomData<Q>,
}

impl<S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader> PixelRow for RowPixels<'_, '_, S, T, Q, Sh> {
    #[inline(always)]
    fn samples(self) -> impl Iterator<Item = Sample> {
        self
    }

    #[inline(always)]
    fn color_runs(mut self) -> ColorRuns<impl Iterator<Item = Rgb888>> {
        let (lo, hi) = if self.lo_all < self.hi_all {
            (self.lo_all, self.hi_all)
        } else {
            // No active span: the whole row is background.
            (self.end, self.end)
        };
        let before = lo - self.i;
        // The stepping over the skipped columns (the direct stepping's additions are
        // dead and fold away; the incremental ones are needed for the rounding).
        for _ in 0..before {
            self.stepper.next_direction();
        }
        let background = self.background;
        let after = self.end - hi;
        self.i = lo;
        self.end = hi;
        ColorRuns {
            background,
            before,
            traced_len: hi - lo,
            traced: RowColors(self),
            after,
        }
    }
}

/// The colours of a row's traced run: as [`RowPixels`]' samples, without a `Sample`'s
/// direction and hit.
struct RowColors<'r, 's, S: Stepper, T: TestStrategy, Q, Sh: Shader>(RowPixels<'r, 's, S, T, Q, Sh>);

impl<S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader> Iterator for RowColors<'_, '_, S, T, Q, Sh> {
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        let row = &mut self.0;
        let i = row.i;
        if i >= row.end {
            return None;
        }
        row.i += 1;
        let d = row.stepper.next_direction();
        Some(match row.closest(i, d) {
            Some((_, t, s)) => Sh::shade(&s.shade, row.w, d, t),
            None => row.background,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.0.end - self.0.i) as usize;
        (n, Some(n))
    }
}

impl<'s, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader> RowPixels<'_, 's, S, T, Q, Sh> {
    /// The closest hit of the ray `d` of column `i` (inside the union of the active
    /// spans): index, `t` and sphere.
    #[inline(always)]
    fn closest(&mut self, i: u32, d: Vec3) -> Option<(usize, f32, &'s FrameSphere<T, Sh>)> {
        let mut best = None;
        let a = d.dot(d);
        // Closest hit over the spheres whose span holds this column, in scene order;
        // each test gets the nearest t so far as its t_max.
        let mut t_max = f32::INFINITY;
        for act in self.active.iter_mut() {
            if i.wrapping_sub(act.lo) < act.len {
                let s = act.sphere;
                if let Some(t) = T::hit::<Q>(&mut act.state, &s.geom, &s.test, d, a, i, t_max) {
                    t_max = t;
                    best = Some((act.index, t, s));
                }
            }
        }
        best
    }
}

impl<S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader> Iterator for RowPixels<'_, '_, S, T, Q, Sh> {
    type Item = Sample;

    #[inline(always)]
    fn next(&mut self) -> Option<Sample> {
        let i = self.i;
        if i >= self.end {
            return None;
        }
        let pixel = Point::new(i as i32, self.j as i32);
        self.i += 1;
        // Form the ray from the eye through the pixel centre.
        let d = self.stepper.next_direction();
        let best = if i >= self.lo_all && i < self.hi_all {
            self.closest(i, d)
        } else {
            None
        };
        // Shade the closest hit; background where there is none.
        let (hit, color) = match best {
            Some((index, t, s)) => (
                Some(Hit {
                    index,
                    t: self.scale.unscale_t(t),
                }),
                Sh::shade(&s.shade, self.w, d, t),
            ),
            None => (None, self.background),
        };
        Some(Sample {
            pixel,
            direction: d,
            hit,
            color,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.i) as usize;
        (n, Some(n))
    }
}
