//! The DMA band path: the ST7789's wire pixel format, and the frame-time label drawn
//! over a band.

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};

/// The panel, in pixels.
pub const WIDTH: u32 = 240;
pub const HEIGHT: u32 = 240;
/// Rows per band: 240 × 16 pixels × 2 bytes = 7.5 KiB per buffer, 15 bands a frame.
pub const BAND_ROWS: u32 = 16;
pub const BANDS: u32 = HEIGHT / BAND_ROWS;
pub const BAND_PIXELS: usize = (WIDTH * BAND_ROWS) as usize;

/// An Rgb565 pixel in the ST7789's wire order: its two bytes, high byte first (the
/// order the controller reads a 16-bit pixel in, COLMOD 0x55).
#[derive(Clone, Copy, PartialEq, Eq)]
#[repr(transparent)]
pub struct WireRgb565([u8; 2]);

impl WireRgb565 {
    pub const BLACK: Self = Self([0; 2]);
    /// Dark red (Rgb565 red 16 of 31): a band the kernel refused, not to be taken for
    /// the black background.
    pub const REFUSED: Self = Self([0x80, 0x00]);

    /// The two bytes as they go on the wire.
    #[allow(dead_code)] // used by band_cycles only
    pub const fn bytes(self) -> [u8; 2] {
        self.0
    }
}

impl PixelColor for WireRgb565 {
    type Raw = RawU16;
}

impl From<Rgb565> for WireRgb565 {
    #[inline]
    fn from(color: Rgb565) -> Self {
        Self(color.into_storage().to_be_bytes())
    }
}

/// The kernel's colour conversion: the same Rgb565 as the blocking example's display
/// gets, in wire order.
impl From<Rgb888> for WireRgb565 {
    #[inline]
    fn from(color: Rgb888) -> Self {
        Self::from(Rgb565::from(color))
    }
}

// SAFETY: `WireRgb565` is `repr(transparent)` over `[u8; 2]`: two initialised bytes, no
// padding, alignment 1, so a `[WireRgb565; N]` is readable by DMA as 2·N bytes (the
// length `ReadTarget`'s default method computes from `size_of_val`).
unsafe impl embedded_dma::ReadTarget for WireRgb565 {
    type Word = u8;
}

/// Draws `text` (white on black, 6×10 font) at (2, 2) over band 0 in `buf`.
pub fn draw_label(buf: &mut [WireRgb565], text: &str) {
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(Rgb565::WHITE)
        .background_color(Rgb565::BLACK)
        .build();
    let Ok(_) = Text::with_baseline(text, Point::new(2, 2), style, Baseline::Top).draw(&mut Band0(buf));
}

/// Band 0 (rows 0–15) as a `DrawTarget`; pixels outside it are dropped.
struct Band0<'a>(&'a mut [WireRgb565]);

impl OriginDimensions for Band0<'_> {
    fn size(&self) -> Size {
        Size::new(WIDTH, BAND_ROWS)
    }
}

impl DrawTarget for Band0<'_> {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        let area = self.bounding_box();
        for Pixel(p, color) in pixels {
            if area.contains(p) {
                // Inside the band: both coordinates are non-negative.
                let i = p.y as usize * WIDTH as usize + p.x as usize;
                if let Some(pixel) = self.0.get_mut(i) {
                    *pixel = color.into();
                }
            }
        }
        Ok(())
    }
}
