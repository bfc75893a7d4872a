//! A frame of changed runs, without the HAL: the bands that hold a changed run are
//! traced by the integer kernel alone (`Render::draw_integer`, clipped to the traced
//! rectangles of `Changes`: no `f32` render is linked), and each run goes out in an
//! address window of its own. Compiled by the two-core firmware (`main.rs`, where
//! core 0 sends such a frame alone) and by the host test
//! `lab/tests/lab/rp2040_split.rs`, which sends the frames to a model of the
//! controller's memory.

use core::convert::Infallible;
use core::ops::Range;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::incremental::Changes;
use embedded_raytracer::{IntegerError, Render};

/// The controller's side of the wire: an address window opened (CASET, RASET, RAMWR),
/// then pixels written into it.
pub trait Wire<C> {
    fn window(&mut self, x: Range<u32>, y: Range<u32>);
    fn pixels(&mut self, pixels: &[C]);
}

/// Rows `rows` of the image in a band buffer (row-major, `width` a row), seen as a
/// target whose bounding box is `clip`: the render traces only that rectangle.
struct Clipped<'a, C> {
    buf: &'a mut [C],
    width: u32,
    top: u32,
    clip: Rectangle,
}

impl<C> Dimensions for Clipped<'_, C> {
    fn bounding_box(&self) -> Rectangle {
        self.clip
    }
}

impl<C: PixelColor> DrawTarget for Clipped<'_, C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            if self.clip.contains(p) {
                // Inside the clip, which lies within the band: non-negative, in range.
                let i = (p.y as u32 - self.top) * self.width + p.x as u32;
                if let Some(px) = self.buf.get_mut(i as usize) {
                    *px = c;
                }
            }
        }
        Ok(())
    }
}

/// Sends the changed runs of `changes` (neither whole nor refused) of `frame`: every
/// band of `band_rows` rows holding a run is traced into `buf` where `changes` traces
/// (its rectangles), `label` is drawn over band 0, and each run goes out in a window
/// of its own. Returns the pixels sent.
///
/// # Errors
///
/// The integer kernel's refusal of a rectangle (`IntegerError::Refused`): the runs sent
/// before it are on the display, the rest not (the caller then forgets what the
/// display shows).
pub fn send_runs<C, W, const N: usize>(
    changes: &Changes,
    frame: &Render<'_, N, C>,
    band_rows: u32,
    buf: &mut [C],
    mut label: impl FnMut(&mut [C]),
    wire: &mut W,
) -> Result<u32, IntegerError<Infallible>>
where
    C: PixelColor + From<Rgb888>,
    W: Wire<C>,
{
    let size = frame.area().size;
    let mut sent = 0;
    for top in (0..size.height).step_by(band_rows.max(1) as usize) {
        let band = top..(top + band_rows).min(size.height);
        if band.clone().all(|j| changes.runs(j).next().is_none()) {
            continue;
        }
        let rows = Rectangle::new(
            Point::new(0, top as i32),
            Size::new(size.width, band.len() as u32),
        );
        for rect in changes.rectangles() {
            let clip = rect.intersection(&rows);
            if clip.is_zero_sized() {
                continue;
            }
            let mut target = Clipped {
                buf: &mut *buf,
                width: size.width,
                top,
                clip,
            };
            frame.draw_integer(&mut target)?;
        }
        if top == 0 {
            label(buf);
        }
        for j in band.clone() {
            for (lo, hi) in changes.runs(j) {
                let first = ((j - top) * size.width + lo) as usize;
                wire.window(lo..hi, j..j + 1);
                wire.pixels(buf.get(first..first + (hi - lo) as usize).unwrap_or(&[]));
                sent += hi - lo;
            }
        }
    }
    Ok(sent)
}
