//! The plan of a frame ([`Changes`]): its regions' rectangles cut into strips of rows,
//! and the strips traced as one frame into a band buffer.

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::error::{BandError, FrameError};
use crate::render::Render;

use crate::method::Arithmetic;

use super::plan_integer::IntRule;
use super::region::{edge, Area, Entry, Region};

/// At most this many regions (silhouettes and rectangles) a frame re-traces; more draw
/// the whole frame.
///
/// With the strips it bounds the plan's size ([`Changes`]).
pub const MAX_REGIONS: usize = 12;

/// What a new strip costs, in pixels traced outside the changed runs, for each kind of
/// frame ([`STRIP_SETUP`]).
///
/// A traced rectangle is cut into strips of rows that follow the changed runs; a strip
/// grows while it traces at most this many pixels outside the runs. Tuning constants:
/// any values draw the same pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StripSetup {
    /// One ray a pixel and grids: the strips of a frame are traced as one frame, its
    /// set-up (scale, silhouettes, shadow regions, the integer kernel's rule) paid once,
    /// so a strip costs only its rows' start.
    pub one_frame: u32,
    /// Adaptive sampling: its rows hold their clip, so each strip is a frame of its own
    /// and pays the set-up.
    pub frame_each: u32,
}

/// The pixels outside the changed runs a strip may trace before a new strip is cheaper.
///
/// What these values give on the Cortex-M4F (`bounce`'s worst frame: its pixels,
/// strips and instructions) is measured in `docs/animation.md` ("One set-up a frame").
pub const STRIP_SETUP: StripSetup = StripSetup {
    one_frame: 16,
    frame_each: 512,
};

/// At most this many strips a frame; more trace each rectangle whole.
const MAX_STRIPS: usize = 48;

/// The plan of one frame: the regions that can have changed, their rectangles and strips.
///
/// It takes at most 1,008 bytes on a 32-bit target (checked when the crate compiles), on
/// the stack beside the render's own while a frame draws.
#[derive(Clone, Debug)]
pub struct Changes {
    pub(super) width: u16,
    pub(super) height: u16,
    /// The regions; a row's runs are merged only with runs of the same rectangle.
    pub(super) regions: Vec<Entry, MAX_REGIONS, u8>,
    /// The regions' boxes, those that overlap merged into one, until none does.
    pub(super) rects: Vec<Area, MAX_REGIONS, u8>,
    /// The rectangles the render is clipped to: each of `rects` cut into strips of rows
    /// that follow the runs' extent.
    pub(super) strips: Vec<Area, MAX_STRIPS, u8>,
    /// The frame kind's [`STRIP_SETUP`].
    pub(super) strip_setup: u32,
    /// Pixels a silhouette is widened by each way: the sampling's footprint (rule step 3).
    pub(super) pad: u8,
    pub(super) full: bool,
    pub(super) refused: Option<FrameError>,
    /// The integer kernel's rule for the frame, where the plan asked it.
    pub(super) int_rule: IntRule,
}

// The plan sits on the stack beside the render's own while a frame draws (the size the
// `Incremental` and `Changes` docs state).
#[cfg(target_pointer_width = "32")]
const _: () = assert!(size_of::<Changes>() <= 1008);

impl Changes {
    pub(super) fn empty(size: Size, strip_setup: u32, pad: u32) -> Self {
        Self {
            width: edge(size.width),
            height: edge(size.height),
            regions: Vec::new(),
            rects: Vec::new(),
            strips: Vec::new(),
            strip_setup,
            pad: u8::try_from(pad).unwrap_or(u8::MAX),
            full: false,
            refused: None,
            int_rule: IntRule::Unknown,
        }
    }

    /// The whole frame, for the integer kernel's `rule`.
    pub(super) fn full_with(size: Size, rule: IntRule) -> Self {
        let mut plan = Self::full(size);
        plan.int_rule = rule;
        plan
    }

    pub(super) fn full(size: Size) -> Self {
        let image = Area::new(0, 0, size.width, size.height);
        let mut plan = Self::empty(size, 0, 0);
        let _ = plan.regions.push(Entry {
            region: Region::Rect,
            bbox: image,
            waste: 0,
            rect: 0,
        });
        let _ = plan.rects.push(image);
        let _ = plan.strips.push(image);
        plan.full = true;
        plan
    }

    pub(super) fn refusal(size: Size, why: FrameError) -> Self {
        let mut plan = Self::empty(size, 0, 0);
        plan.refused = Some(why);
        plan
    }

    /// The image's width and the silhouettes' widening, as a row's cut takes them.
    pub(super) fn row_consts(&self) -> (u32, u32) {
        (u32::from(self.width), u32::from(self.pad))
    }

    /// Cuts rectangle `r` into strips of rows, each as wide as its rows' runs reach;
    /// `false` if the strips do not fit.
    ///
    /// A strip grows a row while the pixels it would trace outside the runs stay within
    /// the frame kind's [`STRIP_SETUP`] (what a new strip costs); a row without a run
    /// ends it.
    pub(super) fn cut_strips(&mut self, r: usize) -> bool {
        let Some(&rect) = self.rects.get(r) else {
            return true;
        };
        let group = r as u8;
        // The whole rectangle is one strip if it traces at most `strip_setup` pixels
        // outside its runs: a strip's pixels outside its runs never shrink as it grows a
        // row, so the rule below never ends it early. Bounded from the regions' boxes,
        // without a row's runs: the rectangle's rows are its boxes' rows, joined (boxes
        // that share no row never merge), so if each box has a run in every row, so has
        // the rectangle; and its runs hold any one region's.
        let outside = self
            .regions
            .iter()
            .filter(|e| e.rect == group)
            .try_fold(u32::MAX, |least, e| {
                (e.waste != u16::MAX).then(|| least.min(rect.pixels() - e.bbox.pixels() + u32::from(e.waste)))
            });
        if outside.is_some_and(|w| w <= self.strip_setup) {
            return self.strips.push(rect).is_ok();
        }
        let (width, pad) = self.row_consts();
        let (y0, y1) = rect.rows();
        // The open strip: first row, columns, and the pixels of its rows' runs' extents.
        let mut open: Option<(u32, u32, u32, u32)> = None;
        let mut ok = true;
        let mut close =
            |strips: &mut Vec<Area, MAX_STRIPS, u8>, (top, lo, hi, _): (u32, u32, u32, u32), end: u32| {
                ok &= strips.push(Area::new(lo, top, hi, end)).is_ok();
            };
        for j in y0..y1 {
            // This row's runs' extent: the rectangle's regions' (merging runs closer than
            // `MERGE_GAP` fills gaps inside it only).
            let extent = self
                .regions
                .iter()
                .filter(|e| e.rect == group)
                .filter_map(|e| e.span(j, width, pad))
                .fold(None, |e: Option<(u32, u32)>, (lo, hi)| {
                    Some(e.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))))
                });
            open = match (open, extent) {
                (None, None) => None,
                (None, Some((lo, hi))) => Some((j, lo, hi, hi - lo)),
                (Some(strip), None) => {
                    close(&mut self.strips, strip, j);
                    None
                }
                (Some((top, a, b, used)), Some((lo, hi))) => {
                    let (na, nb) = (a.min(lo), b.max(hi));
                    let used = used + (hi - lo);
                    if (nb - na) * (j + 1 - top) - used <= self.strip_setup {
                        Some((top, na, nb, used))
                    } else {
                        close(&mut self.strips, (top, a, b, used), j);
                        Some((j, lo, hi, hi - lo))
                    }
                }
            };
        }
        if let Some(strip) = open {
            close(&mut self.strips, strip, y1);
        }
        ok
    }

    /// The whole frame is drawn.
    #[must_use]
    pub fn is_full(&self) -> bool {
        self.full
    }

    /// Nothing changed: nothing to trace or send.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.rects.is_empty()
    }

    /// Why the frame cannot be drawn ([`Render::check`]); nothing is traced then.
    #[must_use]
    pub fn refused(&self) -> Option<FrameError> {
        self.refused
    }

    /// The arithmetic that draws the frame: [`Arithmetic::Integer`] where the method
    /// asks for the integer kernel and its per-frame rule takes the frame, as
    /// [`Render::arithmetic`] says of the same render.
    #[must_use]
    pub fn arithmetic(&self) -> Arithmetic {
        match self.int_rule {
            IntRule::Took(_) => Arithmetic::Integer,
            IntRule::Unknown | IntRule::Refused => Arithmetic::F32,
        }
    }

    /// The rectangles traced (image coordinates), disjoint.
    pub fn rectangles(&self) -> impl Iterator<Item = Rectangle> + '_ {
        self.strips.iter().map(|s| s.rect())
    }

    /// Pixels traced: the rectangles' area.
    #[must_use]
    pub fn traced(&self) -> u32 {
        self.strips.iter().map(|s| s.pixels()).sum()
    }

    /// Traces the changed pixels of rows `rows` into `buf`, a band as
    /// [`Render::draw_band`] takes it (row-major, the image's width a row).
    ///
    /// The pixels of [`Changes::runs`] (and the rest of their rectangles) get the full
    /// render's colours, the others keep what `buf` held.
    ///
    /// # Errors
    ///
    /// [`Render::draw_band`]'s; a refused plan ([`Changes::refused`]) is
    /// [`BandError::Frame`], as the render refuses that frame, though nothing is traced.
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub fn draw_band<C, const N: usize, const L: usize, const P: usize, const D: usize>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        rows: core::ops::Range<u32>,
        buf: &mut [C],
    ) -> Result<(), BandError>
    where
        C: PixelColor + From<Rgb888>,
    {
        let (band, mut sink) = render.band(rows, buf)?;
        // A refusal is the plan's: it has no strip, so no render refuses it again.
        if let Some(why) = self.refused {
            return Err(BandError::Frame(why));
        }
        let clips = self
            .strips
            .iter()
            .map(|strip| strip.rect().intersection(&band))
            .filter(|clip| !clip.is_zero_sized());
        let Ok(()) = render.render_clips(clips, Point::zero(), &mut sink);
        match sink.refused {
            None => Ok(()),
            Some(why) => Err(BandError::Frame(why)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x: i32, y: i32, w: u32, h: u32) -> Rectangle {
        Rectangle::new(Point::new(x, y), Size::new(w, h))
    }

    #[test]
    fn the_full_plan_traces_and_sends_the_image() {
        let plan = Changes::full(Size::new(8, 4));
        assert!(plan.is_full() && !plan.is_empty() && plan.refused().is_none());
        assert_eq!(
            plan.rectangles().collect::<std::vec::Vec<_>>(),
            [rect(0, 0, 8, 4)]
        );
        assert_eq!(plan.traced(), 32);
        assert_eq!(plan.sent(), (32, 4));
        let nothing = Changes::empty(Size::new(8, 4), STRIP_SETUP.one_frame, 0);
        assert!(nothing.is_empty() && nothing.traced() == 0);
    }

    #[test]
    fn a_rectangle_is_one_strip_while_it_wastes_little() {
        // Two boxes of 9 pixels merged into 16: 7 pixels outside the runs.
        let mut plan = Changes::empty(Size::new(20, 10), 7, 0);
        assert!(plan.push_rect(rect(1, 1, 3, 3)) && plan.push_rect(rect(2, 2, 3, 3)));
        plan.merge();
        assert_eq!(
            plan.rectangles().collect::<std::vec::Vec<_>>(),
            [rect(1, 1, 4, 4)]
        );
    }

    #[test]
    fn strips_follow_the_runs() {
        // An L: a column of rows 0..4 and a bar of rows 3..5, merged into one 10 × 5
        // rectangle; with no waste allowed, a strip ends where the runs widen or narrow.
        let mut plan = Changes::empty(Size::new(20, 10), 0, 0);
        assert!(plan.push_rect(rect(0, 0, 2, 4)) && plan.push_rect(rect(1, 3, 9, 2)));
        plan.merge();
        assert_eq!(plan.rects.len(), 1);
        assert_eq!(
            plan.rectangles().collect::<std::vec::Vec<_>>(),
            [rect(0, 0, 2, 3), rect(0, 3, 10, 1), rect(1, 4, 9, 1)]
        );
        assert_eq!(plan.traced(), 6 + 10 + 9);
    }

    #[test]
    fn a_refused_frame_traces_nothing() {
        let why = FrameError::Magnitudes {
            far: crate::error::ObjectRef::Sphere(0),
            near: crate::error::ObjectRef::Sphere(1),
        };
        let plan = Changes::refusal(Size::new(8, 4), why);
        assert_eq!(plan.refused(), Some(why));
        assert!(plan.is_empty() && plan.traced() == 0);
    }
}
