//! Where finished rows go: an embedded-graphics `DrawTarget` (one `fill_contiguous`
//! per row, for [`Render::draw`](embedded_graphics::Drawable::draw)) or a callback per
//! traced pixel ([`Render::trace`](crate::Render::trace)).

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::error::FrameError;
use crate::trace::options::Sample;
use crate::trace::scanline::{PixelRow, RowSink};

/// Rows into a `DrawTarget`, colours converted to its colour type.
pub(crate) struct DrawSink<'t, D, C> {
    pub target: &'t mut D,
    pub color: PhantomData<C>,
}

impl<D: DrawTarget<Color = C>, C: PixelColor + From<Rgb888>> RowSink for DrawSink<'_, D, C> {
    type Error = D::Error;
    #[inline(always)]
    fn row<R: PixelRow>(&mut self, area: Rectangle, row: R) -> Result<(), D::Error> {
        // One iterator for the target (`ColorRuns::colors`). The background is
        // converted once per row; a traced colour is converted as it comes (a one-entry
        // cache's compare cost more than converting to `Rgb888` or an RGB type: `bash
        // .ci/cycles --quick`).
        let runs = row.color_runs().colors::<C>();
        self.target.fill_contiguous(&area, runs)
    }
}

/// Rows `j0..` of the image into a caller's row-major buffer of `width`-pixel rows.
pub(crate) struct BandSink<'b, C> {
    pub buf: &'b mut [C],
    pub width: u32,
    pub j0: u32,
    /// Why the frame was not drawn, if it was not.
    pub refused: Option<FrameError>,
}

impl<C: PixelColor + From<Rgb888>> RowSink for BandSink<'_, C> {
    type Error = core::convert::Infallible;
    #[inline(always)]
    fn row<R: PixelRow>(&mut self, area: Rectangle, row: R) -> Result<(), Self::Error> {
        // The area lies in the band (the render was clipped to it), so the offsets are
        // in the buffer, whose size the caller checked; `get_mut` keeps that unpanicking.
        let start = (area.top_left.y as u32).wrapping_sub(self.j0) as usize * self.width as usize
            + area.top_left.x as usize;
        let Some(out) = self.buf.get_mut(start..start + area.size.width as usize) else {
            return Ok(());
        };
        let runs = row.color_runs();
        let background = C::from(runs.background);
        // The runs' lengths add up to the row's width; `split_at_mut_checked` keeps a
        // mistake there unpanicking.
        let Some((head, rest)) = out.split_at_mut_checked(runs.before as usize) else {
            return Ok(());
        };
        let Some((middle, tail)) = rest.split_at_mut_checked(runs.traced_len as usize) else {
            return Ok(());
        };
        head.fill(background);
        for (px, c) in middle.iter_mut().zip(runs.traced) {
            *px = C::from(c);
        }
        tail.fill(background);
        Ok(())
    }

    fn refused(&mut self, why: FrameError) -> Result<(), Self::Error> {
        self.refused = Some(why);
        Ok(())
    }
}

/// Every traced pixel handed to a callback.
pub(crate) struct TraceSink<'f, F>(pub &'f mut F);

impl<F: FnMut(Sample)> RowSink for TraceSink<'_, F> {
    type Error = core::convert::Infallible;
    fn row<R: PixelRow>(&mut self, _area: Rectangle, row: R) -> Result<(), Self::Error> {
        row.samples().for_each(&mut *self.0);
        Ok(())
    }
}
