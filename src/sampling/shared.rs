//! [`Sampling::Adaptive`](super::Sampling::Adaptive)`(n)` from samples shared between
//! neighbouring pixels: two rows of centre samples (identity, colour, edge bits) of a
//! fixed width.

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use heapless::Vec;

use super::average::SubSteps;
use super::grid::{row_area, SampledRow};
use crate::math::SqrtFn;
use crate::method::intersect::TestStrategy;
use crate::method::stepping::Stepper;
use crate::trace::frame::Frame;
use crate::trace::rows::{Rows, FINE};
use crate::trace::scanline::{self, RowPixels, RowSink, RowTracer};
use crate::trace::shade::Shader;

/// The widest image `Adaptive` keeps its two rows of shared samples for (scenes with
/// features, and Lab #1 frames the silhouettes cannot decide).
///
/// There, a wider image's pixels are all edge pixels (`Grid(n)`'s); a Lab #1 frame
/// decided by its silhouettes has no width limit.
pub const ADAPTIVE_MAX_WIDTH: usize = 256;

/// Silhouettes whose semi-minor axis (lower bound, pixels) is under this may hold no
/// pixel centre: all their pixels are edge pixels.
///
/// An ellipse with a semi-minor axis of `√2/2` or more holds a pixel centre; 2 leaves
/// room for the culling ellipse's enlargement.
pub const SMALL: f32 = 2.0;

/// Neighbouring centre colours further apart than this (levels, any channel) make
/// both pixels edge pixels: where shading changes this fast (a sphere's rim, a
/// highlight) the pixel's mean is not its centre's colour.
pub const CONTRAST: u8 = 16;

/// [`Sampling::Adaptive`](super::Sampling::Adaptive)`(n)` by samples shared between
/// neighbours; `clip` is the render's own (the frame traces the ring around it).
///
/// Its edge pixels (a scene with lights, planes or mirrors, or a Lab #1 frame the
/// silhouettes cannot decide), conservatively:
/// - *shared samples*: every centre ray is traced once, with an identity (what decides
///   its colour discontinuously: the object; in the features path also the checker
///   cell, which lights reach the point, what each reflected ray hit). A pixel whose
///   identity differs from one of its eight neighbours' is an edge pixel, and so is
///   that neighbour: any boundary between two centres is found on both sides of it.
///   Neighbours whose centre colours differ by more than [`CONTRAST`] levels are
///   marked the same way: where shading changes that fast across a pixel (a sphere's
///   rim, a highlight), its mean is not its centre's colour.
///   The identities are kept for two rows (a fixed buffer of [`ADAPTIVE_MAX_WIDTH`]
///   columns: 16-bit identities, centre colours and edge bits, 2,624 bytes), so each
///   row is emitted one row after it is traced; a clipped render traces the one-pixel
///   ring around the clip too, so a pixel never depends on the clip.
/// - *detail finer than the pixels*: a centre ray that meets a checkered plane where
///   the pixel's footprint on it is more than half a cell wide (the cells alias: the
///   centres can agree by chance) makes its pixel an edge pixel.
/// - *small silhouettes*: a sphere whose silhouette (its culling ellipse) has a
///   semi-minor axis under [`SMALL`] pixels may hold no pixel centre at all; every pixel
///   whose footprint meets its bounding box, widened by one pixel, is an edge pixel.
///
/// What the shared-sample rule can miss: a feature narrower than the spacing of the
/// pixel centres that falls between them (the tip of a thin silhouette, a shadow or
/// checker sliver, a small object seen in a mirror) where no centre in the 3×3
/// neighbourhood sees it; and two identities that collide in 16 bits (one in 65,536).
/// The README's "Anti-aliasing" section measures how often Adaptive(4) differs from
/// Grid(4).
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

/// The render's own columns and rows (its `clip`) inside the frame's traced, ringed
/// ones; `None` if it shows nothing.
pub(super) fn own_area<T: TestStrategy, Sh: Shader>(
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

/// Bounding boxes (widened by one pixel) of the silhouettes that may hold no pixel
/// centre (semi-minor axis under [`SMALL`]).
fn small_silhouettes<const N: usize, T: TestStrategy, Sh: Shader>(
    frame: &Frame<'_, T, Sh>,
) -> Vec<[f32; 4], N> {
    let mut small = Vec::new();
    for fs in frame.spheres {
        if let Some(b) = small_box(&fs.geom, fs.silhouette, frame.camera) {
            let _ = small.push(b);
        }
    }
    small
}

/// A sphere's box of the small silhouettes (`geom` and its culling silhouette `culled`
/// in the frame's units), `[x0, x1, y0, y1]` in pixels: its culling ellipse's bounding
/// box widened by one pixel, if its semi-minor axis is under [`SMALL`].
///
/// Every pixel whose footprint meets the box is an edge pixel (`mark_small`), however
/// far the box reaches beyond the ellipse: an incremental frame redraws the box of a
/// sphere that moved.
pub(crate) fn small_box(
    geom: &crate::method::intersect::SphereGeom,
    culled: crate::camera::span::Silhouette,
    camera: &crate::camera::Camera,
) -> Option<[f32; 4]> {
    // The sphere's size from its tight silhouette (the robust test's margin, no
    // stepping error: the culling margins of the quadratic tests or of a far eye's
    // stepping could make a sub-pixel sphere look large); the box from the culling
    // ellipse, which contains every pixel a centre ray can hit it in (without
    // culling, `Silhouette::ALL`, the tight one stands in).
    let tight = crate::camera::span::Silhouette::new(
        geom.l,
        crate::math::sqrt_exact(geom.r2),
        camera,
        crate::camera::span::Margin::Linear,
        0.0,
    )
    .bounds();
    let culled = culled.bounds().or(tight);
    let size = tight.or(culled).map(|(_, semi_minor)| semi_minor);
    match (culled, size) {
        (Some((b, _)), Some(semi_minor)) if !(semi_minor >= SMALL) => {
            Some([b[0] - 1.0, b[1] + 1.0, b[2] - 1.0, b[3] + 1.0])
        }
        _ => None,
    }
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
