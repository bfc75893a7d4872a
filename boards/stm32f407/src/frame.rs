//! What a frame sends, without the HAL: the bands of a whole frame, or only the changed
//! runs of an incremental one, each in its own address window. The firmware
//! (`main.rs`) puts them on the wire (whole frames by DMA); the lab's host test
//! (`lab/tests/lab/board_examples.rs`) compiles this file and sends them to a model of
//! the controller's memory, which must then hold the whole render of the frame.

use core::ops::Range;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_raytracer::incremental::Changes;
use embedded_raytracer::{BandError, Render};

/// The label's rows over the picture: `draw_label`'s 6×10 text at (2, 2).
pub const LABEL_ROWS: u32 = 12;

/// The controller's side of the wire: an address window opened (CASET, RASET, RAMWR),
/// then pixels written into it.
pub trait Wire<C> {
    fn window(&mut self, x: Range<u32>, y: Range<u32>);
    fn pixels(&mut self, pixels: &[C]);
}

/// A frame of changed runs (`changes` of `frame`, neither whole nor refused): every
/// band of `band_rows` rows that holds a run is traced into `buf` (`Changes::draw_band`:
/// the changed pixels only), `label` is drawn over band 0, and each run goes out in a
/// window of its own. Returns the pixels sent.
///
/// Always inlined, as `Changes::draw_band` is: the caller's `frame`, built with a
/// constant method, then dispatches to that method's code alone; out of line, the
/// method would be a run-time value here and every method's code would be linked.
///
/// # Errors
///
/// A band `draw_band` refused: the runs sent before it are on the display, the rest
/// not (the caller then forgets what the display shows).
#[inline(always)]
pub fn send_runs<C, W, const N: usize, const L: usize, const P: usize, const D: usize>(
    changes: &Changes,
    frame: &Render<'_, N, C, L, P, D>,
    band_rows: u32,
    buf: &mut [C],
    mut label: impl FnMut(&mut [C]),
    wire: &mut W,
) -> Result<u32, BandError>
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
        let expected = (size.width * band.len() as u32) as usize;
        let found = buf.len();
        let pixels = buf
            .get_mut(..expected)
            .ok_or(BandError::BufferSize { expected, found })?;
        changes.draw_band(frame, band.clone(), pixels)?;
        if top == 0 {
            label(pixels);
        }
        for j in band.clone() {
            for (lo, hi) in changes.runs(j) {
                let first = ((j - top) * size.width + lo) as usize;
                wire.window(lo..hi, j..j + 1);
                wire.pixels(pixels.get(first..first + (hi - lo) as usize).unwrap_or(&[]));
                sent += hi - lo;
            }
        }
    }
    Ok(sent)
}
