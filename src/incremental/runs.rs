//! A row's changed runs ([`Runs`], [`Changes::runs`]) and the sink that sends each as its
//! own window ([`RunSink`]).

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::integer::IntSphere;
use crate::render::Render;
use crate::trace::scanline::{ColorRuns, PixelRow, RowSink};

use super::plan_integer::IntRule;
use super::region::{edge, Area};
use super::{Changes, FrameStats, MAX_REGIONS};

/// Two runs of a row at most this many pixels apart are sent as one.
///
/// A display controller of the ST7789/ILI9341 family opens a window with 11 bytes
/// (column and row address commands with four bytes each, the memory-write command);
/// re-sending a gap of `g` unchanged `Rgb565` pixels costs `2g` bytes: up to 5 pixels,
/// less than a second window.
pub const MERGE_GAP: u32 = 5;

impl Changes {
    /// Adds to `runs` the runs in row `j` of rectangle `g`'s regions that can reach
    /// columns `x0..x1`, merged.
    ///
    /// A gap is filled only between runs at most [`MERGE_GAP`] apart, so within
    /// `x0..x1` the runs of the regions reaching `x0 − MERGE_GAP..x1 + MERGE_GAP` are
    /// those of all of them.
    pub(super) fn add_runs(&self, runs: &mut Runs, g: u8, j: u32, (x0, x1): (u32, u32)) {
        let (width, pad) = self.row_consts();
        let from = runs.len;
        for e in &self.regions {
            let (lo, hi) = e.bbox.cols();
            if e.rect != g || lo >= x1 + MERGE_GAP || hi + MERGE_GAP <= x0 {
                continue;
            }
            if let Some(span) = e.span(j, width, pad) {
                runs.insert(span, from, MERGE_GAP);
            }
        }
    }

    /// The changed runs `[lo, hi)` of image row `j`, left to right, disjoint, runs of
    /// one rectangle closer than [`MERGE_GAP`] merged: what a DMA sender sends of the
    /// row.
    #[must_use]
    pub fn runs(&self, j: u32) -> Runs {
        let mut runs = Runs::new();
        for (g, rect) in self.rects.iter().enumerate() {
            if rect.has_row(j) {
                self.add_runs(&mut runs, g as u8, j, rect.cols());
            }
        }
        runs.sort();
        runs
    }

    /// Pixels and windows sent: the runs of every row.
    #[must_use]
    pub fn sent(&self) -> (u32, u32) {
        let (mut pixels, mut windows) = (0, 0);
        for j in 0..u32::from(self.height) {
            for (lo, hi) in self.runs(j) {
                pixels += hi - lo;
                windows += 1;
            }
        }
        (pixels, windows)
    }

    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub(super) fn draw<C, Tg, const N: usize, const L: usize, const P: usize, const D: usize>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        target: &mut Tg,
        picture: Option<&[IntSphere]>,
    ) -> Result<FrameStats, Tg::Error>
    where
        C: PixelColor + From<Rgb888>,
        Tg: DrawTarget<Color = C>,
    {
        let mut stats = FrameStats {
            full: self.full,
            refused: self.refused,
            arithmetic: self.arithmetic(),
            ..FrameStats::default()
        };
        if self.refused.is_some() {
            return Ok(stats);
        }
        let offset = render.offset();
        let bbox = target.bounding_box();
        // The strips on the target, traced as one frame (its set-up once).
        let clips = self
            .strips
            .iter()
            .map(|strip| {
                let rect = strip.rect();
                Rectangle::new(rect.top_left + offset, rect.size).intersection(&bbox)
            })
            .filter(|clip| !clip.is_zero_sized());
        for clip in clips.clone() {
            stats.traced += clip.size.width * clip.size.height;
            stats.strips += 1;
        }
        match (self.int_rule, picture) {
            // The integer kernel's frame from the picture the plan built, each strip one
            // window.
            (IntRule::Took(key), Some(picture)) => {
                let (sent, windows) = crate::integer::fill_strips::<N, _, _, _>(
                    picture,
                    key,
                    render.scene().background(),
                    render.camera(),
                    clips,
                    offset,
                    target,
                )?;
                stats.sent += sent;
                stats.windows += windows;
            }
            (IntRule::Took(_), None) => {
                render.render_clips(clips, offset, &mut self.sink(target, offset, &mut stats))?
            }
            // The rule refused the frame, or was not asked (not an integer kind of
            // render): the f32 method's.
            _ => render.render_clips_f32(clips, offset, &mut self.sink(target, offset, &mut stats))?,
        }
        Ok(stats)
    }

    /// The sink sending each changed run of a row as its own window.
    fn sink<'t, 's, Tg: DrawTarget<Color = C>, C>(
        &self,
        target: &'t mut Tg,
        offset: Point,
        stats: &'s mut FrameStats,
    ) -> RunSink<'t, '_, 's, Tg, C> {
        RunSink {
            target,
            changes: self,
            offset,
            stats,
            full: self.full,
            color: PhantomData,
        }
    }
}

/// The changed runs of one row ([`Changes::runs`]).
#[derive(Clone, Debug)]
pub struct Runs {
    runs: [(u16, u16); MAX_REGIONS],
    len: usize,
    next: usize,
}

impl Runs {
    pub(super) fn new() -> Self {
        Self {
            runs: [(0, 0); MAX_REGIONS],
            len: 0,
            next: 0,
        }
    }

    /// Adds `span` to the runs from index `from` on (one rectangle's), merging it with
    /// any it overlaps or comes within `gap` of.
    pub(super) fn insert(&mut self, (mut lo, mut hi): (u32, u32), from: usize, gap: u32) {
        let mut k = from;
        while k < self.len {
            let Some(&(a, b)) = self.runs.get(k) else { break };
            let (a, b) = (u32::from(a), u32::from(b));
            if lo <= b + gap && a <= hi + gap {
                lo = lo.min(a);
                hi = hi.max(b);
                // Remove run k (order is restored by `sort`).
                self.len -= 1;
                let last = self.runs.get(self.len).copied().unwrap_or((0, 0));
                if let Some(slot) = self.runs.get_mut(k) {
                    *slot = last;
                }
                k = from;
                continue;
            }
            k += 1;
        }
        if let Some(slot) = self.runs.get_mut(self.len) {
            *slot = (edge(lo), edge(hi));
            self.len += 1;
        }
    }

    pub(super) fn sort(&mut self) {
        if let Some(runs) = self.runs.get_mut(..self.len) {
            runs.sort_unstable_by_key(|r| r.0);
        }
    }
}

impl Iterator for Runs {
    type Item = (u32, u32);
    fn next(&mut self) -> Option<(u32, u32)> {
        let (lo, hi) = self
            .runs
            .get(self.next)
            .copied()
            .filter(|_| self.next < self.len)?;
        self.next += 1;
        Some((u32::from(lo), u32::from(hi)))
    }
}

/// Rows of one strip into a `DrawTarget`, only their changed runs, each run its own
/// `fill_contiguous`.
pub(super) struct RunSink<'t, 'c, 's, Tg, C> {
    target: &'t mut Tg,
    changes: &'c Changes,
    offset: Point,
    stats: &'s mut FrameStats,
    full: bool,
    color: PhantomData<C>,
}

impl<Tg: DrawTarget<Color = C>, C: PixelColor + From<Rgb888>> RowSink for RunSink<'_, '_, '_, Tg, C> {
    type Error = Tg::Error;
    fn row<R: PixelRow>(&mut self, area: Rectangle, row: R) -> Result<(), Tg::Error> {
        let ColorRuns {
            background,
            before,
            traced,
            traced_len: _,
            after,
        } = row.color_runs();
        let background = C::from(background);
        // A chain, not `ColorRuns::colors`: taken through `by_ref().take(..)` per run,
        // that iterator cost an incremental frame of the lit `bounce` 160 B more stack
        // on the Cortex-M4F (`docs/firmware.md`, "On the host").
        let mut colors = core::iter::repeat_n(background, before as usize)
            .chain(traced.map(C::from))
            .chain(core::iter::repeat_n(background, after as usize));
        if self.full {
            self.stats.sent += area.size.width;
            self.stats.windows += 1;
            return self.target.fill_contiguous(&area, colors);
        }
        // The area's columns in the image.
        let j = (area.top_left.y - self.offset.y) as u32;
        let x0 = (area.top_left.x - self.offset.x) as u32;
        let x1 = x0 + area.size.width;
        // The rectangle the row's strip was cut from (they are disjoint): its regions'
        // runs are the strip's.
        let at_row = Area::new(x0, j, x0 + 1, j + 1);
        let rect = self
            .changes
            .rects
            .iter()
            .position(|r| r.meets(at_row))
            .unwrap_or(0) as u8;
        let mut runs = Runs::new();
        self.changes.add_runs(&mut runs, rect, j, (x0, x1));
        runs.sort();
        let mut at = x0;
        for (lo, hi) in runs {
            let (lo, hi) = (lo.max(x0), hi.min(x1));
            if lo >= hi {
                continue;
            }
            // Skip to the run, then hand the target exactly the run's colours, however
            // many of them it takes.
            if lo > at {
                colors.nth((lo - at - 1) as usize);
            }
            let len = hi - lo;
            let mut taken = 0;
            let run = Rectangle::new(
                Point::new(lo as i32 + self.offset.x, area.top_left.y),
                Size::new(len, 1),
            );
            self.target
                .fill_contiguous(&run, colors.by_ref().take(len as usize).inspect(|_| taken += 1))?;
            if taken < len {
                colors.nth((len - taken - 1) as usize);
            }
            at = hi;
            self.stats.sent += len;
            self.stats.windows += 1;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn runs(r: Runs) -> std::vec::Vec<(u32, u32)> {
        r.collect()
    }

    #[test]
    fn runs_within_the_gap_merge() {
        let mut r = Runs::new();
        r.insert((20, 30), 0, MERGE_GAP);
        r.insert((0, 5), 0, MERGE_GAP);
        // 3 pixels from the first run, 8 from the second: joins the first only.
        r.insert((8, 12), 0, MERGE_GAP);
        r.sort();
        assert_eq!(runs(r), [(0, 12), (20, 30)]);
        // A run that bridges two merges all three.
        let mut r = Runs::new();
        r.insert((0, 5), 0, MERGE_GAP);
        r.insert((20, 30), 0, MERGE_GAP);
        r.insert((9, 16), 0, MERGE_GAP);
        r.sort();
        assert_eq!(runs(r), [(0, 30)]);
    }

    #[test]
    fn runs_of_another_rectangle_stay_apart() {
        let mut r = Runs::new();
        r.insert((0, 5), 0, MERGE_GAP);
        r.insert((6, 8), 1, MERGE_GAP);
        r.sort();
        assert_eq!(runs(r), [(0, 5), (6, 8)]);
    }

    #[test]
    fn a_row_sends_its_regions_runs() {
        let rect = |x, y, w, h| Rectangle::new(Point::new(x, y), Size::new(w, h));
        let mut plan = Changes::empty(Size::new(20, 10), 16, 0);
        assert!(plan.push_rect(rect(1, 1, 3, 3)));
        assert!(plan.push_rect(rect(2, 2, 3, 3)));
        assert!(plan.push_rect(rect(15, 5, 2, 2)));
        plan.merge();
        assert_eq!(runs(plan.runs(0)), []);
        assert_eq!(runs(plan.runs(1)), [(1, 4)]);
        assert_eq!(runs(plan.runs(3)), [(1, 5)]);
        assert_eq!(runs(plan.runs(5)), [(15, 17)]);
        assert_eq!(plan.sent(), (3 + 4 + 4 + 3 + 2 + 2, 6));
    }
}
