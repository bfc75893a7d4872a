//! The integer kernel's strips as pixel streams ([`fill_strips`]): each clip's rows one
//! after another, for a target to take as one window.

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use super::frame::{IntFrame, IntSphere, Quantisation};
use super::row::{activate, Active, IntRow};
use crate::camera::Camera;
use crate::trace::frame::{hull, visible};

/// Draws the part of a picture the rule has built ([`picture`](super::picture),
/// quantised by `key`) that each of `clips` shows, each clip's visible rectangle as one
/// `fill_contiguous`: the same frame as [`render`](super::render)'s, without deciding
/// the rule again, its rows pulled by the target one pixel after another. Returns the
/// pixels and the windows sent.
///
/// A display controller opens a window with a few commands (the ST7789: 11 bytes, and
/// on a Cortex-M0+ through `mipidsi` about as many cycles as 40 pixels take): one
/// window a strip instead of one a row.
pub(crate) fn fill_strips<const N: usize, C, Tg, I>(
    picture: &[IntSphere],
    key: Quantisation,
    background: Rgb888,
    camera: &Camera,
    clips: I,
    offset: Point,
    target: &mut Tg,
) -> Result<(u32, u32), Tg::Error>
where
    C: PixelColor + From<Rgb888>,
    Tg: DrawTarget<Color = C>,
    I: Iterator<Item = Rectangle> + Clone,
{
    let Some(bound) = clips.clone().reduce(hull) else {
        return Ok((0, 0));
    };
    let Some(mut frame) = IntFrame::from_picture(picture, key, background, camera, bound, offset) else {
        return Ok((0, 0));
    };
    let (mut sent, mut windows) = (0, 0);
    for clip in clips {
        let Some((i0, i1, j0, j1)) = visible(camera.size(), offset, clip) else {
            continue;
        };
        (frame.i0, frame.i1, frame.j0, frame.j1) = (i0, i1, j0, j1);
        let area = Rectangle::new(
            Point::new(offset.x.wrapping_add(i0 as i32), offset.y.wrapping_add(j0 as i32)),
            Size::new(i1 - i0, j1 - j0),
        );
        target.fill_contiguous(&area, StripPixels::<N>::new(&frame).map(C::from))?;
        sent += area.size.width * area.size.height;
        windows += 1;
    }
    Ok((sent, windows))
}

/// The frame's visible rectangle, row after row: each row's background before its
/// traced columns, the traced colours, the background after (as a row sink takes
/// them, [`ColorRuns`](crate::trace::scanline::ColorRuns)).
struct StripPixels<'s, 'c, const N: usize> {
    row: IntRow<'s, 'c, Vec<Active<'c>, N>>,
    /// The next row to start.
    next_j: u32,
    /// The current row's background columns still to give before and after its
    /// traced ones.
    before: u32,
    after: u32,
    background: Rgb888,
}

impl<'s, 'c, const N: usize> StripPixels<'s, 'c, N> {
    fn new(frame: &'s IntFrame<'c>) -> Self {
        Self {
            row: IntRow::new(frame, Vec::new()),
            next_j: frame.j0,
            before: 0,
            after: 0,
            background: frame.background,
        }
    }

    /// Starts the next row; `false` after the last.
    #[inline(never)]
    fn start_row(&mut self) -> bool {
        let (frame, active) = self.row.parts();
        let j = self.next_j;
        if j >= frame.j1 {
            return false;
        }
        self.next_j = j + 1;
        let spans = activate(frame, j, active.as_mut_view());
        self.row.begin(j, spans);
        (self.before, self.after) = self.row.enter_traced();
        true
    }
}

impl<const N: usize> Iterator for StripPixels<'_, '_, N> {
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        loop {
            if self.before > 0 {
                self.before -= 1;
                return Some(self.background);
            }
            if let Some(color) = self.row.next_traced() {
                return Some(color);
            }
            if self.after > 0 {
                self.after -= 1;
                return Some(self.background);
            }
            if !self.start_row() {
                return None;
            }
        }
    }
}
