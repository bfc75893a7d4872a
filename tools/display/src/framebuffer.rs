//! A framebuffer in memory, in a panel's own colour type.

use alloc::vec;
use alloc::vec::Vec;
use core::convert::Infallible;

use embedded_graphics::{pixelcolor::BinaryColor, prelude::*};

/// `size.width × size.height` pixels of colour `C`, row-major, as a panel holds them.
pub(crate) struct Framebuffer<C> {
    size: Size,
    pixels: Vec<C>,
}

impl<C: PixelColor + From<BinaryColor>> Framebuffer<C> {
    /// A framebuffer of `size`, dark (`BinaryColor::Off`, as the simulator's display
    /// starts).
    pub(crate) fn new(size: Size) -> Self {
        let n = size.width as usize * size.height as usize;
        Self {
            size,
            pixels: vec![C::from(BinaryColor::Off); n],
        }
    }
}

impl<C: PixelColor> Framebuffer<C> {
    /// The pixels, row-major.
    pub(crate) fn pixels(&self) -> &[C] {
        &self.pixels
    }
}

impl<C: PixelColor> OriginDimensions for Framebuffer<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor> DrawTarget for Framebuffer<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        let (w, h) = (self.size.width, self.size.height);
        for Pixel(p, color) in pixels {
            // Outside the panel: dropped, as a display drops it.
            let (Ok(x), Ok(y)) = (u32::try_from(p.x), u32::try_from(p.y)) else {
                continue;
            };
            if x < w && y < h {
                if let Some(pixel) = self.pixels.get_mut(y as usize * w as usize + x as usize) {
                    *pixel = color;
                }
            }
        }
        Ok(())
    }
}
