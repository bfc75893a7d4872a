//! The scanline loop: per row, cut every sphere's silhouette with the scanline, then
//! trace the row's pixels as the sink pulls them.
//!
//! The cuts give the row's active spheres and their spans; a pixel forms its ray, finds
//! the closest hit among the active spheres and shades it. What happens after the
//! closest sphere hit is a [`RowTracer`]: [`Lab1Row`] shades it with the lecture notes'
//! Lab #1 (the loop of a `Scene<N>`); the scene-features path (`lit/row.rs`) adds
//! planes, lights, shadow rays and mirrors.
//!
//! This is the only per-pixel code of the renderer. It adds, compares and calls the
//! strategy types; everything it reads was computed once per frame (`frame.rs`) or
//! once per row (here, before the pixel iterator starts).

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::error::FrameError;
use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::{Scale, TestStrategy};
use crate::method::stepping::{RowStep, Stepper};
use crate::scene::Hit;
use crate::trace::frame::{Frame, FrameSphere};
use crate::trace::options::Sample;
use crate::trace::shade::{Lab1, Shader};

/// What a row does with each pixel's closest sphere hit: the shading model, and any
/// primitive beyond spheres.
///
/// Built once per row.
pub(crate) trait RowTracer<'s, T: TestStrategy, Sh: Shader> {
    /// The colour of rays that hit nothing (the row's background runs).
    fn background(&self) -> Rgb888;
    /// Column `i`'s ray `d` (in the union of the spans), given its closest sphere hit:
    /// the object hit with its `t`, and the pixel's colour.
    ///
    /// The sphere hit is `(index, t, sphere)`, `t` in the frame's scaled units; the
    /// object numbers are the spheres' first, then whatever the tracer adds.
    fn pixel(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, Sh>)>,
        i: u32,
        d: Vec3,
    ) -> (Option<(usize, f32)>, Rgb888);
    /// [`Self::pixel`]'s colour alone: what a row's colour runs draw
    /// ([`PixelRow::color_runs`], the path of a `DrawTarget`).
    ///
    /// A tracer may give this path a copy of its shading inlined into the row loop.
    #[inline(always)]
    fn color(&mut self, sphere_hit: Option<(usize, f32, &'s FrameSphere<T, Sh>)>, i: u32, d: Vec3) -> Rgb888 {
        self.pixel(sphere_hit, i, d).1
    }
    /// As [`Self::pixel`]'s colour, with the ray's identity for adaptive sampling
    /// (`sampling/`).
    ///
    /// The identity is 0 where the ray hits nothing, otherwise a hash of what decides
    /// the colour discontinuously (the object, and for the features path the checker
    /// cell, the lights visible and what each reflected ray hit).
    fn identified(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, Sh>)>,
        i: u32,
        d: Vec3,
    ) -> (u32, Rgb888);
    /// A sub-pixel ray `d` (anywhere in the row's footprint, so no per-row span may
    /// cull it) given its closest sphere hit over every sphere: identity and colour.
    fn sub_sample(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, Sh>)>,
        d: Vec3,
    ) -> (u32, Rgb888);
}

/// Lab #1 on spheres: the tracer of a scene without lights, planes or mirrors.
pub(crate) struct Lab1Row {
    pub w: Vec3,
    pub background: Rgb888,
}

impl<'s, T: TestStrategy> RowTracer<'s, T, Lab1> for Lab1Row {
    #[inline(always)]
    fn background(&self) -> Rgb888 {
        self.background
    }

    #[inline(always)]
    fn pixel(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, Lab1>)>,
        _i: u32,
        d: Vec3,
    ) -> (Option<(usize, f32)>, Rgb888) {
        match sphere_hit {
            Some((index, t, s)) => (Some((index, t)), Lab1::shade(&s.shade, self.w, d, t)),
            None => (None, self.background),
        }
    }

    #[inline(always)]
    fn identified(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, Lab1>)>,
        i: u32,
        d: Vec3,
    ) -> (u32, Rgb888) {
        let (hit, color) = <Self as RowTracer<'s, T, Lab1>>::pixel(self, sphere_hit, i, d);
        (hit.map_or(0, |(index, _)| index as u32 + 1), color)
    }

    #[inline(always)]
    fn sub_sample(
        &mut self,
        sphere_hit: Option<(usize, f32, &'s FrameSphere<T, Lab1>)>,
        d: Vec3,
    ) -> (u32, Rgb888) {
        <Self as RowTracer<'s, T, Lab1>>::identified(self, sphere_hit, 0, d)
    }
}

/// Draws the frame's visible rows into the sink, one row (one iterator) at a time.
///
/// `tracer(j, &mut lo, &mut hi)` builds row `j`'s tracer and may widen the union
/// `[lo, hi)` of the spheres' visible spans by its own primitives' spans.
pub(crate) fn draw_rows<
    's,
    const N: usize,
    K: RowSink,
    S: Stepper,
    T: TestStrategy,
    Q: SqrtFn,
    Sh: Shader,
    X,
>(
    frame: &Frame<'s, T, Sh>,
    sink: &mut K,
    mut tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
) -> Result<(), K::Error>
where
    X: RowTracer<'s, T, Sh>,
{
    let mut stepper = S::new(frame.camera);
    let width = frame.i1 - frame.i0;
    let mut active: Vec<Active<'s, T, Sh>, N> = Vec::new();
    for j in frame.j0..frame.j1 {
        let row_step = stepper.start_row(j, frame.i0);
        let (mut lo_all, mut hi_all) = activate(frame, &mut stepper, j, &mut active);
        let tracer = tracer(j, &mut lo_all, &mut hi_all);
        // Visible rows and columns fit in the target's i32 coordinates.
        let area = Rectangle::new(
            Point::new(
                frame.offset.x.wrapping_add(frame.i0 as i32),
                frame.offset.y.wrapping_add(j as i32),
            ),
            Size::new(width, 1),
        );
        let row = RowPixels::<S, T, Q, Sh, X> {
            stepper: row_step,
            active: &mut active,
            lo_all,
            hi_all,
            tracer,
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
pub(crate) fn activate<'s, const N: usize, S: Stepper, T: TestStrategy, Sh: Shader>(
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

/// A consumer of rows: the pixels of `area` (one row, left to right), pulled from the
/// scanline loop's row as samples or as colour runs.
pub(crate) trait RowSink {
    type Error;
    fn row<R: PixelRow>(&mut self, area: Rectangle, row: R) -> Result<(), Self::Error>;
    /// The frame cannot be drawn exactly: no row comes.
    ///
    /// A sink that can say so keeps the reason; a `DrawTarget` keeps what it shows.
    #[inline(always)]
    fn refused(&mut self, _why: FrameError) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// One row as a sink takes it: every pixel as a [`Sample`] (direction, hit, colour),
/// or only the colours as runs.
pub(crate) trait PixelRow {
    /// The row's pixels, left to right.
    fn samples(self) -> impl Iterator<Item = Sample>;
    /// The row's colours: background up to the union of the active spans, the traced
    /// colours inside it, background after it.
    ///
    /// Outside the union no sphere can be hit,
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

impl<I: Iterator<Item = Rgb888>> ColorRuns<I> {
    /// The row's colours in a target's colour type, as one iterator: the background
    /// converted once, each traced colour as it comes.
    ///
    /// Its `next` is always inlined and converts the colour itself, so a target whose
    /// `fill_contiguous` pulls colours one at a time (a `for` loop over a zip) traces
    /// the row in its own loop. `core`'s `Chain` and `Map` leave inlining their `next`
    /// to the optimiser, which on the host can make it, with the whole pixel trace
    /// inside, a call per pixel (`docs/firmware.md`, "On the host"). Its `fold` (what
    /// `for_each` calls) folds each run as a loop of its own.
    #[inline(always)]
    pub fn colors<C: From<Rgb888> + Copy>(self) -> TargetColors<I, C> {
        let background = C::from(self.background);
        TargetColors {
            head: core::iter::repeat_n(background, self.before as usize),
            traced: self.traced,
            tail: core::iter::repeat_n(background, self.after as usize),
        }
    }
}

/// A row's colours in a target's colour type, as one iterator ([`ColorRuns::colors`]).
pub(crate) struct TargetColors<I, C> {
    head: core::iter::RepeatN<C>,
    traced: I,
    tail: core::iter::RepeatN<C>,
}

impl<I: Iterator<Item = Rgb888>, C: From<Rgb888> + Copy> Iterator for TargetColors<I, C> {
    type Item = C;

    #[inline(always)]
    fn next(&mut self) -> Option<C> {
        if let Some(c) = self.head.next() {
            return Some(c);
        }
        // Past its end the traced run stays empty: every row's traced colours check
        // their column against the row's end.
        if let Some(c) = self.traced.next() {
            return Some(C::from(c));
        }
        self.tail.next()
    }

    #[inline(always)]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let (lo, hi) = self.traced.size_hint();
        let edges = self.head.len() + self.tail.len();
        (lo.saturating_add(edges), hi.and_then(|h| h.checked_add(edges)))
    }

    /// Each run folded as a loop of its own, so that a background run costs the
    /// target's store alone.
    #[inline(always)]
    fn fold<B, F: FnMut(B, C) -> B>(self, init: B, mut f: F) -> B {
        let acc = self.head.fold(init, &mut f);
        let acc = self.traced.map(C::from).fold(acc, &mut f);
        self.tail.fold(acc, f)
    }
}

/// A sphere whose span meets the current row.
pub(crate) struct Active<'s, T: TestStrategy, Sh: Shader> {
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
pub(crate) struct RowPixels<'r, 's, S: Stepper, T: TestStrategy, Q, Sh: Shader, X> {
    stepper: S::Row,
    active: &'r mut [Active<'s, T, Sh>],
    /// Union of the active spans: outside it a pixel is background without a test.
    lo_all: u32,
    hi_all: u32,
    /// Shading (and primitives beyond spheres).
    tracer: X,
    /// The frame's length scale: a hit's `t` is reported in the scene's units.
    scale: Scale,
    i: u32,
    end: u32,
    j: u32,
    sqrt: PhantomData<Q>,
}

impl<'s, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> PixelRow
    for RowPixels<'_, 's, S, T, Q, Sh, X>
{
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
        let background = self.tracer.background();
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
struct RowColors<'r, 's, S: Stepper, T: TestStrategy, Q, Sh: Shader, X>(RowPixels<'r, 's, S, T, Q, Sh, X>);

impl<'s, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> Iterator
    for RowColors<'_, 's, S, T, Q, Sh, X>
{
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
        let best = row.closest(i, d);
        Some(row.tracer.color(best, i, d))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.0.end - self.0.i) as usize;
        (n, Some(n))
    }
}

impl<'r, 's, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>>
    RowPixels<'r, 's, S, T, Q, Sh, X>
{
    /// Row `j` of the frame's visible columns, as [`draw_rows`] builds it, for a row
    /// loop of its own (adaptive sampling's centre rays).
    pub(crate) fn new(
        frame: &Frame<'s, T, Sh>,
        stepper: S::Row,
        active: &'r mut [Active<'s, T, Sh>],
        (lo_all, hi_all): (u32, u32),
        tracer: X,
        j: u32,
    ) -> Self {
        Self {
            stepper,
            active,
            lo_all,
            hi_all,
            tracer,
            scale: frame.scale,
            i: frame.i0,
            end: frame.i1,
            j,
            sqrt: PhantomData,
        }
    }

    /// The next column's centre ray, exactly as [`Iterator::next`] traces it: its
    /// identity ([`RowTracer::identified`]) and colour.
    ///
    /// Past the row's end: nothing hit.
    #[inline(always)]
    pub(crate) fn next_identified(&mut self) -> (u32, Rgb888) {
        let i = self.i;
        if i >= self.end {
            return (0, self.tracer.background());
        }
        self.i += 1;
        let d = self.stepper.next_direction();
        if i >= self.lo_all && i < self.hi_all {
            let best = self.closest(i, d);
            self.tracer.identified(best, i, d)
        } else {
            (0, self.tracer.background())
        }
    }

    /// The next column's centre colour, exactly as [`PixelRow::color_runs`] traces it
    /// (background outside the union of the spans).
    ///
    /// Past the row's end: background.
    #[inline(always)]
    pub(crate) fn next_color(&mut self) -> Rgb888 {
        let i = self.i;
        if i >= self.end {
            return self.tracer.background();
        }
        self.i += 1;
        let d = self.stepper.next_direction();
        if i >= self.lo_all && i < self.hi_all {
            let best = self.closest(i, d);
            self.tracer.pixel(best, i, d).1
        } else {
            self.tracer.background()
        }
    }

    /// Steps over `n` background columns without tracing them (as
    /// [`PixelRow::color_runs`] does before the union of the spans).
    #[inline(always)]
    pub(crate) fn skip_columns(&mut self, n: u32) {
        for _ in 0..n {
            self.stepper.next_direction();
        }
        self.i += n;
    }

    /// The union `[lo, hi)` of the row's active spans, `None` if no sphere is active.
    pub(crate) fn spans(&self) -> Option<(u32, u32)> {
        (self.lo_all < self.hi_all).then_some((self.lo_all, self.hi_all))
    }

    /// The colour of rays that hit nothing.
    pub(crate) fn background(&self) -> Rgb888 {
        self.tracer.background()
    }

    /// The row's tracer (for sub-pixel rays).
    pub(crate) fn tracer_mut(&mut self) -> &mut X {
        &mut self.tracer
    }
}

impl<'s, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X> RowPixels<'_, 's, S, T, Q, Sh, X> {
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

impl<'s, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> Iterator
    for RowPixels<'_, 's, S, T, Q, Sh, X>
{
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
        let (hit, color) = self.tracer.pixel(best, i, d);
        let hit = hit.map(|(index, t)| Hit {
            index,
            t: self.scale.unscale_t(t),
        });
        Some(Sample {
            pixel,
            direction: d,
            hit,
            color,
            rays: 1,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.i) as usize;
        (n, Some(n))
    }
}

#[cfg(test)]
mod tests {
    use embedded_graphics::pixelcolor::{BinaryColor, Rgb565};

    use super::*;

    fn runs(before: u32, traced: &[Rgb888], after: u32) -> ColorRuns<impl Iterator<Item = Rgb888> + '_> {
        ColorRuns {
            background: Rgb888::new(10, 20, 30),
            before,
            traced: traced.iter().copied(),
            traced_len: traced.len() as u32,
            after,
        }
    }

    /// What a target must receive: the background converted, `before` times, the
    /// traced colours converted, the background `after` times.
    fn expected<C: From<Rgb888>>(before: u32, traced: &[Rgb888], after: u32) -> std::vec::Vec<C> {
        let bg = || C::from(Rgb888::new(10, 20, 30));
        let mut v: std::vec::Vec<C> = (0..before).map(|_| bg()).collect();
        v.extend(traced.iter().map(|&c| C::from(c)));
        v.extend((0..after).map(|_| bg()));
        v
    }

    #[test]
    fn target_colors_pulled_or_folded_are_the_three_runs() {
        let traced = [
            Rgb888::new(255, 0, 0),
            Rgb888::new(0, 255, 0),
            Rgb888::new(0, 0, 255),
            Rgb888::new(200, 200, 200),
        ];
        for (before, n, after) in [(0, 0, 0), (3, 0, 0), (0, 4, 0), (0, 0, 2), (2, 4, 5), (1, 1, 1)] {
            let traced = &traced[..n];
            let want = expected::<Rgb565>(before, traced, after);
            // Pulled one at a time, as a `for` loop over a zip does; `None` after the
            // last, every time.
            let mut it = runs(before, traced, after).colors::<Rgb565>();
            assert_eq!(it.size_hint(), (want.len(), Some(want.len())));
            let mut pulled = std::vec::Vec::new();
            for c in it.by_ref() {
                pulled.push(c);
            }
            assert_eq!(it.next(), None);
            assert_eq!(pulled, want, "next: {before} + {n} + {after}");
            // Folded, as `for_each` does.
            let mut folded = std::vec::Vec::new();
            runs(before, traced, after)
                .colors::<Rgb565>()
                .for_each(|c| folded.push(c));
            assert_eq!(folded, want, "fold: {before} + {n} + {after}");
            // Pulled part way, then folded: the rest, in order.
            let mut it = runs(before, traced, after).colors::<BinaryColor>();
            let k = want.len() / 2;
            let mut mixed: std::vec::Vec<BinaryColor> = it.by_ref().take(k).collect();
            it.for_each(|c| mixed.push(c));
            assert_eq!(mixed, expected::<BinaryColor>(before, traced, after));
        }
    }
}
