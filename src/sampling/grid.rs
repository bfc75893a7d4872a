//! [`Sampling::Grid`](super::Sampling::Grid)`(n)`: every pixel's `n × n` rays averaged,
//! in rows the shared-sample `Adaptive` draws its pixels with too.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use super::average::{average, SubSteps};
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::trace::frame::{Frame, FrameSphere};
use crate::trace::options::Sample;
use crate::trace::rows::Rows;
use crate::trace::scanline::{ColorRuns, PixelRow, RowSink, RowTracer};
use crate::trace::shade::Shader;

/// [`Sampling::Grid`](super::Sampling::Grid)`(n)`: every pixel averaged.
#[derive(Clone, Copy)]
pub(crate) struct GridRows(pub u32);

impl Rows for GridRows {
    const CENTER: bool = false;
    #[inline(always)]
    fn clip(&self, clip: Rectangle) -> Rectangle {
        clip
    }

    // Out of line: the one-ray path's callers do not carry its frame (the adaptive
    // rows' buffers) on their stack.
    #[inline(never)]
    fn draw_rows<'s, const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X>(
        self,
        frame: &Frame<'s, T, Sh>,
        sink: &mut K,
        mut tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
    ) -> Result<(), K::Error>
    where
        X: RowTracer<'s, T, Sh>,
    {
        let steps = SubSteps::new(frame, self.0);
        for j in frame.j0..frame.j1 {
            let (mut lo, mut hi) = (frame.i1, frame.i0);
            let mut tracer = tracer(j, &mut lo, &mut hi);
            let row = SampledRow::<T, Q, Sh, X> {
                spheres: frame.spheres,
                tracer: &mut tracer,
                steps: &steps,
                stored: None,
                i: frame.i0,
                end: frame.i1,
                j,
                background: frame.background,
                sqrt: core::marker::PhantomData,
            };
            sink.row(row_area(frame, frame.i0, frame.i1, j), row)?;
        }
        Ok(())
    }
}

/// Where row `j`, columns `i0..i1` of the image, go on the target.
pub(super) fn row_area<T: TestStrategy, Sh: Shader>(
    frame: &Frame<'_, T, Sh>,
    i0: u32,
    i1: u32,
    j: u32,
) -> Rectangle {
    // Visible rows and columns fit in the target's i32 coordinates.
    Rectangle::new(
        Point::new(
            frame.offset.x.wrapping_add(i0 as i32),
            frame.offset.y.wrapping_add(j as i32),
        ),
        Size::new(i1 - i0, 1),
    )
}

/// One row of `Grid`/`Adaptive` pixels, computed as the sink pulls them.
///
/// `stored`: adaptive sampling's centre colours and edge bits (indexed from its
/// column); `None`: every pixel is averaged.
pub(super) struct SampledRow<'a, 's, T: TestStrategy, Q, Sh: Shader, X> {
    pub(super) spheres: &'s [FrameSphere<T, Sh>],
    pub(super) tracer: &'a mut X,
    pub(super) steps: &'a SubSteps,
    pub(super) stored: Option<(&'a [Rgb888], &'a [u32], u32)>,
    pub(super) i: u32,
    pub(super) end: u32,
    pub(super) j: u32,
    pub(super) background: Rgb888,
    pub(super) sqrt: core::marker::PhantomData<Q>,
}

impl<'s, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> SampledRow<'_, 's, T, Q, Sh, X> {
    /// Pixel `i`'s colour and the rays averaged into it.
    #[inline(always)]
    fn color(&mut self, i: u32) -> (Rgb888, u32) {
        if let Some((colors, edges, base)) = self.stored {
            let k = (i - base) as usize;
            let edge = edges.get(k / 32).is_some_and(|w| w & (1 << (k % 32)) != 0);
            if !edge {
                return (colors.get(k).copied().unwrap_or(self.background), 1);
            }
        }
        let rays = (self.steps.n * self.steps.n) as u32;
        (
            average::<T, Q, Sh, X>(
                self.spheres.iter().enumerate(),
                self.tracer,
                self.steps,
                i,
                self.j,
            ),
            rays,
        )
    }

    /// The next pixel: column, colour, rays.
    #[inline(always)]
    fn next_pixel(&mut self) -> Option<(u32, Rgb888, u32)> {
        let i = self.i;
        if i >= self.end {
            return None;
        }
        self.i += 1;
        let (c, rays) = self.color(i);
        Some((i, c, rays))
    }
}

impl<'s, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> Iterator
    for SampledRow<'_, 's, T, Q, Sh, X>
{
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        self.next_pixel().map(|(_, c, _)| c)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.i) as usize;
        (n, Some(n))
    }
}

impl<'s, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> PixelRow
    for SampledRow<'_, 's, T, Q, Sh, X>
{
    /// Every pixel as a [`Sample`]: its colour and rays, the centre direction (formed
    /// directly from the camera's steps) and no hit (not kept for the centre rays of
    /// adaptive sampling; several rays have no single one).
    fn samples(mut self) -> impl Iterator<Item = Sample> {
        let (j, steps) = (self.j, self.steps);
        core::iter::from_fn(move || {
            self.next_pixel().map(|(i, color, rays)| Sample {
                pixel: Point::new(i as i32, j as i32),
                direction: steps.center(i, j),
                hit: None,
                color,
                rays,
            })
        })
    }

    fn color_runs(self) -> ColorRuns<impl Iterator<Item = Rgb888>> {
        ColorRuns {
            background: self.background,
            before: 0,
            traced_len: self.end - self.i,
            traced: self,
            after: 0,
        }
    }
}
