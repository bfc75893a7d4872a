//! Span culling: which columns of a scanline can see a sphere.
//!
//! Once per frame each sphere's silhouette is turned into an ellipse in image
//! coordinates `(x, y)` (column, row; pixel centres at integers); once per row that
//! ellipse is cut with the scanline `y = j`, giving a column interval `[lo, hi)`.
//! Only columns inside a sphere's interval test it; a row's pixels outside every
//! interval are background without any test.
//!
//! ## Why it is conservative (changes no pixel)
//!
//! A test can only report a hit where its computed discriminant is `≥ 0`. The interval
//! is the exact silhouette of a sphere **enlarged** to a radius `r_tot` that covers
//! 1. the test's own rounding ([`Margin`]): for the robust and forward-differenced
//!    tests the computed perpendicular distance is within `≈ 2⁻²²·|L|` of the true one,
//!    so `r_eff = r·(1 + 2⁻¹⁶) + 2⁻¹⁸·|L|`; the algebraic and geometric tests cancel two
//!    squares of size `|L|²` (error `≲ 16·2⁻²⁴·|L|²` in `r²` units), so
//!    `r_eff² = r²·(1 + 2⁻¹⁰) + 2⁻¹⁷·|L|²`;
//! 2. the stepping's rounding: the direction a [`Stepping`](crate::Stepping) produces
//!    is within `E` of the ideal `F + x·du + y·dv` (bounds per stepping in
//!    `stepping.rs`), which turns the ray by at most `2E` (ideal directions have
//!    `|d| ≥ d·w ≈ 1`), moving its distance from the centre by at most `2E·|L|`.
//!
//! The ellipse coefficients are computed in `f64` once per frame (about a hundred
//! operations per sphere: cheap even in software floating point on a Cortex-M4), the
//! per-row cut in `f32` with its rounding covered by a relative slack on the squared
//! half-width and one extra column on each side. The integer kernel cuts the same
//! ellipse in fixed point ([`IntCut`](super::int_cut::IntCut): no soft float per row on
//! a chip without an FPU), rounding every step outward.
//!
//! When the enlarged sphere contains the eye or crosses the plane through the eye
//! parallel to the image, its silhouette is not a bounded ellipse (a parabola, a
//! hyperbola, or the whole image): that sphere is not culled ([`Silhouette::ALL`]).
//! The same fallback catches any non-finite coefficient.
//!
//! ## Where each part is
//!
//! - once per frame, the ellipses: [`Silhouette::new`] (enlarged), [`Silhouette::inner`]
//!   (shrunk, for adaptive sampling), [`Silhouette::on_plane`] (the image of a disc or
//!   a cylinder's cut on a plane: where a shadow can be seen), all through `ellipse` and
//!   `conic`; and a silhouette's rows, [`Silhouette::rows`];
//! - once per row, the cuts: [`Silhouette::row_span`] in `f32`, the integer kernel's
//!   [`IntCut`](super::int_cut::IntCut) (`camera/int_cut.rs`, with its rows,
//!   [`Silhouette::int_cut_rows`]), and a band of rows' reach and inside
//!   ([`Silhouette::band_reach`], [`Silhouette::band_inside`]);
//! - the tests, `camera/span/tests.rs`; the cone of the image's rays, which leaves
//!   whole spheres out, `camera/cone.rs`.

use crate::camera::Camera;
use crate::math::vec3::Vec3;
use crate::math::{max, min};

/// How much a test's rounding can widen its hit set beyond the true silhouette.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Margin {
    /// Perpendicular-distance tests (robust, forward-differenced): linear in `|L|`.
    Linear,
    /// Tests that subtract squares of size `|L|²` (algebraic, geometric).
    Quadratic,
}

/// A sphere's silhouette for one frame: an [`Ellipse`], or every column of every row
/// (not culled, [`Silhouette::ALL`]).
///
/// Six floats and no tag: an ellipse always has `q > 0` (see `ellipse`), and anything
/// else (`ALL` has `q = 0`) culls nothing, so a frame keeps no tag word per sphere of
/// its capacity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Silhouette(Ellipse);

// Six floats, no tag: what every sphere of a frame's capacity keeps for its culling.
const _: () = assert!(size_of::<Silhouette>() == 24);

/// The (enlarged) silhouette: for row `y`, columns
/// `xc0 + kx·(y − y0) ± √(h0 − q·(y − y0)²)`, with the centre row split as
/// `y0 = y0i + y0f` (`y0i` an integer, `|y0f| ≤ ½`) so that `j − y0` has one rounding.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ellipse {
    pub y0i: f32,
    pub y0f: f32,
    pub q: f32,
    pub h0: f32,
    pub xc0: f32,
    pub kx: f32,
}

/// A silhouette's size on the image, in pixels: the largest half-width along a row
/// (columns) and the half-height (rows) of the (enlarged) ellipse.
///
/// Upper bounds of the sphere's own extent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Extent {
    pub half_width: f32,
    pub half_height: f32,
}

impl Silhouette {
    /// Not culled: every column of every row.
    pub(crate) const ALL: Self = Self(Ellipse {
        y0i: 0.0,
        y0f: 0.0,
        q: 0.0,
        h0: 0.0,
        xc0: 0.0,
        kx: 0.0,
    });

    /// Culls everything: an ellipse with `h0 < 0`, which no row's cut reaches
    /// (`hw² = h0·(1 + 2⁻¹⁶) − q·dy² < 0` for every `dy`).
    pub(crate) const NONE: Self = Self(Ellipse {
        y0i: 0.0,
        y0f: 0.0,
        q: 1.0,
        h0: -1.0,
        xc0: 0.0,
        kx: 0.0,
    });

    /// The ellipse; `None` for [`Self::ALL`] (and any `q` that is not positive).
    #[inline(always)]
    pub(crate) fn get(&self) -> Option<Ellipse> {
        (self.0.q > 0.0).then_some(self.0)
    }

    /// Whether this silhouette culls nothing.
    #[inline(always)]
    pub(crate) fn is_all(&self) -> bool {
        self.get().is_none()
    }

    /// The ellipse's extent; `None` when the silhouette is not a bounded ellipse.
    pub(crate) fn extent(&self) -> Option<Extent> {
        self.get().map(|Ellipse { q, h0, .. }| Extent {
            half_width: crate::math::sqrt_exact(h0),
            half_height: crate::math::sqrt_exact(h0 / q),
        })
    }

    /// The ellipse's bounding box `[x0, x1] × [y0, y1]` (image coordinates, pixel
    /// centres at integers) and a lower bound of its semi-minor axis; `None` when the
    /// silhouette is not a bounded ellipse.
    ///
    /// The lower bound is its area `π·h0/√q` over `π` times an upper bound of its
    /// semi-major axis, the box's half-diagonal.
    pub(crate) fn bounds(&self) -> Option<([f32; 4], f32)> {
        match self.get() {
            None => None,
            Some(Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            }) => {
                let half_height = crate::math::sqrt_exact(h0 / q);
                // Along a row the centre moves by kx per row: over ±half_height.
                let half_width = kx.abs() * half_height + crate::math::sqrt_exact(h0);
                let y0 = y0i + y0f;
                let semi_major = crate::math::sqrt_exact(half_width * half_width + half_height * half_height);
                let semi_minor = h0 / crate::math::sqrt_exact(q) / semi_major;
                Some((
                    [
                        xc0 - half_width,
                        xc0 + half_width,
                        y0 - half_height,
                        y0 + half_height,
                    ],
                    semi_minor,
                ))
            }
        }
    }

    /// The silhouette of the sphere (`l = centre − eye`, radius `radius`) for the
    /// camera, enlarged for the test's `margin` and the stepping's direction error
    /// bound `step_err`.
    ///
    /// [`Self::ALL`] whenever culling cannot be proven safe.
    pub(crate) fn new(l: Vec3, radius: f32, camera: &Camera, margin: Margin, step_err: f32) -> Self {
        Self::new_in(l, radius, &ImageBasis::of(camera), margin, step_err)
    }

    /// [`Self::new`] with the camera's part of the ellipse's coefficients worked out
    /// once (`basis`, [`ImageBasis::of`]) for every sphere of a frame.
    pub(crate) fn new_in(l: Vec3, radius: f32, basis: &ImageBasis, margin: Margin, step_err: f32) -> Self {
        let Some(ellipse) = ellipse::<false>(l, radius, basis, margin, step_err) else {
            return Silhouette::ALL;
        };
        ellipse
    }

    /// The sphere's silhouette **shrunk** by the same margins: every ray inside it (a
    /// test's rounding and a direction error up to `step_err` included) hits the
    /// sphere.
    ///
    /// `None` when that cannot be proven (the shrunk sphere is empty, or its
    /// silhouette is not a bounded ellipse).
    pub(crate) fn inner(
        l: Vec3,
        radius: f32,
        camera: &Camera,
        margin: Margin,
        step_err: f32,
    ) -> Option<Self> {
        ellipse::<true>(l, radius, &ImageBasis::of(camera), margin, step_err)
    }

    /// The pixels whose ray meets a plane inside a disc of it (where a shadow can be
    /// seen), as the same kind of ellipse as a sphere's silhouette.
    ///
    /// The disc has `centre` (relative to the eye, in the frame's units) and `radius`,
    /// on the plane through `centre` with unit normal `normal`; with
    /// `axis = Some((a, r))`, only the part of the disc within `r` of the line through
    /// `centre` along the unit `a` counts (a cylinder's cut: the disc must hold it).
    /// Enlarged for the stepping's direction error bound `step_err`. [`Self::ALL`]
    /// whenever it cannot be proven a bounded ellipse.
    ///
    /// A ray `t·d` meets the plane `n·p = s` at `t = s/(n·d)`, where `p − c` is
    /// `u/(n·d)` with `u = s·d − (n·d)·c`: inside the disc when `|u|² ≤ R²·(n·d)²`,
    /// within `r` of the line when `|u|² − (u·a)² ≤ r²·(n·d)²`. Either is a quadratic form
    /// in `d`, so in the pixel coordinates, cut per row as a sphere's silhouette is (the
    /// same `f32` slack and column). Only hits in front of the eye count: the ball of
    /// radius `R` around `c` lies strictly in front of the plane through the eye parallel
    /// to the image, and every ray `d` has `d·w = 1 > 0`.
    ///
    /// **Direction error.** A ray `d'` within `E` of the ideal `d` (`|d'| ≥ 1 − E ≥ ½`)
    /// that meets the plane inside the disc does so at most `D = |c| + R` away, so
    /// `|n·d'| ≥ |d'|/K ≥ 1/(2K)` with `K = D/|s|`; for `E ≤ 1/(4K)` the two hit points
    /// `s·d/(n·d)` and `s·d'/(n·d')` differ by at most
    /// `|s|·E/|n·d'|·(1 + (K·|n·d'| + E)/(|n·d'| − E)) ≤ 4·E·D·(1 + K)`: `R` and `r` are
    /// enlarged by that (with `E > 1/(4K)`, a ray grazing the plane: not bounded).
    pub(crate) fn on_plane(
        centre: [f64; 3],
        normal: [f64; 3],
        radius: f64,
        axis: Option<([f64; 3], f64)>,
        camera: &Camera,
        step_err: f32,
    ) -> Self {
        let (f, du, dv, w) = (
            v64(camera.first_direction()),
            v64(camera.pixel_step()),
            v64(camera.scanline_step()),
            v64(camera.w()),
        );
        let (c, n) = (centre, normal);
        let s = dot(c, n);
        let far = libm::sqrt(dot(c, c)) + radius;
        let k = far / s.abs();
        let e = f64::from(step_err);
        if !(radius > 0.0 && e * k <= 0.25 && far.is_finite()) {
            return Silhouette::ALL;
        }
        let grow = 4.0 * e * far * (1.0 + k);
        let big = radius + grow;
        if !(dot(c, w) > big * (1.0 + TWO_M10)) {
            return Silhouette::ALL;
        }
        // The set as −Q(d) ≥ 0, a bilinear form B(x, y) with u(x) = s·x − (n·x)·c:
        // B = −(u(x)·u(y) − (u(x)·a)(u(y)·a) − r²·(n·x)(n·y)), or a = 0 and r = R.
        let (a, r) = match axis {
            Some((a, r)) => (a, r + grow),
            None => ([0.0; 3], big),
        };
        let u = |x: [f64; 3]| {
            let nx = dot(n, x);
            [s * x[0] - nx * c[0], s * x[1] - nx * c[1], s * x[2] - nx * c[2]]
        };
        let form = |x: [f64; 3], y: [f64; 3]| {
            let (ux, uy) = (u(x), u(y));
            -(dot(ux, uy) - dot(ux, a) * dot(uy, a) - r * r * dot(n, x) * dot(n, y))
        };
        conic([
            form(du, du),
            form(du, dv),
            form(dv, dv),
            form(f, du),
            form(f, dv),
            form(f, f),
        ])
        .unwrap_or(Silhouette::ALL)
    }

    /// The columns `x` (image coordinates, real) the silhouette reaches between rows
    /// `j − h` and `j + h`: an interval containing the ellipse's cut with that band.
    ///
    /// `None` if it misses the band; [`Self::ALL`] reaches every column.
    ///
    /// The left edge `xc(y) − hw(y)` is convex in `y` and the right edge `xc(y) + hw(y)`
    /// concave, so each extreme over the band is at the band's end nearest the edge's
    /// own extreme row `dy = ∓kx·√(h0 / (q·(q + kx²)))`. Padded outward for the f32
    /// rounding as [`Self::row_span`] is, plus `2⁻⁸` pixel.
    ///
    /// `reach` is [`Self::reach_consts`], once per frame.
    #[inline]
    pub(crate) fn band_reach(&self, j: u32, h: f32, reach: (f32, f32)) -> Option<(f32, f32)> {
        let (half_height, m) = reach;
        match self.get() {
            None => Some((f32::NEG_INFINITY, f32::INFINITY)),
            Some(Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            }) => {
                let dy = (j as f32 - y0i) - y0f;
                // The band in rows from the centre row, widened for the roundings of
                // dy ± h, and cut to the ellipse's own rows (half-height widened by a
                // relative 2⁻¹⁶ for its f32 rounding).
                let slack = (dy.abs() + h) * (1.0 / 1_048_576.0);
                let a = max(dy - h - slack, -half_height);
                let b = min(dy + h + slack, half_height);
                if !(a <= b) {
                    return None;
                }
                let edge = |y: f32, sign: f32| {
                    let y = min(max(y, a), b);
                    let hw2 = (h0 - q * (y * y)) + h0 * (1.0 / 65536.0);
                    let hw = crate::math::sqrt_exact(max(hw2, 0.0));
                    let shift = kx * y;
                    let pad = (xc0.abs() + shift.abs() + hw) * (1.0 / 1_048_576.0) + 1.0 / 256.0;
                    xc0 + shift + sign * (hw + pad)
                };
                let (lo, hi) = (edge(-kx * m, -1.0), edge(kx * m, 1.0));
                // NaN coefficients reach everything.
                if lo <= hi {
                    Some((lo, hi))
                } else {
                    Some((f32::NEG_INFINITY, f32::INFINITY))
                }
            }
        }
    }

    /// [`Self::band_reach`]'s per-frame constants: the half-height (widened by a
    /// relative 2⁻¹⁶ for its rounding) and `√(h0 / (q·(q + kx²)))`.
    pub(crate) fn reach_consts(&self) -> (f32, f32) {
        match self.get() {
            None => (f32::INFINITY, 0.0),
            Some(Ellipse { q, h0, kx, .. }) => (
                crate::math::sqrt_exact(h0 / q) * (1.0 + 1.0 / 65536.0),
                crate::math::sqrt_exact(h0 / (q * (q + kx * kx))),
            ),
        }
    }

    /// The columns `x` whose vertical segment from row `j − h` to `j + h` lies inside
    /// the ellipse.
    ///
    /// They are the cuts with the band's two ends intersected (the ellipse is convex),
    /// padded inward for the f32 rounding and `2⁻⁸` pixel. `None` if empty;
    /// [`Self::ALL`] is never inside (it is not a proven region).
    #[inline]
    pub(crate) fn band_inside(&self, j: u32, h: f32) -> Option<(f32, f32)> {
        match self.get() {
            None => None,
            Some(Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            }) => {
                let dy = (j as f32 - y0i) - y0f;
                let slack = (dy.abs() + h) * (1.0 / 1_048_576.0);
                let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
                // The band's ends, each taken at its outermost rounding: the segment
                // between two inside points is inside.
                for y in [dy - h - slack, dy + h + slack] {
                    let hw2 = (h0 - q * (y * y)) - h0 * (1.0 / 65536.0);
                    if !(hw2 >= 0.0) {
                        return None;
                    }
                    let hw = crate::math::sqrt_exact(hw2);
                    let shift = kx * y;
                    let pad = (xc0.abs() + shift.abs() + hw) * (1.0 / 1_048_576.0) + 1.0 / 256.0;
                    lo = max(lo, xc0 + shift - hw + pad);
                    hi = min(hi, xc0 + shift + hw - pad);
                }
                (lo <= hi).then_some((lo, hi))
            }
        }
    }

    /// Row `j`'s offset `dy` from the centre row and the squared half-width of the
    /// ellipse's cut there, with its slack ([`Self::row_span`]).
    #[inline(always)]
    fn row_cut(j: u32, y0i: f32, y0f: f32, q: f32, h0: f32) -> (f32, f32) {
        // Cut the ellipse with the scanline through the row's pixel centres.
        // `j − y0i` is exact (integers below 2²⁴), so dy has one rounding.
        let dy = (j as f32 - y0i) - y0f;
        // Slack 2⁻¹⁶·h0 covers the f32 rounding of h0 − q·dy² (≤ 3 ulp of
        // max(h0, q·dy²), and rows with q·dy² ≫ h0 are far outside anyway).
        (dy, (h0 - q * (dy * dy)) + h0 * (1.0 / 65536.0))
    }

    /// The rows `[j0, j1)` of `0..height` outside which [`Self::row_span`] is `None`
    /// (every row for [`Self::ALL`] and for coefficients that are not finite),
    /// found once per frame by binary search, so that a row pays no floating-point
    /// operation for a sphere it cannot meet.
    ///
    /// Exact, not a bound: it evaluates `row_span`'s own test (`hw2 < 0`, the same
    /// `f32` expression, [`Self::row_cut`]), and the rows passing it are an interval.
    /// `dy` is non-decreasing in `j` (each rounded operation is monotone); where
    /// `dy ≤ 0`, `dy²` is non-increasing in `j`, so `hw2` (monotone in `q·dy²` for a
    /// finite `q > 0`) is non-decreasing, and where `dy ≥ 0` non-increasing. So `hw2`
    /// peaks at the last row with `dy < 0` or the first with `dy ≥ 0`, and falls off
    /// on both sides. Test: `rows_hold_every_row_span`.
    pub(crate) fn rows(&self, height: u32) -> (u32, u32) {
        let Some(Ellipse { y0i, y0f, q, h0, .. }) = self.get() else {
            return (0, height);
        };
        if !(q > 0.0 && q.is_finite() && h0.is_finite() && y0i.is_finite() && y0f.is_finite()) {
            return (0, height);
        }
        let cut = |j: u32| Self::row_cut(j, y0i, y0f, q, h0);
        rows_around(height, &|j| cut(j).0 >= 0.0, &|j| !(cut(j).1 < 0.0))
    }

    /// The columns `[lo, hi)` of row `j` (clamped to the visible `[i0, i1)`) whose
    /// rays can hit the sphere; `None` if none can.
    #[inline]
    pub(crate) fn row_span(&self, j: u32, i0: u32, i1: u32) -> Option<(u32, u32)> {
        match self.get() {
            None => Some((i0, i1)),
            Some(Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            }) => {
                let (dy, hw2) = Self::row_cut(j, y0i, y0f, q, h0);
                if hw2 < 0.0 {
                    return None;
                }
                let hw = crate::math::sqrt_exact(hw2);
                let shift = kx * dy;
                let xc = xc0 + shift;
                // One column (covers the f32 rounding of xc0, ≤ 2⁻⁴ for |xc0| ≤ 2²⁰)
                // plus a relative slack for the rounding of xc and hw.
                let pad = 1.0 + (xc0.abs() + shift.abs() + hw) * (1.0 / 1_048_576.0);
                let lo = libm::floorf(xc - hw - pad);
                let hi = libm::ceilf(xc + hw + pad) + 1.0;
                // Clamp to the visible columns; NaN picks the bound (no culling).
                let (f0, f1) = (i0 as f32, i1 as f32);
                let lo = lo.max(f0).min(f1);
                let hi = hi.min(f1).max(f0);
                // Exact: both are integers in [i0, i1] ⊂ [0, 8192].
                let (lo, hi) = (lo as u32, hi as u32);
                (lo < hi).then_some((lo, hi))
            }
        }
    }
}

/// The rows of `0..height` where `inside` holds, when they are an interval around the
/// centre row: `inside` holds nowhere, or at the last row before the first where
/// `past` holds (`past` false, then true) or at that row, and falls off on both sides.
pub(super) fn rows_around(
    height: u32,
    past: &dyn Fn(u32) -> bool,
    inside: &dyn Fn(u32) -> bool,
) -> (u32, u32) {
    // The first row of `lo..hi` where a predicate false-then-true holds (`hi` if none).
    let first = |mut lo: u32, mut hi: u32, p: &dyn Fn(u32) -> bool| {
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if p(mid) {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        lo
    };
    let p = first(0, height, past);
    let peak = [p.checked_sub(1), (p < height).then_some(p)]
        .into_iter()
        .flatten()
        .find(|&j| inside(j));
    let Some(m) = peak else {
        return (0, 0);
    };
    (first(0, m, inside), first(m + 1, height, &|j| !inside(j)))
}

pub(super) const TWO_M10: f64 = 1.0 / 1024.0;
pub(super) const TWO_M16: f64 = 1.0 / 65_536.0;
pub(super) const TWO_M17: f64 = 1.0 / 131_072.0;
pub(super) const TWO_M18: f64 = 1.0 / 262_144.0;

/// The sphere's radius `r` (at distance `l_len`, `l2` its square, from the eye) enlarged for the test's
/// rounding `margin`, then for the stepping's direction error `step_err`.
fn enlarged(r: f64, l2: f64, l_len: f64, margin: Margin, step_err: f64) -> f64 {
    let r_eff = match margin {
        Margin::Linear => r * (1.0 + TWO_M16) + l_len * TWO_M18,
        Margin::Quadratic => libm::sqrt(r * r * (1.0 + TWO_M10) + l2 * TWO_M17),
    };
    r_eff + 2.0 * step_err * (1.0 + 1e-3) * l_len
}

/// The camera's part of every silhouette's ellipse: the dot products of the image's
/// vectors in `f64`, which do not depend on the sphere, beside the camera they come from.
///
/// Worked out once per frame, not once per sphere: in software `f64` (a chip without a
/// double-precision unit) they are 18 of a silhouette's products. The same operations
/// in the same order as where each is used, so every ellipse is the same to the bit.
/// It keeps the six products and a reference (56 B on a 32-bit target), not copies of
/// the camera's vectors: it lives in the frame set-up's stack frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ImageBasis<'c> {
    /// The camera: `F`, `du`, `dv` and `w` are read from it.
    camera: &'c Camera,
    /// `du·du`, `du·dv`, `dv·dv`, `F·du`, `F·dv`, `F·F`.
    dots: [f64; 6],
}

impl<'c> ImageBasis<'c> {
    /// The camera's dot products.
    pub(crate) fn of(camera: &'c Camera) -> Self {
        let (f, du, dv) = (
            camera.first_direction(),
            camera.pixel_step(),
            camera.scanline_step(),
        );
        Self {
            camera,
            dots: [
                du.dot_f64(du),
                du.dot_f64(dv),
                dv.dot_f64(dv),
                f.dot_f64(du),
                f.dot_f64(dv),
                f.dot_f64(f),
            ],
        }
    }
}

/// A vector in `f64` (exactly).
fn v64(v: Vec3) -> [f64; 3] {
    [f64::from(v.x), f64::from(v.y), f64::from(v.z)]
}

/// `a·b` in `f64`, summed left to right.
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The enlarged silhouette (`INNER`: shrunk) as an ellipse, or `None` when it is not a
/// bounded ellipse.
///
/// The side is a const: a firmware that only culls links only the enlarged one.
fn ellipse<const INNER: bool>(
    l: Vec3,
    radius: f32,
    basis: &ImageBasis,
    margin: Margin,
    step_err: f32,
) -> Option<Silhouette> {
    let ImageBasis { camera, dots } = *basis;
    let (f, du, dv, w) = (
        camera.first_direction(),
        camera.pixel_step(),
        camera.scanline_step(),
        camera.w(),
    );
    let [du_du, du_dv, dv_dv, f_du, f_dv, f_f] = dots;
    let r = f64::from(radius);
    let l2 = l.dot_f64(l);
    let l_len = libm::sqrt(l2);
    let step_err = f64::from(step_err);
    // A direction error of 2E or more is not small: no culling.
    if !(r > 0.0 && step_err < 1e-2 && l_len.is_finite()) {
        return None;
    }
    // Enlarge the sphere: the test's rounding, then the stepping's (or shrink it by
    // the same amounts: a miss needs the same error the other way).
    let r_tot = if INNER {
        let r_eff = match margin {
            Margin::Linear => r * (1.0 - TWO_M16) - l_len * TWO_M18,
            Margin::Quadratic => libm::sqrt((r * r * (1.0 - TWO_M10) - l2 * TWO_M17).max(0.0)),
        };
        let r_tot = r_eff - 2.0 * step_err * (1.0 + 1e-3) * l_len;
        if !(r_tot > 0.0) {
            return None;
        }
        r_tot
    } else {
        enlarged(r, l2, l_len, margin, step_err)
    };
    // A bounded ellipse needs the enlarged sphere strictly in front of the plane through
    // the eye parallel to the image (which also puts the eye outside it).
    if !(l.dot_f64(w) > r_tot * (1.0 + TWO_M10)) {
        return None;
    }
    // Hit condition of the enlarged sphere for the ideal ray d = F + x·du + y·dv:
    // (L·d)² ≥ c'·(d·d) with c' = |L|² − r_tot², a quadratic form in (x, y):
    // A x² + 2B xy + C y² + 2D x + 2E y + G ≥ 0.
    let cp = l2 - r_tot * r_tot;
    let (lf, lu, lvv) = (l.dot_f64(f), l.dot_f64(du), l.dot_f64(dv));
    let a = lu * lu - cp * du_du;
    let b = lu * lvv - cp * du_dv;
    let c = lvv * lvv - cp * dv_dv;
    let d = lf * lu - cp * f_du;
    let e = lf * lvv - cp * f_dv;
    let g = lf * lf - cp * f_f;
    conic([a, b, c, d, e, g])
}

/// The ellipse of the pixels `(x, y)` where `A x² + 2B xy + C y² + 2D x + 2E y + G ≥ 0`
/// (`[a, b, c, d, e, g]`, from a quadratic form in the ray `d = F + x·du + y·dv`).
///
/// `None` when that set is not a bounded ellipse or its coefficients leave the ranges
/// the per-row cut is argued for.
#[inline(always)]
fn conic([a, b, c, d, e, g]: [f64; 6]) -> Option<Silhouette> {
    // Row y: A x² + 2(By + D) x + (Cy² + 2Ey + G) ≥ 0 with A < 0, i.e. x between the
    // roots; the discriminant (By + D)² − A(Cy² + 2Ey + G) = P2 y² + 2 P1 y + P0.
    if !(a < 0.0) {
        return None;
    }
    let p2 = b * b - a * c;
    let p1 = b * d - a * e;
    let p0 = d * d - a * g;
    if !(p2 < 0.0) {
        return None;
    }
    // Centre row and the discriminant's maximum; half-width² = disc/A².
    let y0 = -p1 / p2;
    let disc_max = p0 - p1 * p1 / p2;
    let a2 = a * a;
    let h0 = disc_max / a2;
    let q = -p2 / a2;
    let kx = -b / a;
    let xc0 = -(b * y0 + d) / a;
    // Centres beyond ±2²⁰ pixels (a sphere near the eye plane, an ellipse reaching far
    // off-screen) would lose the per-row precision argued above: no culling. The
    // comparisons also reject NaN.
    let limit = 1_048_576.0;
    if !(y0.abs() <= limit
        && xc0.abs() <= limit
        && h0 >= 0.0
        && q > 0.0
        && h0.is_finite()
        && q.is_finite()
        && kx.is_finite())
    {
        return None;
    }
    let y0i = libm::round(y0);
    let (q, h0, kx) = (q as f32, h0 as f32, kx as f32);
    (q > 0.0 && q.is_finite() && h0.is_finite() && kx.is_finite()).then_some(Silhouette(Ellipse {
        y0i: y0i as f32,
        y0f: (y0 - y0i) as f32,
        q,
        h0,
        xc0: xc0 as f32,
        kx,
    }))
}

#[cfg(test)]
mod tests;
