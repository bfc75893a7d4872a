//! The regions' geometry: each region of the image that can have changed (a silhouette,
//! an integer cut or a rectangle) to its runs and bounding box, and the boxes merged
//! into disjoint rectangles.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::camera::int_cut::IntCut;
use crate::camera::span::Silhouette;

use super::Changes;

// Every edge of a rectangle of the image fits an `Area`'s `u16`.
const _: () = assert!(crate::math::limits::MAX_RESOLUTION <= u16::MAX as u32);

/// A rectangle of the image, `[x0, x1) × [y0, y1)` in pixels, each edge a `u16`.
///
/// An image is at most `MAX_RESOLUTION` pixels each way, so each edge fits: half a
/// `Rectangle`, for the plan's rectangles and strips.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Area {
    x0: u16,
    y0: u16,
    x1: u16,
    y1: u16,
}

impl Area {
    /// From edges of the image (each at most `MAX_RESOLUTION`).
    pub(super) fn new(x0: u32, y0: u32, x1: u32, y1: u32) -> Self {
        Self {
            x0: edge(x0),
            y0: edge(y0),
            x1: edge(x1),
            y1: edge(y1),
        }
    }

    /// A rectangle of the image.
    pub(super) fn of(r: Rectangle) -> Self {
        let (x0, y0) = (r.top_left.x.max(0) as u32, r.top_left.y.max(0) as u32);
        Self::new(x0, y0, x0 + r.size.width, y0 + r.size.height)
    }

    pub(super) fn rect(self) -> Rectangle {
        let ((x0, x1), (y0, y1)) = (self.cols(), self.rows());
        Rectangle::new(
            Point::new(x0 as i32, y0 as i32),
            Size::new(x1.saturating_sub(x0), y1.saturating_sub(y0)),
        )
    }

    pub(super) fn cols(self) -> (u32, u32) {
        (u32::from(self.x0), u32::from(self.x1))
    }

    pub(super) fn rows(self) -> (u32, u32) {
        (u32::from(self.y0), u32::from(self.y1))
    }

    pub(super) fn has_row(self, j: u32) -> bool {
        u32::from(self.y0) <= j && j < u32::from(self.y1)
    }

    pub(super) fn pixels(self) -> u32 {
        let ((x0, x1), (y0, y1)) = (self.cols(), self.rows());
        x1.saturating_sub(x0) * y1.saturating_sub(y0)
    }

    /// Whether the two share a pixel.
    pub(super) fn meets(self, o: Area) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// Whether the two share no pixel but sit side by side in a row they share (one's
    /// last column next to the other's first): their runs there can touch, two windows
    /// where one does.
    pub(super) fn abuts(self, o: Area) -> bool {
        self.y0 < o.y1 && o.y0 < self.y1 && (self.x1 == o.x0 || o.x1 == self.x0)
    }

    /// The smallest rectangle holding both.
    pub(super) fn bounding(self, o: Area) -> Area {
        Area {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }
}

/// An edge or size of the image as a `u16` (it is at most `MAX_RESOLUTION`).
pub(super) fn edge(v: u32) -> u16 {
    u16::try_from(v).unwrap_or(u16::MAX)
}

/// One region of the image that can have changed; its rows and columns are its entry's
/// bounding box.
#[derive(Clone, Copy, Debug)]
pub(super) enum Region {
    /// A silhouette, widened by the plan's `pad` pixels each way.
    Ellipse(Silhouette),
    /// A sphere's cut in the integer kernel (one that culls nothing is a `Rect`).
    Int(IntCut),
    /// Its bounding box.
    Rect,
}

impl Region {
    /// Its columns `[lo, hi)` in row `j` of an image `width` wide, or `None` for `Rect`
    /// (its box is its run); for `Int`, `j` is one of its sphere's rows.
    pub(super) fn cut(&self, j: u32, width: u32, pad: u32) -> Option<(u32, u32)> {
        match *self {
            Region::Rect => None,
            Region::Int(cut) => cut.row_span(j, width),
            Region::Ellipse(sil) if pad == 0 => sil.row_span(j, 0, width),
            Region::Ellipse(sil) => {
                // A pixel's rays (and, with `pad`, its neighbours') lie within
                // `pad + ½` of its centre: the silhouette's reach over those rows,
                // widened as much in columns. The reach's two roots are taken per row:
                // only a frame of several rays a pixel widens, and there they are a few
                // of the row's rays.
                let h = pad as f32 + 0.5;
                let (lo, hi) = sil.band_reach(j, h, sil.reach_consts())?;
                let lo = libm::floorf(lo - h).max(0.0).min(width as f32);
                let hi = (libm::ceilf(hi + h) + 1.0).max(0.0).min(width as f32);
                // NaN clamps to a bound: the whole row.
                let (lo, hi) = (lo as u32, hi as u32);
                (lo < hi).then_some((lo, hi))
            }
        }
    }
}

/// A region, its bounding box (the rows and columns of its runs) and its rectangle.
#[derive(Clone, Copy, Debug)]
pub(super) struct Entry {
    pub(super) region: Region,
    pub(super) bbox: Area,
    /// The pixels of `bbox` outside the region's runs, if every row of `bbox` has a run
    /// (else, or if more, `u16::MAX`): what a strip of `bbox` alone traces outside them.
    pub(super) waste: u16,
    /// The index in `Changes::rects` of the rectangle holding `bbox`.
    pub(super) rect: u8,
}

impl Entry {
    /// Its run `[lo, hi)` in row `j` of an image `width` wide.
    #[inline]
    pub(super) fn span(&self, j: u32, width: u32, pad: u32) -> Option<(u32, u32)> {
        if !self.bbox.has_row(j) {
            return None;
        }
        match self.region {
            Region::Rect => Some(self.bbox.cols()),
            region => region.cut(j, width, pad),
        }
    }
}

impl Changes {
    /// Adds a silhouette (rule steps 2 and 3); `false` if it cannot be planned (not a
    /// bounded ellipse, or one region too many).
    ///
    /// Its rows: with one ray a pixel, those whose centre line cuts the ellipse
    /// ([`Silhouette::rows`], exactly `row_span`'s). With a footprint (`pad > 0`) a row
    /// can change where no centre line cuts the ellipse (one smaller than a pixel,
    /// between two rows' centres, which their sub-pixel rays meet): so every row whose
    /// band `j ± (pad + ½)` ([`Region::cut`]) can meet the ellipse's vertical extent,
    /// the centre row `y0` ± the half-height `Silhouette::band_reach` cuts its band to.
    /// That function misses the band only where `|j − y0|` exceeds the half-height plus
    /// the band plus a relative `2⁻²⁰` slack, so the half-height and band widened by a
    /// relative `2⁻¹⁶` and a row each way (for the `f32` rounding of `y0` and of the
    /// ends) hold every row it reaches; `Region::cut` then gives each row its run.
    pub(super) fn push_silhouette(&mut self, sil: Silhouette) -> bool {
        let Some(ellipse) = sil.get() else {
            return false;
        };
        // An ellipse with `h0 < 0` ([`Silhouette::NONE`]) has no row.
        if ellipse.h0 < 0.0 {
            return true;
        }
        let (height, pad) = (u32::from(self.height), u32::from(self.pad));
        let rows = if pad == 0 {
            sil.rows(height)
        } else {
            let reach = (sil.reach_consts().0 + pad as f32 + 0.5) * (1.0 + 1.0 / 65536.0) + 1.0;
            let y0 = ellipse.y0i + ellipse.y0f;
            let (a, b) = (libm::floorf(y0 - reach), libm::ceilf(y0 + reach) + 1.0);
            // Clamped by comparisons: a NaN end is the image's.
            let a = if a > 0.0 { a.min(height as f32) as u32 } else { 0 };
            let b = if b < height as f32 {
                b.max(0.0) as u32
            } else {
                height
            };
            (a, b)
        };
        self.push(Region::Ellipse(sil), rows)
    }

    /// Adds the pixels adaptive sampling's shared samples mark around a small
    /// silhouette (`b`, the box `sampling::small_box` gives, image coordinates).
    ///
    /// Those are the pixels whose footprint `[i ± ½] × [j ± ½]` meets the box
    /// (`mark_small`); a pixel more each way covers the rounding of those comparisons.
    /// A NaN edge reaches the image's edge there, as it marks up to it. `false` if one
    /// region too many.
    pub(super) fn push_box(&mut self, b: [f32; 4]) -> bool {
        let (width, height) = (f32::from(self.width), f32::from(self.height));
        // Clamped by comparisons: a NaN end is the image's.
        let lo = |v: f32, max: f32| {
            let v = libm::floorf(v - 1.5);
            if v > 0.0 {
                v.min(max) as u32
            } else {
                0
            }
        };
        let hi = |v: f32, max: f32| {
            let v = libm::ceilf(v + 1.5) + 1.0;
            if v < max {
                v.max(0.0) as u32
            } else {
                max as u32
            }
        };
        let (x0, x1) = (lo(b[0], width), hi(b[1], width));
        let (y0, y1) = (lo(b[2], height), hi(b[3], height));
        x0 >= x1 || y0 >= y1 || self.push_area(Area::new(x0, y0, x1, y1))
    }

    /// Adds the integer kernel's cut of a sphere's rows `rows`; `false` if one region
    /// too many.
    pub(super) fn push_cut(&mut self, rows: (u32, u32), cut: IntCut) -> bool {
        let height = u32::from(self.height);
        let (j0, j1) = (rows.0.min(height), rows.1.min(height));
        if cut == IntCut::All {
            // Every column of its rows.
            return j0 >= j1 || self.push_area(Area::new(0, j0, u32::from(self.width), j1));
        }
        self.push(Region::Int(cut), (j0, j1))
    }

    /// Adds a rectangle of the image (rule step 4); `false` if one region too many.
    pub(super) fn push_rect(&mut self, r: Rectangle) -> bool {
        r.is_zero_sized() || self.push_area(Area::of(r))
    }

    fn push_area(&mut self, bbox: Area) -> bool {
        self.regions
            .push(Entry {
                region: Region::Rect,
                bbox,
                waste: 0,
                rect: 0,
            })
            .is_ok()
    }

    /// Adds a region whose runs lie in rows `j0..j1`, with its bounding box (none if it
    /// has no run: off the image); `false` if one region too many.
    fn push(&mut self, region: Region, (j0, j1): (u32, u32)) -> bool {
        let (width, pad) = self.row_consts();
        let (mut x0, mut x1, mut y0, mut y1) = (u32::MAX, 0, u32::MAX, 0);
        let (mut covered, mut gap) = (0, false);
        for j in j0..j1 {
            if let Some((lo, hi)) = region.cut(j, width, pad) {
                // A row without a run lies between this one and the last with one.
                gap |= y0 != u32::MAX && y1 != j;
                x0 = x0.min(lo);
                x1 = x1.max(hi);
                y0 = y0.min(j);
                y1 = j + 1;
                covered += hi - lo;
            }
        }
        if x0 >= x1 {
            return true;
        }
        let bbox = Area::new(x0, y0, x1, y1);
        let waste = if gap {
            u16::MAX
        } else {
            u16::try_from(bbox.pixels() - covered).unwrap_or(u16::MAX)
        };
        self.regions
            .push(Entry {
                region,
                bbox,
                waste,
                rect: 0,
            })
            .is_ok()
    }

    /// The traced rectangles: the regions' boxes, those that overlap or abut in a row
    /// merged into one, until none does (runs of one rectangle that touch are one
    /// window, `Changes::runs`); then each region's rectangle, and the strips.
    pub(super) fn merge(&mut self) {
        self.rects.clear();
        for e in &self.regions {
            let _ = self.rects.push(e.bbox);
        }
        let mut merged = true;
        while merged {
            merged = false;
            'outer: for a in 0..self.rects.len() {
                for b in a + 1..self.rects.len() {
                    let (Some(&ra), Some(&rb)) = (self.rects.get(a), self.rects.get(b)) else {
                        continue;
                    };
                    if ra.meets(rb) || ra.abuts(rb) {
                        if let Some(slot) = self.rects.get_mut(a) {
                            *slot = ra.bounding(rb);
                        }
                        self.rects.swap_remove(b);
                        merged = true;
                        break 'outer;
                    }
                }
            }
        }
        // The rectangles are disjoint: a box meets only the one holding it.
        for e in &mut self.regions {
            e.rect = self.rects.iter().position(|r| r.meets(e.bbox)).unwrap_or(0) as u8;
        }
        self.strips.clear();
        for r in 0..self.rects.len() {
            if !self.cut_strips(r) {
                // Too many strips: each rectangle whole.
                self.strips.clear();
                for &rect in &self.rects {
                    let _ = self.strips.push(rect);
                }
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::incremental::MAX_REGIONS;

    fn rect(x: i32, y: i32, w: u32, h: u32) -> Rectangle {
        Rectangle::new(Point::new(x, y), Size::new(w, h))
    }

    #[test]
    fn an_area_is_a_rectangle_of_the_image() {
        let a = Area::of(rect(2, 3, 4, 5));
        assert_eq!((a.cols(), a.rows(), a.pixels()), ((2, 6), (3, 8), 20));
        assert_eq!(a.rect(), rect(2, 3, 4, 5));
        assert!(a.has_row(3) && a.has_row(7) && !a.has_row(8));
        assert_eq!(edge(70_000), u16::MAX);
    }

    #[test]
    fn areas_that_touch_do_not_meet() {
        let a = Area::new(0, 0, 2, 2);
        assert!(!a.meets(Area::new(2, 0, 4, 2)));
        assert!(!a.meets(Area::new(0, 2, 2, 4)));
        assert!(a.meets(Area::new(1, 1, 3, 3)));
        assert_eq!(a.bounding(Area::new(3, 1, 4, 5)), Area::new(0, 0, 4, 5));
    }

    #[test]
    fn overlapping_boxes_merge_into_one_rectangle() {
        let mut plan = Changes::empty(Size::new(20, 10), 16, 0);
        assert!(plan.push_rect(rect(1, 1, 3, 3)));
        assert!(plan.push_rect(rect(15, 5, 2, 2)));
        assert!(plan.push_rect(rect(2, 2, 3, 3)));
        // An empty rectangle is no region.
        assert!(plan.push_rect(rect(0, 0, 0, 4)));
        plan.merge();
        assert_eq!(plan.rects.len(), 2);
        assert!(plan.rects.contains(&Area::new(1, 1, 5, 5)));
        assert!(plan.rects.contains(&Area::new(15, 5, 17, 7)));
        // Each region knows the rectangle that holds its box.
        for e in &plan.regions {
            assert!(plan.rects[usize::from(e.rect)].meets(e.bbox));
        }
    }

    #[test]
    fn one_region_too_many_is_refused() {
        let mut plan = Changes::empty(Size::new(64, 8), 16, 0);
        for k in 0..MAX_REGIONS as i32 {
            assert!(plan.push_rect(rect(5 * k, 0, 2, 2)));
        }
        assert!(!plan.push_rect(rect(0, 4, 2, 2)));
    }
}
