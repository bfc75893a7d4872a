//! Anti-aliasing: how many rays a pixel gets, chosen once per frame like the method.
//!
//! - [`Sampling::Center`] (default): one ray through the pixel centre — the row loop of
//!   `scanline.rs`, untouched.
//! - [`Sampling::Grid`]`(n)`: `n × n` rays at offsets `((a + ½)/n − ½, (b + ½)/n − ½)`
//!   pixel widths and heights from the centre along `u` and `−v`, averaged (box filter).
//! - [`Sampling::Adaptive`]`(n)`: exactly `Grid(n)`'s rays in edge pixels, the centre
//!   ray alone elsewhere.
//!
//! **Averaging in linear light.** Every ray's colour is the 8-bit colour the row
//! tracer rounds once; it is decoded to linear light by a table (IEC 61966-2-1, built
//! by `build.rs`: `round(65535·L)`), the `n²` values are summed in integers, and the
//! sum is encoded by comparing it with the 255 linear thresholds where the encoded
//! value is exactly `k + ½` levels (a bucket table picks the one threshold to compare
//! with): rounding to nearest, once, with no `powf` in the pixel loop. Decoding
//! rounded samples instead of averaging the unrounded ones moves the result by at
//! most one level (the unit test `rounded_samples_within_one_level` measures it over
//! random sample sets: see its output).
//!
//! **Sub-pixel directions** are formed directly from the camera's per-frame steps
//! (`F` the upper-left pixel's direction, `du`, `dv` the column and row steps), for
//! every stepping: `d = (F + dv·y) + du·x` with `x = i + o_a`, `y = j + o_b`. Error
//! bound: the offset `o` (exact for `n` = 2 and 4, one rounding of `≤ 2⁻²⁵` for 3) and
//! `i + o` round by at most `2⁻²⁴·(|i| + 1)`, moving `d` by `≤ 2⁻²⁴·S`; the two products
//! and two sums round by `≤ 4·2⁻²⁴·S` (`S = |F| + H·|dv| + W·|du|` as in `stepping.rs`):
//! `|d − ideal| ≤ 2⁻²³·3·S`, within `Stepping::Direct`'s bound. The sphere test is the
//! method's single-ray test (`TestStrategy::ray`, what secondary rays use: the
//! forward-differenced test's row state belongs to the centre rays), tested against
//! every sphere and plane (a row's spans hold for its centre line only).
//!
//! **Edge pixels** (`Adaptive`) of a Lab #1 scene (spheres only), from the silhouettes
//! alone, per row (`SpanAdaptiveRows`): once per frame each sphere gets two ellipses,
//! its silhouette enlarged and shrunk by the test's rounding margin and the larger of
//! the stepping's and the sub-pixel rays' direction errors (`span.rs`); once per row,
//! the columns whose sub-sample square `[i ± h] × [j ± h]`, `h = (n − 1)/(2n)`, reaches
//! the enlarged one but is not inside the shrunk one are its edge columns. So every
//! pixel whose samples may see two different things (a sphere and the background, or
//! two spheres: between spheres that do not touch the one in front never changes) is
//! an edge pixel, however small the sphere; `lab/tests/lab/sampling.rs` checks it sample by
//! sample. Edge columns hidden by a sphere in front that all the samples hit are
//! dropped. A second ring per sphere marks pixels where the centre's Lab #1 shade is
//! not a fair stand-in for the mean (the `0.3` floor's kink, and steep shading on small
//! spheres; [`SHADE_TOLERANCE`]) — a heuristic the quality tables measure. A frame the
//! silhouettes cannot decide — a sphere reaching the eye's plane (one wholly behind
//! the eye cannot be hit and is left out), two spheres closer than a small gap, a fast
//! square root — uses the shared samples below. This path keeps no row buffer: its
//! cost is the centre row plus a few interval comparisons per row, and it has no
//! width limit.
//!
//! **Edge pixels** of a scene with lights, planes or mirrors (`AdaptiveRows`),
//! conservatively:
//! - *shared samples*: every centre ray is traced once, with an identity (what decides
//!   its colour discontinuously: the object; in the features path also the checker
//!   cell, which lights reach the point, what each reflected ray hit). A pixel whose
//!   identity differs from one of its eight neighbours' is an edge pixel, and so is
//!   that neighbour: any boundary between two centres is found on both sides of it.
//!   Neighbours whose centre colours differ by more than [`CONTRAST`] levels are
//!   marked the same way: where shading changes that fast across a pixel (a sphere's
//!   rim, a highlight), its mean is not its centre's colour.
//!   The identities are kept for two rows (a fixed buffer of [`ADAPTIVE_MAX_WIDTH`]
//!   columns: 16-bit identities, centre colours and edge bits, 2,624 bytes), so each
//!   row is emitted one row after it is traced; a clipped render traces the one-pixel
//!   ring around the clip too, so a pixel never depends on the clip.
//! - *detail finer than the pixels*: a centre ray that meets a checkered plane where
//!   the pixel's footprint on it is more than half a cell wide (the cells alias: the
//!   centres can agree by chance) makes its pixel an edge pixel.
//! - *small silhouettes*: a sphere whose silhouette (its culling ellipse) has a
//!   semi-minor axis under [`SMALL`] pixels may hold no pixel centre at all; every pixel
//!   whose footprint meets its bounding box, widened by one pixel, is an edge pixel.
//!
//! What the shared-sample rule can miss: a feature narrower than the spacing of the pixel centres
//! that falls between them (the tip of a thin silhouette, a shadow or checker sliver,
//! a small object seen in a mirror) where no centre in the 3×3 neighbourhood sees it;
//! and two identities that collide in 16 bits (one in 65,536). The README's
//! "Anti-aliasing" section measures how often Adaptive(4) differs from Grid(4).

use core::fmt;
use core::str::FromStr;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::trace::frame::{Frame, FrameSphere};
use crate::trace::options::Sample;
use crate::trace::rows::{Rows, FINE};
use crate::trace::scanline::RowSink;
use crate::trace::scanline::{self, ColorRuns, PixelRow, RowPixels, RowTracer};
use crate::trace::shade::Shader;

include!(concat!(env!("OUT_DIR"), "/srgb_tables.rs"));

/// Rays per pixel: one at the centre, a grid, or a grid only where an edge can cross
/// the pixel (`src/sampling/mod.rs` documents how the edges are found and each rule's
/// error bound).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Sampling {
    /// One ray through the pixel centre.
    #[default]
    Center,
    /// `n × n` rays in every pixel, averaged in linear light.
    Grid(SubSamples),
    /// `n × n` rays where an edge can cross the pixel, the centre ray elsewhere.
    Adaptive(SubSamples),
}

/// The `n` of an `n × n` grid: 2, 3 or 4 (checked by [`SubSamples::new`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SubSamples(u8);

impl SubSamples {
    /// `n × n` sub-samples.
    ///
    /// # Errors
    ///
    /// [`SamplingError::SubSamples`] unless `n` is 2, 3 or 4.
    pub const fn new(n: u32) -> Result<Self, SamplingError> {
        if n >= 2 && n <= 4 {
            Ok(Self(n as u8))
        } else {
            Err(SamplingError::SubSamples(n))
        }
    }

    /// `n`.
    #[must_use]
    pub const fn get(self) -> u32 {
        self.0 as u32
    }
}

impl Sampling {
    /// [`Sampling::Grid`] with `n × n` rays.
    ///
    /// # Errors
    ///
    /// [`SamplingError::SubSamples`] unless `n` is 2, 3 or 4.
    pub const fn grid(n: u32) -> Result<Self, SamplingError> {
        match SubSamples::new(n) {
            Ok(n) => Ok(Sampling::Grid(n)),
            Err(e) => Err(e),
        }
    }

    /// [`Sampling::Adaptive`] with `n × n` rays in edge pixels.
    ///
    /// # Errors
    ///
    /// [`SamplingError::SubSamples`] unless `n` is 2, 3 or 4.
    pub const fn adaptive(n: u32) -> Result<Self, SamplingError> {
        match SubSamples::new(n) {
            Ok(n) => Ok(Sampling::Adaptive(n)),
            Err(e) => Err(e),
        }
    }

    /// Every choice the renderer offers, for tests and tables.
    pub const ALL: [Sampling; 7] = [
        Sampling::Center,
        Sampling::Grid(SubSamples(2)),
        Sampling::Grid(SubSamples(3)),
        Sampling::Grid(SubSamples(4)),
        Sampling::Adaptive(SubSamples(2)),
        Sampling::Adaptive(SubSamples(3)),
        Sampling::Adaptive(SubSamples(4)),
    ];
}

/// Why a sampling choice was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SamplingError {
    /// The grid is `n × n` with `n` = 2…4; this `n` is outside.
    SubSamples(u32),
    /// Not `center`, `grid:N` or `adaptive:N`.
    Syntax,
}

impl fmt::Display for SamplingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SamplingError::SubSamples(n) => write!(f, "sub-samples per axis must be 2, 3 or 4, not {n}"),
            SamplingError::Syntax => f.write_str("expected center, grid:N or adaptive:N (N = 2, 3, 4)"),
        }
    }
}

impl core::error::Error for SamplingError {}

impl fmt::Display for Sampling {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Sampling::Center => f.write_str("center"),
            Sampling::Grid(n) => write!(f, "grid:{}", n.get()),
            Sampling::Adaptive(n) => write!(f, "adaptive:{}", n.get()),
        }
    }
}

impl FromStr for Sampling {
    type Err = SamplingError;

    /// `center`, `grid:N` or `adaptive:N`, as [`Display`](fmt::Display) writes them.
    fn from_str(s: &str) -> Result<Self, SamplingError> {
        if s == "center" {
            return Ok(Sampling::Center);
        }
        let (kind, n) = s.split_once(':').ok_or(SamplingError::Syntax)?;
        let n: u32 = n.parse().map_err(|_| SamplingError::Syntax)?;
        match kind {
            "grid" => Sampling::grid(n),
            "adaptive" => Sampling::adaptive(n),
            _ => Err(SamplingError::Syntax),
        }
    }
}

/// The widest image `Adaptive` keeps its two rows of shared samples for (scenes with
/// features, and Lab #1 frames the silhouettes cannot decide); there, a wider image's
/// pixels are all edge pixels (`Grid(n)`'s). A Lab #1 frame decided by its silhouettes
/// has no width limit.
pub const ADAPTIVE_MAX_WIDTH: usize = 256;

/// Silhouettes whose semi-minor axis (lower bound, pixels) is under this may hold no
/// pixel centre: all their pixels are edge pixels. An ellipse with a semi-minor axis of
/// `√2/2` or more holds a pixel centre; 2 leaves room for the culling ellipse's
/// enlargement.
pub const SMALL: f32 = 2.0;

/// Neighbouring centre colours further apart than this (levels, any channel) make
/// both pixels edge pixels: where shading changes this fast (a sphere's rim, a
/// highlight) the pixel's mean is not its centre's colour.
pub const CONTRAST: u8 = 16;

/// [`Sampling::Grid`]`(n)`: every pixel averaged.
#[derive(Clone, Copy)]
pub(crate) struct GridRows(pub u32);

impl Rows for GridRows {
    const CENTER: bool = false;
    #[inline(always)]
    fn clip(&self, clip: Rectangle) -> Rectangle {
        clip
    }

    // Out of line: the one-ray path's callers do not carry its frame (the adaptive
    // rows' buffers) on their stack.
    #[inline(never)]
    fn draw_rows<'s, const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X>(
        self,
        frame: &Frame<'s, T, Sh>,
        sink: &mut K,
        mut tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
    ) -> Result<(), K::Error>
    where
        X: RowTracer<'s, T, Sh>,
    {
        let steps = SubSteps::new(frame, self.0);
        for j in frame.j0..frame.j1 {
            let (mut lo, mut hi) = (frame.i1, frame.i0);
            let mut tracer = tracer(j, &mut lo, &mut hi);
            let row = SampledRow::<T, Q, Sh, X> {
                spheres: frame.spheres,
                tracer: &mut tracer,
                steps: &steps,
                stored: None,
                i: frame.i0,
                end: frame.i1,
                j,
                background: frame.background,
                sqrt: core::marker::PhantomData,
            };
            sink.row(row_area(frame, frame.i0, frame.i1, j), row)?;
        }
        Ok(())
    }
}

/// [`Sampling::Adaptive`]`(n)`; `clip` is the render's own (the frame traces the ring
/// around it).
#[derive(Clone, Copy)]
pub(crate) struct AdaptiveRows {
    pub n: u32,
    pub clip: Rectangle,
}

/// One row of adaptive sampling's shared samples.
struct RowBuf {
    colors: [Rgb888; ADAPTIVE_MAX_WIDTH],
    ids: [u16; ADAPTIVE_MAX_WIDTH],
    edges: [u32; ADAPTIVE_MAX_WIDTH / 32],
}

impl RowBuf {
    const EMPTY: RowBuf = RowBuf {
        colors: [Rgb888::BLACK; ADAPTIVE_MAX_WIDTH],
        ids: [0; ADAPTIVE_MAX_WIDTH],
        edges: [0; ADAPTIVE_MAX_WIDTH / 32],
    };

    #[inline(always)]
    fn mark(&mut self, k: usize) {
        if let Some(w) = self.edges.get_mut(k / 32) {
            *w |= 1 << (k % 32);
        }
    }
}

/// Whether pixels `k` of `a` and `m` of `b` (both in range) disagree: on their
/// identity, or on a colour channel by more than [`CONTRAST`] levels.
#[inline(always)]
fn differ(a: &RowBuf, k: usize, b: &RowBuf, m: usize) -> bool {
    match ((a.ids.get(k), a.colors.get(k)), (b.ids.get(m), b.colors.get(m))) {
        ((Some(x), Some(p)), (Some(y), Some(q))) => {
            x != y
                || p.r().abs_diff(q.r()) > CONTRAST
                || p.g().abs_diff(q.g()) > CONTRAST
                || p.b().abs_diff(q.b()) > CONTRAST
        }
        _ => false,
    }
}

impl Rows for AdaptiveRows {
    const CENTER: bool = false;
    #[inline(always)]
    fn clip(&self, clip: Rectangle) -> Rectangle {
        // One pixel more on every side: the neighbours' shared samples.
        // Saturating: a clip at the coordinates' edge keeps a ring on its other sides
        // (an extra traced column or row is harmless, only the clip is drawn).
        Rectangle::new(
            Point::new(
                clip.top_left.x.saturating_sub(1),
                clip.top_left.y.saturating_sub(1),
            ),
            Size::new(
                clip.size.width.saturating_add(2),
                clip.size.height.saturating_add(2),
            ),
        )
    }

    // Out of line: the one-ray path's callers do not carry its frame (the adaptive
    // rows' buffers) on their stack.
    #[inline(never)]
    fn draw_rows<'s, const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X>(
        self,
        frame: &Frame<'s, T, Sh>,
        sink: &mut K,
        mut tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
    ) -> Result<(), K::Error>
    where
        X: RowTracer<'s, T, Sh>,
    {
        let Some(((ri0, ri1), (rj0, rj1))) = own_area(frame, self.clip) else {
            return Ok(());
        };
        let steps = SubSteps::new(frame, self.n);
        let width = (frame.i1 - frame.i0) as usize;
        let small = small_silhouettes::<N, T, Sh>(frame);
        let mut stepper = S::new(frame.camera);
        let mut active: Vec<_, N> = Vec::new();
        let (mut buf_a, mut buf_b) = (RowBuf::EMPTY, RowBuf::EMPTY);
        let (mut cur, mut prev) = (&mut buf_a, &mut buf_b);
        // From the image's width, not the traced one: a clip must not switch an image
        // between the adaptive rule and the grid.
        let wide = frame.camera.size().width as usize > ADAPTIVE_MAX_WIDTH;
        for j in frame.j0..frame.j1 {
            let row_step = stepper.start_row(j, frame.i0);
            let (mut lo, mut hi) = scanline::activate(frame, &mut stepper, j, &mut active);
            let tracer = tracer(j, &mut lo, &mut hi);
            let mut row = RowPixels::<S, T, Q, Sh, X>::new(frame, row_step, &mut active, (lo, hi), tracer, j);
            if !wide {
                // The centre rays, once: colours and identities.
                cur.edges = [0; ADAPTIVE_MAX_WIDTH / 32];
                for k in 0..width {
                    let (h, c) = row.next_identified();
                    if h == FINE {
                        cur.mark(k);
                    }
                    if let (Some(color), Some(id)) = (cur.colors.get_mut(k), cur.ids.get_mut(k)) {
                        *color = c;
                        *id = (h ^ (h >> 16)) as u16;
                    }
                }
                // Compare with the left neighbour and the three above; mark both sides.
                for k in 0..width {
                    if k > 0 && differ(cur, k, cur, k - 1) {
                        cur.mark(k);
                        cur.mark(k - 1);
                    }
                    if j > frame.j0 {
                        // Only columns that exist: past the row's end the buffer holds
                        // no pixel.
                        for m in [k.wrapping_sub(1), k, k + 1] {
                            if m < width && differ(cur, k, prev, m) {
                                cur.mark(k);
                                prev.mark(m);
                            }
                        }
                    }
                }
            }
            // Row j − 1 has all its neighbours now; the last row has no row below.
            let mut emit = |buf: &mut RowBuf, r: u32, tracer: &mut X| {
                if !(rj0..rj1).contains(&r) {
                    return Ok(());
                }
                mark_small(buf, &small, frame.i0, r);
                let row = SampledRow::<T, Q, Sh, X> {
                    spheres: frame.spheres,
                    tracer,
                    steps: &steps,
                    stored: (!wide).then_some((buf.colors.as_slice(), buf.edges.as_slice(), frame.i0)),
                    i: ri0,
                    end: ri1,
                    j: r,
                    background: frame.background,
                    sqrt: core::marker::PhantomData,
                };
                sink.row(row_area(frame, ri0, ri1, r), row)
            };
            if j > frame.j0 {
                emit(prev, j - 1, row.tracer_mut())?;
            }
            if j + 1 == frame.j1 {
                emit(cur, j, row.tracer_mut())?;
            }
            drop(row);
            core::mem::swap(&mut cur, &mut prev);
        }
        Ok(())
    }
}

/// [`Sampling::Adaptive`]`(n)` for scenes whose colours jump only at sphere
/// silhouettes (Lab #1 on spheres): the edge pixels come from the silhouettes alone,
/// per row, and no sample is shared between pixels (see [`SpanBands`]). A frame where
/// that cannot be proven (a silhouette that is not a bounded ellipse, two spheres that
/// touch, a fast square root) is drawn by [`AdaptiveRows`]' shared samples; `clip` is
/// the render's own, and the frame is ringed for that case.
#[derive(Clone, Copy)]
pub(crate) struct SpanAdaptiveRows {
    pub n: u32,
    pub clip: Rectangle,
}

/// A ring on the image between two ellipses: `outer` contains it, `inner` (`None`:
/// empty) is cut out of it.
#[derive(Clone, Copy)]
struct Ring {
    outer: crate::camera::span::Silhouette,
    inner: Option<crate::camera::span::Silhouette>,
    /// The outer ellipse's [`Silhouette::reach_consts`](crate::camera::span::Silhouette::reach_consts).
    reach: (f32, f32),
}

impl Ring {
    fn new(outer: crate::camera::span::Silhouette, inner: Option<crate::camera::span::Silhouette>) -> Self {
        Self {
            outer,
            inner,
            reach: outer.reach_consts(),
        }
    }

    /// Row `j`'s columns `i` whose segment `[i − h, i + h] × [j − h, j + h]` meets the
    /// outer ellipse (`lo..hi`) and, within them, those whose segment lies inside the
    /// inner one (`in_lo..in_hi`, empty as `hi..hi`); clamped to `f0..f1`. `None` if
    /// the outer one is out of reach.
    #[inline(always)]
    fn columns(&self, j: u32, h: f32, (f0, f1): (f32, f32)) -> Option<[u32; 4]> {
        // The columns `⌈a⌉ ..= ⌊b⌋` of the frame, `None` if none: an interval that
        // ends left of the frame or starts right of it is empty (clamping it first
        // would make it the border column). Clamped, then rounded by conversion (the
        // bounds are integers, so the two commute; the values are in [0, 2¹³]).
        let columns = |a: f32, b: f32| -> Option<(u32, u32)> {
            if !(b >= f0 && a < f1 && a <= b) {
                return None;
            }
            let a = crate::math::max(a, f0);
            let t = a as u32;
            let lo = t + u32::from((t as f32) < a);
            let hi = (crate::math::min(b, f1) as u32 + 1).min(f1 as u32);
            (lo < hi).then_some((lo, hi))
        };
        let (x0, x1) = self.outer.band_reach(j, h, self.reach)?;
        // [i − h, i + h] meets [x0, x1]: i in [x0 − h, x1 + h].
        let (lo, hi) = columns(x0 - h, x1 + h)?;
        // [i − h, i + h] inside [x0, x1]: i in [x0 + h, x1 − h].
        let (in_lo, in_hi) = self
            .inner
            .and_then(|s| s.band_inside(j, h))
            .and_then(|(x0, x1)| columns(x0 + h, x1 - h))
            .map(|(a, z)| (a.max(lo), z.min(hi)))
            .filter(|(a, z)| a < z)
            .unwrap_or((hi, hi));
        Some([lo, hi, in_lo, in_hi])
    }
}

/// Per frame, per sphere: the ring between where sub-pixel and centre rays can hit it
/// and where they all do (the silhouette's edge), and the ring where the centre's
/// Lab #1 shade may be more than [`SHADE_TOLERANCE`] from the pixel's mean.
struct SpanBands {
    /// `None`: a sphere wholly behind the eye, which no ray hits.
    silhouette: Option<Ring>,
    shade: Option<Ring>,
}

/// Per row: a sphere some ray of the row's pixels can hit (`lo..hi`: the columns
/// whose samples can hit it), and the row's edge columns for it: four intervals (the
/// silhouette's ring on either side, the shading ring on either side), empty ones as
/// `(x, x)`.
struct Band<'s, T: TestStrategy, Sh: Shader> {
    index: usize,
    sphere: &'s FrameSphere<T, Sh>,
    lo: u32,
    hi: u32,
    /// The columns whose samples all hit it.
    inside: (u32, u32),
    edges: [(u32, u32); 4],
}

/// A row's edge columns as runs `[lo, hi)` in increasing order, disjoint and not
/// touching: the union of the bands' edge intervals (`edges`, four per band, empty
/// ones as `(x, x)`), sorted and merged once per row so that each pixel pays one
/// comparison. Built in `runs`; returns how many of its intervals (flattened, from
/// the first) are runs.
fn edge_runs<const N: usize>(
    edges: impl Iterator<Item = [(u32, u32); 4]>,
    runs: &mut Vec<[(u32, u32); 4], N>,
) -> usize {
    runs.clear();
    for e in edges {
        // Never fails: one per band, at most one band per sphere.
        let _ = runs.push(e);
    }
    let all = runs.as_flattened_mut();
    // The non-empty intervals to the front, sorted by their start: an insertion sort
    // (a few dozen at most, mostly in order already). Slots before `k` are free once
    // read, so the sorted prefix (`m ≤ k`) may grow into them.
    let mut m: usize = 0;
    for k in 0..all.len() {
        let Some(&e) = all.get(k) else { break };
        if e.0 >= e.1 {
            continue;
        }
        let mut p = m;
        while let Some(&before) = p.checked_sub(1).and_then(|q| all.get(q)) {
            if before.0 <= e.0 {
                break;
            }
            if let Some(slot) = all.get_mut(p) {
                *slot = before;
            }
            p -= 1;
        }
        if let Some(slot) = all.get_mut(p) {
            *slot = e;
        }
        m += 1;
    }
    // Merge where they overlap or touch.
    let mut out: usize = 0;
    for k in 0..m {
        let Some(&(a, z)) = all.get(k) else { break };
        if let Some(last) = out.checked_sub(1).and_then(|q| all.get_mut(q)) {
            if a <= last.1 {
                last.1 = last.1.max(z);
                continue;
            }
        }
        if let Some(slot) = all.get_mut(out) {
            *slot = (a, z);
        }
        out += 1;
    }
    out
}

impl Rows for SpanAdaptiveRows {
    const CENTER: bool = false;
    #[inline(always)]
    fn clip(&self, clip: Rectangle) -> Rectangle {
        // The ring the shared samples need if the frame falls back to them.
        AdaptiveRows { n: self.n, clip }.clip(clip)
    }

    // Out of line: the one-ray path's callers do not carry its frame on their stack.
    #[inline(never)]
    fn draw_rows<'s, const N: usize, K: RowSink, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X>(
        self,
        frame: &Frame<'s, T, Sh>,
        sink: &mut K,
        mut tracer: impl FnMut(u32, &mut u32, &mut u32) -> X,
    ) -> Result<(), K::Error>
    where
        X: RowTracer<'s, T, Sh>,
    {
        // A fast square root moves hits and their order by up to 6 %: nothing the
        // silhouettes' margins cover.
        let sils = if Q::EXACT {
            span_bands::<N, S, T, Sh>(frame)
        } else {
            None
        };
        let Some(sils) = sils else {
            let rows = AdaptiveRows {
                n: self.n,
                clip: self.clip,
            };
            return rows.draw_rows::<N, K, S, T, Q, Sh, X>(frame, sink, tracer);
        };
        // The render's own columns and rows inside the ringed frame.
        let Some(((ri0, ri1), (rj0, rj1))) = own_area(frame, self.clip) else {
            return Ok(());
        };
        let steps = SubSteps::new(frame, self.n);
        // Half the extent of the sub-sample grid, `(n − 1)/(2n)` pixels, widened for
        // the rounding of `i + o` (≤ 2⁻²⁴·(|i| + 1), below 2⁻¹¹ for i < 2¹³).
        let half = (self.n - 1) as f32 / (2 * self.n) as f32 + 1.0 / 2048.0;
        let mut stepper = S::new(frame.camera);
        let mut active: Vec<_, N> = Vec::new();
        let mut bands: Vec<Band<'s, T, Sh>, N> = Vec::new();
        let mut runs: Vec<[(u32, u32); 4], N> = Vec::new();
        for j in rj0..rj1 {
            let row_step = stepper.start_row(j, frame.i0);
            let (mut lo, mut hi) = scanline::activate(frame, &mut stepper, j, &mut active);
            let tracer = tracer(j, &mut lo, &mut hi);
            let mut row = RowPixels::<S, T, Q, Sh, X>::new(frame, row_step, &mut active, (lo, hi), tracer, j);
            // The ring's column on the left: traced, not drawn (a test's row state
            // expects every column of its span).
            for _ in frame.i0..ri0 {
                row.next_color();
            }
            row_bands(frame, &sils, j, half, &mut bands);
            let count = edge_runs(bands.iter().map(|b| b.edges), &mut runs);
            let mut span_row = SpanRow::<N, S, T, Q, Sh, X> {
                row,
                bands: &bands,
                steps: &steps,
                runs: runs.as_flattened().get(..count).unwrap_or_default(),
                next: 0,
                edge: (u32::MAX, u32::MAX),
                i: ri0,
                end: ri1,
                j,
            };
            span_row.next_run(ri0);
            sink.row(row_area(frame, ri0, ri1, j), span_row)?;
        }
        Ok(())
    }
}

/// How far (8-bit levels) the Lab #1 shade at a pixel's centre may be from the mean
/// of its sub-samples before the pixel is an edge pixel (the error model is in the
/// source, at `shade_ring`).
pub const SHADE_TOLERANCE: f32 = 1.5;

/// Every sphere's [`SpanBands`] for the frame: silhouettes enlarged and shrunk by the
/// test's margin and the larger of the stepping's and the sub-pixel rays' direction
/// error (`Stepping::Direct`'s bound covers the latter: module docs).
///
/// A sphere wholly behind the eye ([`behind_the_eye`]) has no ring: no ray hits it.
///
/// `None` when the silhouettes alone cannot find the edges: a silhouette that is not
/// a bounded ellipse (a sphere reaching the eye's plane), or two spheres (neither
/// behind the eye) closer than the sum of their radii plus
/// `g = 2⁻¹⁰·(|L₁| + |L₂|)` (where both can be hit, the one in front can change inside
/// a pixel). Between two other spheres a separating plane keeps the same one in front
/// along every ray through both (the eye is on one side of it), with a gap no `t`'s
/// rounding (`≲ 2⁻²⁰·|L|`) can close; and the eye's powers `|L|² − r²` (f32, error
/// `≲ 2⁻²³·|L|²`) order them wherever a ray can hit both (the eye is then at least
/// `g/2` from their radical plane, where the powers differ by at least `g²`).
#[inline(never)]
fn span_bands<const N: usize, S: Stepper, T: TestStrategy, Sh: Shader>(
    frame: &Frame<'_, T, Sh>,
) -> Option<Vec<SpanBands, N>> {
    use crate::camera::span::Silhouette;
    let camera = frame.camera;
    let step_err = S::error_bound(camera);
    let err = step_err.max(<crate::method::stepping::DirectStep as Stepper>::error_bound(
        camera,
    ));
    let mut out: Vec<SpanBands, N> = Vec::new();
    let w = camera.w();
    for (k, fs) in frame.spheres.iter().enumerate() {
        let g = &fs.geom;
        let r = crate::math::sqrt_exact(g.r2);
        if behind_the_eye(g, w) {
            // Never fails: one per sphere.
            let _ = out.push(SpanBands {
                silhouette: None,
                shade: None,
            });
            continue;
        }
        // Each pair once. The f32 distance's rounding (≲ 2⁻²²·(|L₁| + |L₂|)) is far
        // inside the gap asked for; NaN counts as touching.
        let touching = frame
            .spheres
            .iter()
            .skip(k + 1)
            .filter(|o| !behind_the_eye(&o.geom, w))
            .any(|other| {
                let o = &other.geom;
                let gap =
                    crate::math::sqrt_exact((g.l - o.l).dot(g.l - o.l)) - r - crate::math::sqrt_exact(o.r2);
                !(gap > (crate::math::sqrt_exact(g.l2) + crate::math::sqrt_exact(o.l2)) * (1.0 / 1024.0))
            });
        // The culling ellipse where it was built for the same error (the direct
        // stepping), saving its f64 work.
        let outer = if !fs.silhouette.is_all() && step_err >= err {
            fs.silhouette
        } else {
            Silhouette::new(g.l, r, camera, T::MARGIN, err)
        };
        if touching || outer.is_all() {
            return None;
        }
        // Never fails: one per sphere.
        let _ = out.push(SpanBands {
            silhouette: Some(Ring::new(
                outer,
                Silhouette::inner(g.l, r, camera, T::MARGIN, err),
            )),
            shade: shade_ring(g.l, r, camera, outer),
        });
    }
    Some(out)
}

/// Whether the sphere `g` lies wholly behind the eye, its nearest point at least
/// `2⁻⁸·(|L| + r)` behind the plane through the eye parallel to the image (`w` the
/// view direction): `L·w + r ≤ −2⁻⁸·(|L| + r)`, in f32 (`f32` rounding of `L·w`,
/// `|L|` and `r` is below `2⁻²⁰·(|L| + r)`, so a sphere passes only if it is behind
/// by more than `2⁻⁹·(|L| + r)`; NaN fails).
///
/// No ray of the frame hits it, in any test with the exact square root (the only
/// root this rule runs with: a fast root's 6 % can lift the slides' algebraic `√disc`
/// above `|b|`, and frames with it fall back): every primary and sub-pixel direction
/// has `d·w` equal to the focal distance (`du`, `dv` ⟂ `w`; the stepping's error is
/// far smaller), so a point at `t > 0` is in front of that plane and the exact roots
/// are negative. The computed ones keep their sign. With `m = 2⁻⁹·(|L| + r)`, the
/// eye's power is `c = |L|² − r² ≥ m·(|L| + r)` (`|L| ≥ r + m`) and, where the ray's
/// line meets the sphere, the roots' mean `b/a` (`b = L·d`, `a = d·d`) is behind by
/// `m/(d·w)`, so `−b ≥ m·|d|`: each is `2¹³` or more times its `f32` rounding (a
/// forward-differenced `b`, `2⁻²⁰` relative after 16 steps, too). With `b < 0` and
/// `c > 0` every test's roots are negative: `q/a` and `c/q` with `q = b − √disc < 0`
/// (robust, forward differences), `(b ± √disc)/a` with `√disc` below `|b|` by a
/// relative `c/(2|L|²) ≥ 2⁻¹⁰` (the slides' algebraic form), and the geometric test
/// stops at `L·d < 0`. The premise that the directions keep `d·w > 0` is the
/// stepping's error bound (below 10⁻² for any silhouette to be built at all). The
/// tests in `lab/tests/lab/sampling.rs` place spheres just past the margin, and one crossing
/// the eye's plane (not left out).
#[inline]
fn behind_the_eye(g: &crate::method::intersect::SphereGeom, w: crate::math::vec3::Vec3) -> bool {
    let r = crate::math::sqrt_exact(g.r2);
    let l = crate::math::sqrt_exact(g.l2);
    g.l.dot(w) + r <= -(l + r) * (1.0 / 256.0)
}

/// Where the centre's Lab #1 shade may be more than [`SHADE_TOLERANCE`] levels from
/// the mean of a pixel's sub-samples: hits whose `f = n·(−w)` lies in `[f_lo, f_hi]`,
/// as the ring of centres between the sphere of the points with `f ≥ f_lo` and the
/// one of the points with `f ≥ f_hi`.
///
/// The points of the sphere (centre `L`, radius `r`) with `n·(−w) ≥ f` lie in the
/// sphere of centre `L − r·f·w` and radius `r·√(1 − f²)` (their distance² to it is
/// `r²·(1 − 2f·n·(−w) + f²) ≤ r²·(1 − f²)`), so a centre ray outside its silhouette
/// hits at `f < f_lo`; a centre ray inside the silhouette of the `f_hi` one hits, for
/// all but the perspective's slight bulge, at `f ≥ f_hi` (a heuristic: the box
/// filter's error is not an edge, and the tables measure it).
///
/// The error model, for a silhouette of radius `R` pixels (its semi-minor axis) and a
/// channel of 255: the mean of the `n × n` samples (offset variance `5/64` px² for
/// `n` = 4) minus the centre is about `(5/128)·∇²c` plus the linear-light average's
/// `0.6·|∇c|²·(5/64)/c`, together `≲ 22/(f³·R²)` levels, below the tolerance where
/// `f³ ≥ 22/(tol·R²)`; the `f = 0.3` floor of Lab #1 is a kink whose slope
/// `s ≈ 255·3.2/R` levels per pixel moves the mean by up to `s/8` levels, more than the
/// tolerance within `¼ − 2·tol/s` pixels of it.
fn shade_ring(
    l: Vec3,
    r: f32,
    camera: &crate::camera::Camera,
    outer: crate::camera::span::Silhouette,
) -> Option<Ring> {
    use crate::camera::span::{Margin, Silhouette};
    let radius = outer.bounds()?.1.max(0.5);
    let tol = SHADE_TOLERANCE;
    let slope = 255.0 * 3.2 / radius;
    let kink = (0.25 - 2.0 * tol / slope).max(0.0) * 3.2 / radius;
    let smooth = libm::cbrtf(22.0 / (tol * radius * radius));
    let f_lo = if kink > 0.0 {
        crate::trace::shade::AMBIENT - kink
    } else {
        crate::trace::shade::AMBIENT
    };
    let f_hi = smooth.max(crate::trace::shade::AMBIENT + kink);
    if !(f_hi > f_lo) {
        return None;
    }
    let w = camera.w();
    let cap = |f: f32, side_outer: bool| {
        let f = f.clamp(0.0, 1.0);
        let (c, rho) = (l - w * (r * f), r * crate::math::sqrt_exact(1.0 - f * f));
        if side_outer {
            Some(Silhouette::new(c, rho, camera, Margin::Linear, 0.0))
        } else if f < 1.0 {
            Silhouette::inner(c, rho, camera, Margin::Linear, 0.0)
        } else {
            None
        }
    };
    Some(Ring::new(cap(f_lo, true)?, cap(f_hi, false)))
}

/// Row `j`'s [`Band`]s (in scene order) for sub-samples within `half` pixels of the
/// centres: columns whose samples can reach a sphere's outer silhouette, and its edge
/// columns: those of the silhouette's ring and, by their centres, the shading ring's.
#[inline(never)]
fn row_bands<'s, const N: usize, T: TestStrategy, Sh: Shader>(
    frame: &Frame<'s, T, Sh>,
    sils: &[SpanBands],
    j: u32,
    half: f32,
    bands: &mut Vec<Band<'s, T, Sh>, N>,
) {
    bands.clear();
    let frame_columns = (frame.i0 as f32, frame.i1 as f32);
    for (index, (sphere, sil)) in frame.spheres.iter().zip(sils).enumerate() {
        let Some([lo, hi, in_lo, in_hi]) = sil
            .silhouette
            .as_ref()
            .and_then(|ring| ring.columns(j, half, frame_columns))
        else {
            continue;
        };
        // The shading ring's columns within the sphere's (its cap sphere can look
        // wider than the sphere when the eye is near).
        let shade = sil
            .shade
            .as_ref()
            .and_then(|ring| ring.columns(j, 0.0, frame_columns))
            .map_or([hi; 4], |c| c.map(|x| x.clamp(lo, hi)));
        // Never fails: one per sphere.
        let _ = bands.push(Band {
            index,
            sphere,
            lo,
            hi,
            inside: (in_lo, in_hi),
            edges: [
                (lo, in_lo),
                (in_hi, hi),
                (shade[0], shade[2]),
                (shade[3], shade[1]),
            ],
        });
    }
    // A sphere's edges are hidden where every sample hits a sphere in front of it
    // (`c = |L|² − r²`, the eye's power, is smaller for the one in front: the radical
    // plane separates two spheres that do not touch, and a ray that hits both crosses
    // it from the eye's side); trimmed at the ends, the common case of a narrow edge.
    for k in 0..bands.len() {
        let Some(b) = bands.get(k) else { continue };
        let (c, mut edges) = (b.sphere.geom.c, b.edges);
        for front in bands.iter().filter(|f| f.sphere.geom.c < c) {
            let (a, z) = front.inside;
            for e in &mut edges {
                if a <= e.0 && e.0 < z {
                    e.0 = z.min(e.1);
                }
                if a < e.1 && e.1 <= z {
                    e.1 = a.max(e.0);
                }
            }
        }
        if let Some(b) = bands.get_mut(k) {
            b.edges = edges;
        }
    }
}

/// One row of [`SpanAdaptiveRows`]: the centre rays as the one-ray loop traces them,
/// and in edge columns the average of the sub-pixel rays, each tested against the
/// spheres whose band holds the column.
struct SpanRow<'a, 'r, 's, const N: usize, S: Stepper, T: TestStrategy, Q, Sh: Shader, X> {
    row: RowPixels<'r, 's, S, T, Q, Sh, X>,
    bands: &'a [Band<'s, T, Sh>],
    steps: &'a SubSteps,
    /// The row's runs of edge columns ([`edge_runs`]), the index of the next one not
    /// yet taken, and the current or next one.
    runs: &'a [(u32, u32)],
    next: usize,
    edge: (u32, u32),
    i: u32,
    end: u32,
    j: u32,
}

impl<'s, const N: usize, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>>
    SpanRow<'_, '_, 's, N, S, T, Q, Sh, X>
{
    /// Whether column `i` (columns come in increasing order) is an edge column: one
    /// comparison before the next run of edge columns.
    #[inline(always)]
    fn is_edge(&mut self, i: u32) -> bool {
        if i < self.edge.0 {
            return false;
        }
        if i >= self.edge.1 {
            self.next_run(i);
        }
        i >= self.edge.0
    }

    /// Takes the first run still reaching past column `from` (`(u32::MAX, u32::MAX)`
    /// if none), starting at `from` at the earliest.
    #[inline(always)]
    fn next_run(&mut self, from: u32) {
        while let Some(&(lo, hi)) = self.runs.get(self.next) {
            self.next += 1;
            if hi > from {
                self.edge = (lo.max(from), hi);
                return;
            }
        }
        self.edge = (u32::MAX, u32::MAX);
    }

    /// Column `i`'s `Grid(n)` average over the spheres whose band holds it.
    #[inline(never)]
    fn averaged(&mut self, i: u32) -> Rgb888 {
        // The spheres some sample of this pixel can hit, once for its n² rays.
        let mut cands: Vec<(usize, &'s FrameSphere<T, Sh>), N> = Vec::new();
        for b in self.bands.iter().filter(|b| i.wrapping_sub(b.lo) < b.hi - b.lo) {
            // Never fails: one per sphere.
            let _ = cands.push((b.index, b.sphere));
        }
        average::<T, Q, Sh, X>(
            cands.iter().copied(),
            self.row.tracer_mut(),
            self.steps,
            i,
            self.j,
        )
    }
}

impl<'s, const N: usize, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> Iterator
    for SpanRow<'_, '_, 's, N, S, T, Q, Sh, X>
{
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        let i = self.i;
        if i >= self.end {
            return None;
        }
        self.i += 1;
        // The centre ray always: a test's row state (forward differences) expects
        // every column of its span.
        let center = self.row.next_color();
        Some(if self.is_edge(i) { self.averaged(i) } else { center })
    }

    /// The same pixels as [`Self::next`], a run at a time: the centre-ray columns up
    /// to the next edge run without its per-pixel test, then the run's averages.
    #[inline(always)]
    fn fold<B, F: FnMut(B, Rgb888) -> B>(mut self, init: B, mut f: F) -> B {
        let mut acc = init;
        while self.i < self.end {
            let stop = self.edge.0.min(self.end);
            if self.i < stop {
                acc = centre_run(&mut self.row, stop - self.i, acc, &mut f);
                self.i = stop;
            }
            let stop = self.edge.1.min(self.end);
            while self.i < stop {
                let i = self.i;
                self.i += 1;
                // The centre ray too: a test's row state expects every column.
                let _ = self.row.next_color();
                acc = f(acc, self.averaged(i));
            }
            let i = self.i;
            self.next_run(i);
        }
        acc
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.i) as usize;
        (n, Some(n))
    }
}

impl<'s, const N: usize, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> PixelRow
    for SpanRow<'_, '_, 's, N, S, T, Q, Sh, X>
{
    /// Every pixel as a [`Sample`]: a centre-ray pixel as the one-ray loop gives it
    /// (with its hit), an edge pixel with its average, `n²` rays and no hit.
    fn samples(mut self) -> impl Iterator<Item = Sample> {
        let rays = (self.steps.n * self.steps.n) as u32;
        core::iter::from_fn(move || {
            let i = self.i;
            if i >= self.end {
                return None;
            }
            let mut sample = self.row.next()?;
            self.i += 1;
            if self.is_edge(i) {
                sample.color = self.averaged(i);
                sample.hit = None;
                sample.rays = rays;
            }
            Some(sample)
        })
    }

    fn color_runs(mut self) -> ColorRuns<impl Iterator<Item = Rgb888>> {
        // Background before and after both the spans' union and the edge columns.
        let spans = self.row.spans();
        let first = spans
            .map_or(self.end, |(lo, _)| lo)
            .min(self.edge.0)
            .min(self.end)
            .max(self.i);
        let last = spans
            .map_or(first, |(_, hi)| hi)
            .max(
                self.bands
                    .iter()
                    .filter(|b| b.lo < b.hi)
                    .map(|b| b.hi)
                    .max()
                    .unwrap_or(first),
            )
            .min(self.end)
            .max(first);
        let before = first - self.i;
        self.row.skip_columns(before);
        self.i = first;
        let after = self.end - last;
        self.end = last;
        ColorRuns {
            background: self.row.background(),
            before,
            traced_len: last - first,
            traced: self,
            after,
        }
    }
}

/// `n` centre-ray pixels of `row` into `f`, out of line: the row loop's state stays
/// in registers here rather than beside the edge pixels' calls.
#[inline(never)]
fn centre_run<'s, S: Stepper, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>, B>(
    row: &mut RowPixels<'_, 's, S, T, Q, Sh, X>,
    n: u32,
    init: B,
    f: &mut impl FnMut(B, Rgb888) -> B,
) -> B {
    let mut acc = init;
    for _ in 0..n {
        acc = f(acc, row.next_color());
    }
    acc
}

/// The render's own columns and rows (its `clip`) inside the frame's traced, ringed
/// ones; `None` if it shows nothing.
fn own_area<T: TestStrategy, Sh: Shader>(
    frame: &Frame<'_, T, Sh>,
    clip: Rectangle,
) -> Option<((u32, u32), (u32, u32))> {
    let inside = |lo: u32, hi: u32, offset: i32, clip_at: i32, clip_len: u32| {
        let c0 = i64::from(clip_at) - i64::from(offset);
        let c1 = c0 + i64::from(clip_len);
        let a = i64::from(lo).max(c0);
        let b = i64::from(hi).min(c1);
        (a < b).then_some((a as u32, b as u32))
    };
    let c = clip;
    Some((
        inside(frame.i0, frame.i1, frame.offset.x, c.top_left.x, c.size.width)?,
        inside(frame.j0, frame.j1, frame.offset.y, c.top_left.y, c.size.height)?,
    ))
}

/// Where row `j`, columns `i0..i1` of the image, go on the target.
fn row_area<T: TestStrategy, Sh: Shader>(frame: &Frame<'_, T, Sh>, i0: u32, i1: u32, j: u32) -> Rectangle {
    // Visible rows and columns fit in the target's i32 coordinates.
    Rectangle::new(
        Point::new(
            frame.offset.x.wrapping_add(i0 as i32),
            frame.offset.y.wrapping_add(j as i32),
        ),
        Size::new(i1 - i0, 1),
    )
}

/// Bounding boxes (widened by one pixel) of the silhouettes that may hold no pixel
/// centre (semi-minor axis under [`SMALL`]).
fn small_silhouettes<const N: usize, T: TestStrategy, Sh: Shader>(
    frame: &Frame<'_, T, Sh>,
) -> Vec<[f32; 4], N> {
    let mut small = Vec::new();
    for fs in frame.spheres {
        // The sphere's size from its tight silhouette (the robust test's margin, no
        // stepping error: the culling margins of the quadratic tests or of a far eye's
        // stepping could make a sub-pixel sphere look large); the box from the culling
        // ellipse, which contains every pixel a centre ray can hit it in (without
        // culling, `Silhouette::ALL`, the tight one stands in).
        let tight = crate::camera::span::Silhouette::new(
            fs.geom.l,
            crate::math::sqrt_exact(fs.geom.r2),
            frame.camera,
            crate::camera::span::Margin::Linear,
            0.0,
        )
        .bounds();
        let culled = fs.silhouette.bounds().or(tight);
        let size = tight.or(culled).map(|(_, semi_minor)| semi_minor);
        if let (Some((b, _)), Some(semi_minor)) = (culled, size) {
            if !(semi_minor >= SMALL) {
                let _ = small.push([b[0] - 1.0, b[1] + 1.0, b[2] - 1.0, b[3] + 1.0]);
            }
        }
    }
    small
}

/// Marks row `r`'s pixels (columns from `i0`) whose footprint meets a small box.
fn mark_small(buf: &mut RowBuf, small: &[[f32; 4]], i0: u32, r: u32) {
    let y = r as f32;
    for b in small {
        if y + 0.5 < b[2] || y - 0.5 > b[3] {
            continue;
        }
        // Columns i with [i − ½, i + ½] meeting [x0, x1], as offsets from i0 (clamped
        // by comparisons: a NaN bound marks the whole row, more rays but none missed).
        let lo = libm::ceilf(b[0] - 0.5) - i0 as f32;
        let hi = libm::floorf(b[1] + 0.5) - i0 as f32;
        let last = ADAPTIVE_MAX_WIDTH as f32 - 1.0;
        let lo = if lo > 0.0 { lo.min(last + 1.0) as usize } else { 0 };
        let hi = if hi < last { hi.max(-1.0) } else { last };
        if hi < 0.0 {
            continue;
        }
        for k in lo..=hi as usize {
            buf.mark(k);
        }
    }
}

/// The camera's steps and the sub-pixel offsets of an `n × n` grid.
struct SubSteps {
    first: Vec3,
    du: Vec3,
    dv: Vec3,
    offsets: [f32; 4],
    n: usize,
}

impl SubSteps {
    fn new<T: TestStrategy, Sh: Shader>(frame: &Frame<'_, T, Sh>, n: u32) -> Self {
        let mut offsets = [0.0; 4];
        for (a, o) in offsets.iter_mut().enumerate().take(n as usize) {
            // (a + ½)/n − ½ = (2a + 1 − n)/(2n): one rounding (none for n = 2, 4).
            *o = (2.0 * a as f32 + 1.0 - n as f32) / (2.0 * n as f32);
        }
        let c = frame.camera;
        Self {
            first: c.first_direction(),
            du: c.pixel_step(),
            dv: c.scanline_step(),
            offsets,
            n: n as usize,
        }
    }

    /// The centre ray's direction formed the same way (for [`Sample::direction`]).
    fn center(&self, i: u32, j: u32) -> Vec3 {
        (self.first + self.dv * j as f32) + self.du * i as f32
    }
}

/// Pixel `(i, j)` with `Grid(n)`'s rays: each traced against every sphere with the
/// method's single-ray test, coloured by the row's tracer, averaged in linear light.
#[inline(never)]
fn average<'s, T: TestStrategy + 's, Q: SqrtFn, Sh: Shader + 's, X: RowTracer<'s, T, Sh>>(
    spheres: impl Iterator<Item = (usize, &'s FrameSphere<T, Sh>)> + Clone,
    tracer: &mut X,
    st: &SubSteps,
    i: u32,
    j: u32,
) -> Rgb888 {
    let mut sum = [0u32; 3];
    for oy in st.offsets.iter().take(st.n) {
        let base = st.first + st.dv * (j as f32 + oy);
        for ox in st.offsets.iter().take(st.n) {
            let d = base + st.du * (i as f32 + ox);
            let a = d.dot(d);
            let mut best = None;
            let mut t_max = f32::INFINITY;
            for (index, s) in spheres.clone() {
                if let Some(t) = T::ray::<Q>(&s.geom, d, a, t_max) {
                    t_max = t;
                    best = Some((index, t, s));
                }
            }
            let (_, c) = tracer.sub_sample(best, d);
            for (acc, v) in sum.iter_mut().zip([c.r(), c.g(), c.b()]) {
                *acc += decode(v);
            }
        }
    }
    let count = (st.n * st.n) as u32;
    Rgb888::new(
        encode(sum[0], count),
        encode(sum[1], count),
        encode(sum[2], count),
    )
}

/// An 8-bit sRGB level in linear light, `round(65535·L)`.
#[inline(always)]
fn decode(v: u8) -> u32 {
    u32::from(SRGB_TO_LINEAR.get(usize::from(v)).copied().unwrap_or(0))
}

/// The level nearest (in the encoded scale) to the mean of `count` (1…16) decoded
/// values summing to `sum`: the number of thresholds at or below the mean.
///
/// Exact, no search: an integer threshold `t` is at or below `16·sum/count` exactly
/// when it is at or below its floor `x`; a table gives the thresholds below `x`'s
/// bucket (2⁸ wide under 2¹⁶, 2¹⁰ above: never more than one threshold per bucket,
/// `encode_steps_at_most_once_per_bucket`), so one comparison finishes it. Equal to
/// the binary search over the thresholds for every `x` (test
/// `encode_equals_the_search_for_every_mean`).
#[inline(always)]
fn encode(sum: u32, count: u32) -> u8 {
    let x = sum * 16 / count.max(1);
    let start = if x < 1 << 16 {
        LEVELS_BELOW_LOW.get((x >> 8) as usize)
    } else {
        LEVELS_BELOW_HIGH.get((x >> 10) as usize)
    };
    let k = start.copied().unwrap_or(255);
    let next = LINEAR_THRESHOLDS.get(usize::from(k)).copied().unwrap_or(u32::MAX);
    k + u8::from(next <= x)
}

/// One row of `Grid`/`Adaptive` pixels, computed as the sink pulls them. `stored`:
/// adaptive sampling's centre colours and edge bits (indexed from its column); `None`:
/// every pixel is averaged.
struct SampledRow<'a, 's, T: TestStrategy, Q, Sh: Shader, X> {
    spheres: &'s [FrameSphere<T, Sh>],
    tracer: &'a mut X,
    steps: &'a SubSteps,
    stored: Option<(&'a [Rgb888], &'a [u32], u32)>,
    i: u32,
    end: u32,
    j: u32,
    background: Rgb888,
    sqrt: core::marker::PhantomData<Q>,
}

impl<'s, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> SampledRow<'_, 's, T, Q, Sh, X> {
    /// Pixel `i`'s colour and the rays averaged into it.
    #[inline(always)]
    fn color(&mut self, i: u32) -> (Rgb888, u32) {
        if let Some((colors, edges, base)) = self.stored {
            let k = (i - base) as usize;
            let edge = edges.get(k / 32).is_some_and(|w| w & (1 << (k % 32)) != 0);
            if !edge {
                return (colors.get(k).copied().unwrap_or(self.background), 1);
            }
        }
        let rays = (self.steps.n * self.steps.n) as u32;
        (
            average::<T, Q, Sh, X>(
                self.spheres.iter().enumerate(),
                self.tracer,
                self.steps,
                i,
                self.j,
            ),
            rays,
        )
    }

    /// The next pixel: column, colour, rays.
    #[inline(always)]
    fn next_pixel(&mut self) -> Option<(u32, Rgb888, u32)> {
        let i = self.i;
        if i >= self.end {
            return None;
        }
        self.i += 1;
        let (c, rays) = self.color(i);
        Some((i, c, rays))
    }
}

impl<'s, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> Iterator
    for SampledRow<'_, 's, T, Q, Sh, X>
{
    type Item = Rgb888;

    #[inline(always)]
    fn next(&mut self) -> Option<Rgb888> {
        self.next_pixel().map(|(_, c, _)| c)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.i) as usize;
        (n, Some(n))
    }
}

impl<'s, T: TestStrategy, Q: SqrtFn, Sh: Shader, X: RowTracer<'s, T, Sh>> PixelRow
    for SampledRow<'_, 's, T, Q, Sh, X>
{
    /// Every pixel as a [`Sample`]: its colour and rays, the centre direction (formed
    /// directly from the camera's steps) and no hit (not kept for the centre rays of
    /// adaptive sampling; several rays have no single one).
    fn samples(mut self) -> impl Iterator<Item = Sample> {
        let (j, steps) = (self.j, self.steps);
        core::iter::from_fn(move || {
            self.next_pixel().map(|(i, color, rays)| Sample {
                pixel: Point::new(i as i32, j as i32),
                direction: steps.center(i, j),
                hit: None,
                color,
                rays,
            })
        })
    }

    fn color_runs(self) -> ColorRuns<impl Iterator<Item = Rgb888>> {
        ColorRuns {
            background: self.background,
            before: 0,
            traced_len: self.end - self.i,
            traced: self,
            after: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{decode, edge_runs, encode};
    use heapless::Vec;
    use std::println;

    /// The merged runs hold exactly the columns of the union of the intervals, in
    /// increasing order, disjoint and not touching (empty intervals, touching ones,
    /// nested ones and reversed order included).
    #[test]
    fn edge_runs_are_the_union_of_the_intervals() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = |n: u32| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 33) as u32 % n
        };
        for _ in 0..2000 {
            let bands = 1 + next(6) as usize;
            let mut edges = std::vec::Vec::new();
            for _ in 0..bands {
                let mut four = [(0, 0); 4];
                for e in &mut four {
                    let a = next(40);
                    // About a quarter empty, some reversed (empty too).
                    *e = (a, a + next(12));
                    if next(4) == 0 {
                        *e = (e.1, e.0);
                    }
                }
                edges.push(four);
            }
            let mut runs: Vec<[(u32, u32); 4], 6> = Vec::new();
            let count = edge_runs(edges.iter().copied(), &mut runs);
            let got = &runs.as_flattened()[..count];
            for w in got.windows(2) {
                assert!(w[0].1 < w[1].0, "runs {got:?} overlap or touch");
            }
            for x in 0..60 {
                let want = edges.iter().flatten().any(|&(a, z)| a <= x && x < z);
                let have = got.iter().any(|&(a, z)| a <= x && x < z);
                assert_eq!(have, want, "column {x}: runs {got:?} of {edges:?}");
            }
        }
    }

    fn srgb_to_linear(c: f64) -> f64 {
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    }

    fn linear_to_srgb(l: f64) -> f64 {
        if l <= 0.003_130_8 {
            l * 12.92
        } else {
            1.055 * l.powf(1.0 / 2.4) - 0.055
        }
    }

    /// A constant colour averages to itself, for every level and count.
    #[test]
    fn encode_steps_at_most_once_per_bucket() {
        use super::{LEVELS_BELOW_HIGH, LEVELS_BELOW_LOW, LINEAR_THRESHOLDS};
        let bucket = |x: u32| if x < 1 << 16 { x >> 8 } else { (1 << 8) + (x >> 10) };
        for w in LINEAR_THRESHOLDS.windows(2) {
            assert_ne!(
                bucket(w[0]),
                bucket(w[1]),
                "thresholds {} and {} share a bucket",
                w[0],
                w[1]
            );
        }
        // The tables count the thresholds below each bucket's start.
        for (b, &k) in LEVELS_BELOW_LOW.iter().enumerate() {
            assert_eq!(
                usize::from(k),
                LINEAR_THRESHOLDS.partition_point(|&t| t < (b as u32) << 8)
            );
        }
        for (b, &k) in LEVELS_BELOW_HIGH.iter().enumerate() {
            assert_eq!(
                usize::from(k),
                LINEAR_THRESHOLDS.partition_point(|&t| t < (b as u32) << 10)
            );
        }
    }

    #[test]
    fn encode_equals_the_search_for_every_mean() {
        use super::LINEAR_THRESHOLDS;
        for count in 1..=16u32 {
            // Every sum of `count` decoded values (each ≤ 65535), step 1 for the
            // largest grid and a prime step otherwise.
            let step = if count == 16 { 1 } else { 7 };
            for sum in (0..=count * 65535).step_by(step) {
                let want = LINEAR_THRESHOLDS.partition_point(|&t| t * count <= sum * 16);
                assert_eq!(usize::from(encode(sum, count)), want, "sum {sum}, count {count}");
            }
        }
    }

    #[test]
    fn constant_round_trips() {
        for n in [4u32, 9, 16] {
            for v in 0..=255u8 {
                assert_eq!(encode(decode(v) * n, n), v, "level {v}, {n} samples");
            }
        }
    }

    /// The table average of 8-bit-rounded samples against the exact linear-light
    /// average of the unrounded ones, encoded and rounded in f64: at most one level.
    #[test]
    fn rounded_samples_within_one_level() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut worst, mut off) = (0.0f64, 0usize);
        let trials = 200_000;
        for t in 0..trials {
            let n = [4usize, 9, 16][t % 3];
            // Two-tone samples (an edge) and spread ones, over the whole range.
            let (a, b) = (next() * 255.0, next() * 255.0);
            let unrounded: std::vec::Vec<f64> = (0..n)
                .map(|_| {
                    if t % 2 == 0 {
                        if next() < 0.5 {
                            a
                        } else {
                            b
                        }
                    } else {
                        next() * 255.0
                    }
                })
                .collect();
            let exact_lin = unrounded.iter().map(|&x| srgb_to_linear(x / 255.0)).sum::<f64>() / n as f64;
            let exact = linear_to_srgb(exact_lin) * 255.0;
            let sum: u32 = unrounded.iter().map(|&x| decode(x.round() as u8)).sum();
            let got = f64::from(encode(sum, n as u32));
            let diff = (got - exact).abs();
            worst = worst.max(diff);
            if (got - exact.round()).abs() > 0.0 {
                off += 1;
            }
            assert!(diff <= 1.0, "{unrounded:?}: {got} vs {exact}");
        }
        // Not vacuous: rounding the samples first does change some results.
        assert!(off > 0);
        println!(
            "table average of rounded samples vs exact average of unrounded: max {worst:.3} levels, \
             {off} of {trials} results differ from the exact one rounded"
        );
    }

    /// Exactly on a threshold's neighbourhood the encoding rounds to nearest: a mean
    /// just below `k + ½` (encoded) gives k, just above gives k + 1.
    #[test]
    fn encoding_rounds_to_nearest() {
        let mut checked = 0;
        for k in 0..255u32 {
            let mid = srgb_to_linear((f64::from(k) + 0.5) / 255.0) * 65535.0;
            // 16 samples summing to just below / above 16·mid (one unit of slack on
            // the table's integer rounding).
            let below = (mid * 16.0 - 2.0).floor() as u32;
            let above = (mid * 16.0 + 2.0).ceil() as u32;
            assert_eq!(u32::from(encode(below, 16)), k, "below k + ½, k = {k}");
            assert_eq!(u32::from(encode(above, 16)), k + 1, "above k + ½, k = {k}");
            checked += 1;
        }
        assert_eq!(checked, 255);
    }
}
