//! Where finished rows go: an embedded-graphics `DrawTarget` (one `fill_contiguous`
//! per row, for [`Render::draw`](embedded_graphics::Drawable::draw)) or a callback per
//! traced pixel ([`Render::trace`](crate::Render::trace)).

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::render::Sample;

/// A consumer of rows: the pixels of `area` (one row, left to right), pulled from the
/// scanline loop's iterator.
pub(crate) trait RowSink {
    type Error;
    fn row<I: Iterator<Item = Sample>>(&mut self, area: Rectangle, pixels: I) -> Result<(), Self::Error>;
}

/// Rows into a `DrawTarget`, colours converted to its colour type.
pub(crate) struct DrawSink<'t, D, C> {
    pub target: &'t mut D,
    pub color: PhantomData<C>,
}

impl<D: DrawTarget<Color = C>, C: PixelColor + From<Rgb888>> RowSink for DrawSink<'_, D, C> {
    type Error = D::Error;
    #[inline(always)]
    fn row<I: Iterator<Item = Sample>>(&mut self, area: Rectangle, pixels: I) -> Result<(), D::Error> {
        self.target.fill_contiguous(&area, colors(pixels))
    }
}

/// The samples' colours converted to `C` through a one-entry cache: runs of background
/// (and of a flat shade) cost a 3-byte compare instead of a conversion per pixel.
#[inline(always)]
fn colors<C: PixelColor + From<Rgb888>>(pixels: impl Iterator<Item = Sample>) -> impl Iterator<Item = C> {
    let mut last: Option<(Rgb888, C)> = None;
    pixels.map(move |s| match last {
        Some((rgb, c)) if rgb == s.color => c,
        _ => {
            let c = C::from(s.color);
            last = Some((s.color, c));
            c
        }
    })
}

/// Rows `j0..` of the image into a caller's row-major buffer of `width`-pixel rows.
pub(crate) struct BandSink<'b, C> {
    pub buf: &'b mut [C],
    pub width: u32,
    pub j0: u32,
}

impl<C: PixelColor + From<Rgb888>> RowSink for BandSink<'_, C> {
    type Error = core::convert::Infallible;
    #[inline(always)]
    fn row<I: Iterator<Item = Sample>>(&mut self, area: Rectangle, pixels: I) -> Result<(), Self::Error> {
        // The area lies in the band (the render was clipped to it), so the offsets are
        // in the buffer, whose size the caller checked; `get_mut` keeps that unpanicking.
        let start = (area.top_left.y as u32).wrapping_sub(self.j0) as usize * self.width as usize
            + area.top_left.x as usize;
        if let Some(row) = self.buf.get_mut(start..start + area.size.width as usize) {
            for (px, c) in row.iter_mut().zip(colors(pixels)) {
                *px = c;
            }
        }
        Ok(())
    }
}

/// Every traced pixel handed to a callback.
pub(crate) struct TraceSink<'f, F>(pub &'f mut F);

impl<F: FnMut(Sample)> RowSink for TraceSink<'_, F> {
    type Error = core::convert::Infallible;
    fn row<I: Iterator<Item = Sample>>(&mut self, _area: Rectangle, pixels: I) -> Result<(), Self::Error> {
        pixels.for_each(&mut *self.0);
        Ok(())
    }
}
