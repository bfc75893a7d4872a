//! A plain slice-backed Rgb565 frame buffer: what a firmware's DMA buffer looks like.
//! Shared by `lab/benches/render.rs` and `lab/examples/speed_vs_accuracy/`, so both time
//! the render into the same target.

use std::convert::Infallible;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

/// The frame buffer: `buf` holds `size.width × size.height` pixels, row-major.
pub struct SliceTarget<'a> {
    /// The pixels.
    pub buf: &'a mut [Rgb565],
    /// The display size.
    pub size: Size,
}

impl OriginDimensions for SliceTarget<'_> {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for SliceTarget<'_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        let (w, h) = (self.size.width as i32, self.size.height as i32);
        for Pixel(p, c) in pixels {
            if (0..w).contains(&p.x) && (0..h).contains(&p.y) {
                if let Some(px) = self.buf.get_mut((p.y * w + p.x) as usize) {
                    *px = c;
                }
            }
        }
        Ok(())
    }

    /// A row of a frame, or a run or strip of an incremental one, arrives as one
    /// `fill_contiguous`, already clipped to the target: copy it straight in, a row at
    /// a time.
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        let stride = self.size.width as usize;
        let (w, h) = (area.size.width as usize, area.size.height as usize);
        let start = (area.top_left.y as usize) * stride + area.top_left.x as usize;
        if h == 1 {
            for (px, c) in self.buf[start..start + w].iter_mut().zip(colors) {
                *px = c;
            }
            return Ok(());
        }
        let mut colors = colors.into_iter();
        for r in 0..h {
            let row = start + r * stride;
            for (px, c) in self.buf[row..row + w].iter_mut().zip(colors.by_ref()) {
                *px = c;
            }
        }
        Ok(())
    }
}
