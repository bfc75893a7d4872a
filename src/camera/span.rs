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
//! ellipse in fixed point ([`IntCut`]: no soft float per row on a chip without an FPU),
//! rounding every step outward.
//!
//! When the enlarged sphere contains the eye or crosses the plane through the eye
//! parallel to the image, its silhouette is not a bounded ellipse (a parabola, a
//! hyperbola, or the whole image): that sphere is not culled ([`Silhouette::ALL`]).
//! The same fallback catches any non-finite coefficient.

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
/// (columns) and the half-height (rows) of the (enlarged) ellipse. Upper bounds of the
/// sphere's own extent.
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
    /// centres at integers) and a lower bound of its semi-minor axis (its area
    /// `π·h0/√q` over `π` times an upper bound of its semi-major axis, the box's
    /// half-diagonal); `None` when the silhouette is not a bounded ellipse.
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
    /// bound `step_err`. [`Self::ALL`] whenever culling cannot be proven safe.
    pub(crate) fn new(l: Vec3, radius: f32, camera: &Camera, margin: Margin, step_err: f32) -> Self {
        let Some(ellipse) = ellipse::<false>(l, radius, camera, margin, step_err) else {
            return Silhouette::ALL;
        };
        ellipse
    }

    /// The sphere's silhouette **shrunk** by the same margins: every ray inside it (a
    /// test's rounding and a direction error up to `step_err` included) hits the
    /// sphere. `None` when that cannot be proven (the shrunk sphere is empty, or its
    /// silhouette is not a bounded ellipse).
    pub(crate) fn inner(
        l: Vec3,
        radius: f32,
        camera: &Camera,
        margin: Margin,
        step_err: f32,
    ) -> Option<Self> {
        ellipse::<true>(l, radius, camera, margin, step_err)
    }

    /// The pixels whose ray meets a plane inside a disc of it: `centre` (relative to the
    /// eye, in the frame's units) and `radius`, on the plane through `centre` with unit
    /// normal `normal`; with `axis = Some((a, r))`, only the part of the disc within `r`
    /// of the line through `centre` along the unit `a` (a cylinder's cut: the disc must
    /// hold it). Enlarged for the stepping's direction error bound `step_err`.
    /// [`Self::ALL`] whenever it cannot be proven a bounded ellipse.
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
        let v64 = |v: Vec3| [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
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
    /// `j − h` and `j + h`: an interval containing the ellipse's cut with that band,
    /// `None` if it misses the band. [`Self::ALL`] reaches every column.
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
    /// the ellipse: the cuts with the band's two ends intersected (the ellipse is
    /// convex), padded inward for the f32 rounding and `2⁻⁸` pixel. `None` if empty;
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
        let inside = |j: u32| !(cut(j).1 < 0.0);
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
        let p = first(0, height, &|j| cut(j).0 >= 0.0);
        let peak = [p.checked_sub(1), (p < height).then_some(p)]
            .into_iter()
            .flatten()
            .find(|&j| inside(j));
        let Some(m) = peak else {
            return (0, 0);
        };
        (first(0, m, &inside), first(m + 1, height, &|j| !inside(j)))
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

/// A silhouette's per-row cut in integer arithmetic, for the integer kernel: on a chip
/// without an FPU the `f32` cut ([`Silhouette::row_span`]) is a dozen soft-float calls
/// per sphere and row (≈ 1,500 instructions on a Cortex-M0), this one a few 32-bit
/// multiplies and one integer square root.
///
/// ## Why it culls nothing a hit can reach
///
/// Its columns contain those of `row_span`'s formula evaluated **exactly** on the
/// stored `f32` coefficients — `xc ± (hw + pad)` with `xc = xc0 + kx·dy`,
/// `hw² = h0·(1 + 2⁻¹⁶) − q·dy²`, `pad = 1 + (|xc0| + |kx·dy| + hw)·2⁻²⁰`,
/// `dy = j − y0` — and that interval holds every column the enlarged silhouette holds:
/// the coefficients' own `f32` rounding (relative `2⁻²⁴`, `xc0` within `2⁻⁴`) is far
/// inside the slack `2⁻¹⁶·h0` and the pad's column, which were sized to cover it and
/// the per-row `f32` rounding besides. What they do not cover (`y0f`'s rounding, up to
/// `2⁻²⁵` rows, on an ellipse less than `2⁻⁸` rows tall; the `f64` coefficients' own
/// rounding) is far inside the spare margin of the integer kernel's silhouette, which
/// is enlarged by at least 1/8 pixel to cover 1/16. Every step below rounds outward:
/// - `dy·2¹²` lies in `(dy₁₂ − 1, dy₁₂]` with `dy₁₂ = 2¹²·j − ⌊2¹²·y0⌋` (exact), so
///   `m = dy₁₂ − 1` (or `−dy₁₂`) bounds `2¹²·|dy|` from below;
/// - `q·dy² ≥ ⌊q·2²⁴⌋·m²/2⁴⁸`, floored again to `2⁻³²`, and `h0·(1 + 2⁻¹⁶)` is taken
///   rounded up to `2⁻⁸`: an upper bound of `hw²`, rounded up to `2⁻⁶` and its root
///   up to `2⁻³` ([`isqrt32`](crate::math::wide::isqrt32), exact, plus one where not a
///   square);
/// - the centre `xc0 + kx·dy` from `xc0` and `kx` rounded to `2⁻¹⁶` and `dy₁₂`:
///   within `e = 2⁻¹⁷ + 2⁻¹⁷·|dy| + (|kx| + 2⁻¹⁷)·2⁻¹² + 2⁻¹⁶` (the last the shift's
///   floor), taken at the sphere's largest `|dy|` ([`Silhouette::rows`]) and added to
///   the pad with the pad's relative part at its largest;
/// - `lo = ⌊xc − hw − pad⌋`, `hi = ⌊xc + hw + pad⌋ + 1`.
///
/// Where the ranges that keep its coefficients in 32 bits and its products in 64 do
/// not hold (`q ≥ 2⁸`, `h0 ≥ 2²⁴ − 1`, `|kx|, |xc0|, |dy| ≥ 2¹⁵`, `|y0| > 2¹⁸`) or a
/// coefficient is not finite, every column ([`IntCut::All`]): slower, never wrong.
/// Test: `int_cut_holds_the_exact_row_span`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum IntCut {
    /// Every column of every row.
    All,
    /// The cut's fixed-point coefficients (their roundings: [`IntCut`]).
    Ellipse {
        /// `⌊2¹²·y0⌋`.
        y12: i32,
        /// `⌊2²⁴·q⌋`.
        q24: u32,
        /// `⌈2⁸·h0·(1 + 2⁻¹⁶)⌉`.
        h8: u32,
        /// `round(2¹⁶·xc0)`, `round(2¹⁶·kx)` and `⌈2¹⁶·(pad + e)⌉` at the largest `|dy|`.
        xc16: i32,
        kx16: i32,
        pad16: i32,
    },
}

impl Silhouette {
    /// The integer cut of this silhouette for the rows `[j0, j1)` ([`Self::rows`]).
    pub(crate) fn int_cut(&self, (j0, j1): (u32, u32)) -> IntCut {
        let Some(Ellipse {
            y0i,
            y0f,
            q,
            h0,
            xc0,
            kx,
        }) = self.get()
        else {
            return IntCut::All;
        };
        let [y0i, y0f, q, h0, xc0, kx] = [y0i, y0f, q, h0, xc0, kx].map(f64::from);
        let y0 = y0i + y0f;
        let dy_max = (f64::from(j0) - y0).abs().max((f64::from(j1) - y0).abs());
        // h0·(1 + 2⁻¹⁶) rounded up (two f64 roundings of 2⁻⁵³ each, under 2⁻⁵⁰).
        let h0_up = h0 * (1.0 + TWO_M16) * (1.0 + TWO_M50);
        let hw_max = libm::sqrt(h0_up.max(0.0));
        let centre_err = TWO_M17 + TWO_M17 * dy_max + (kx.abs() + TWO_M17) / 4096.0 + TWO_M16;
        let pad = 1.0 + (xc0.abs() + kx.abs() * dy_max + hw_max) * TWO_M20 + centre_err;
        // The comparisons also reject NaN.
        if !(q > 0.0
            && q < 256.0
            && h0_up < 16_777_215.0
            && kx.abs() < 32_768.0
            && xc0.abs() < 32_768.0
            && y0i.abs() <= 262_144.0
            && dy_max < 32_768.0
            && pad < 16.0)
        {
            return IntCut::All;
        }
        IntCut::Ellipse {
            // Exact: y0i·2¹² is an integer, y0f·2¹² is exact in f64.
            y12: (y0i * 4096.0) as i32 + libm::floor(y0f * 4096.0) as i32,
            q24: libm::floor(q * 16_777_216.0) as u32,
            h8: libm::ceil(h0_up.max(0.0) * 256.0) as u32,
            xc16: libm::round(xc0 * 65_536.0) as i32,
            kx16: libm::round(kx * 65_536.0) as i32,
            pad16: libm::ceil(pad * 65_536.0) as i32,
        }
    }
}

impl IntCut {
    /// The columns `[lo, hi)` of row `j` (clamped to `[0, width)`) whose rays can hit
    /// the sphere; `None` if none can.
    #[inline]
    pub(crate) fn row_span(&self, j: u32, width: u32) -> Option<(u32, u32)> {
        use crate::math::wide::{isqrt32, mul_i32_wide, mul_wide};
        let IntCut::Ellipse {
            y12,
            q24,
            h8,
            xc16,
            kx16,
            pad16,
        } = *self
        else {
            return Some((0, width));
        };
        // 2¹²·dy in (dy12 − 1, dy12]; m ≤ 2¹²·|dy| < 2²⁷.
        let dy12 = (i64::from(j) << 12) - i64::from(y12);
        let m = (if dy12 > 0 { dy12 - 1 } else { -dy12 }) as u32;
        let m2 = mul_wide(m, m);
        // ⌊q24·m²/2¹⁶⌋ ≤ 2³²·q·dy² (q24·m² < 2⁸⁶).
        let q_dy2 = ((u128::from(mul_wide(q24, (m2 >> 32) as u32)) << 32)
            + u128::from(mul_wide(q24, m2 as u32)))
            >> 16;
        // 2³²·hw² at most 2²⁴·h8 − q_dy2 (below zero: no column), then 2⁶·hw² rounded
        // up.
        let hw2 = (u128::from(h8) << 24).checked_sub(q_dy2)? as u64;
        let v = (hw2 >> 26) + u64::from(hw2 & ((1 << 26) - 1) != 0);
        let Ok(v) = u32::try_from(v) else {
            return Some((0, width));
        };
        // ⌈√v⌉ = 2³·hw rounded up, as 2¹⁶·hw.
        let r = isqrt32(v);
        let hw16 = i64::from(r + u32::from(r * r < v)) << 13;
        // |dy12| < 2²⁸ (the rows' |dy| < 2¹⁵): an i32.
        let xc = i64::from(xc16) + (mul_i32_wide(kx16, dy12 as i32) >> 12);
        let w = i64::from(width);
        let pad16 = i64::from(pad16);
        let lo = ((xc - hw16 - pad16) >> 16).clamp(0, w) as u32;
        let hi = (((xc + hw16 + pad16) >> 16) + 1).clamp(0, w) as u32;
        (lo < hi).then_some((lo, hi))
    }
}

const TWO_M10: f64 = 1.0 / 1024.0;
const TWO_M16: f64 = 1.0 / 65_536.0;
const TWO_M17: f64 = 1.0 / 131_072.0;
const TWO_M18: f64 = 1.0 / 262_144.0;
const TWO_M20: f64 = 1.0 / 1_048_576.0;
const TWO_M50: f64 = 1.0 / 1_125_899_906_842_624.0;

/// The enlarged silhouette (`INNER`: shrunk) as an ellipse, or `None` when it is not a
/// bounded ellipse. The side is a const: a firmware that only culls links only the
/// enlarged one.
/// The sphere's radius `r` (at distance `l_len`, `l2` its square, from the eye) enlarged for the test's
/// rounding `margin`, then for the stepping's direction error `step_err`.
fn enlarged(r: f64, l2: f64, l_len: f64, margin: Margin, step_err: f64) -> f64 {
    let r_eff = match margin {
        Margin::Linear => r * (1.0 + TWO_M16) + l_len * TWO_M18,
        Margin::Quadratic => libm::sqrt(r * r * (1.0 + TWO_M10) + l2 * TWO_M17),
    };
    r_eff + 2.0 * step_err * (1.0 + 1e-3) * l_len
}

fn ellipse<const INNER: bool>(
    l: Vec3,
    radius: f32,
    camera: &Camera,
    margin: Margin,
    step_err: f32,
) -> Option<Silhouette> {
    let v64 = |v: Vec3| [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (lv, f, du, dv, w) = (
        v64(l),
        v64(camera.first_direction()),
        v64(camera.pixel_step()),
        v64(camera.scanline_step()),
        v64(camera.w()),
    );
    let r = f64::from(radius);
    let l2 = dot(lv, lv);
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
    if !(dot(lv, w) > r_tot * (1.0 + TWO_M10)) {
        return None;
    }
    // Hit condition of the enlarged sphere for the ideal ray d = F + x·du + y·dv:
    // (L·d)² ≥ c'·(d·d) with c' = |L|² − r_tot², a quadratic form in (x, y):
    // A x² + 2B xy + C y² + 2D x + 2E y + G ≥ 0.
    let cp = l2 - r_tot * r_tot;
    let (lf, lu, lvv) = (dot(lv, f), dot(lv, du), dot(lv, dv));
    let a = lu * lu - cp * dot(du, du);
    let b = lu * lvv - cp * dot(du, dv);
    let c = lvv * lvv - cp * dot(dv, dv);
    let d = lf * lu - cp * dot(f, du);
    let e = lf * lvv - cp * dot(f, dv);
    let g = lf * lf - cp * dot(f, f);
    conic([a, b, c, d, e, g])
}

/// The ellipse of the pixels `(x, y)` where `A x² + 2B xy + C y² + 2D x + 2E y + G ≥ 0`
/// (`[a, b, c, d, e, g]`, from a quadratic form in the ray `d = F + x·du + y·dv`), or
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
mod tests {
    use super::*;
    use embedded_graphics::prelude::Size;

    /// Uniform `f32` draws in `[lo, hi)` from an xorshift64 generator seeded `state`.
    fn uniform(mut state: u64) -> impl FnMut(f32, f32) -> f32 {
        move |lo, hi| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            lo + (hi - lo) * ((state >> 40) as f32 / (1u64 << 24) as f32)
        }
    }

    /// A random camera (1–300 pixels each way, eye in front of the origin) and sphere
    /// (centre around the origin, radius up to 3, cubed toward small): the camera, the
    /// sphere's eye-relative centre and its radius; `None` where the camera is refused.
    fn random_view(next: &mut impl FnMut(f32, f32) -> f32) -> Option<(Camera, Vec3, f32)> {
        let size = Size::new(next(1.0, 300.0) as u32, next(1.0, 300.0) as u32);
        let eye = Vec3::new(next(-2.0, 2.0), next(-2.0, 2.0), next(4.0, 9.0));
        let camera = Camera::new(
            eye,
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            next(0.2, 2.5),
            size,
        )
        .ok()?;
        let centre = Vec3::new(next(-6.0, 6.0), next(-6.0, 6.0), next(-6.0, 3.0));
        let radius = next(0.0, 1.0).powi(3) * 3.0;
        Some((camera, centre - eye, radius))
    }

    /// The integer cut holds every column of `row_span`'s formula evaluated exactly (in
    /// `f64` from the stored coefficients, with its slack and pad), on every row of
    /// [`Silhouette::rows`], and is at most a column wider on each side: random spheres
    /// and cameras, random coefficients (thin, tall, sheared, off the image's ends),
    /// and the ranges where it gives up to every column.
    #[test]
    fn int_cut_holds_the_exact_row_span() {
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let mut rows_checked = 0;
        let mut check = |sil: Silhouette, (w, h): (u32, u32)| {
            let rows = sil.rows(h);
            let cut = sil.int_cut(rows);
            let Some(Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            }) = sil.get()
            else {
                assert_eq!(cut, IntCut::All);
                return;
            };
            for j in rows.0..rows.1 {
                let dy = (f64::from(j) - f64::from(y0i)) - f64::from(y0f);
                let hw2 = f64::from(h0) * (1.0 + TWO_M16) - f64::from(q) * dy * dy;
                let got = cut.row_span(j, w);
                if hw2 < 0.0 {
                    continue;
                }
                let hw = hw2.sqrt();
                let shift = f64::from(kx) * dy;
                let xc = f64::from(xc0) + shift;
                let pad = 1.0 + (f64::from(xc0).abs() + shift.abs() + hw) * TWO_M20;
                let (lo, hi) = ((xc - hw - pad).ceil(), (xc + hw + pad).floor());
                let (lo, hi) = (lo.max(0.0), hi.min(f64::from(w) - 1.0));
                if lo > hi {
                    continue;
                }
                rows_checked += 1;
                let (glo, ghi) = got.unwrap_or_else(|| panic!("{sil:?}: row {j} empty"));
                assert!(
                    f64::from(glo) <= lo && f64::from(ghi) > hi,
                    "{sil:?}: row {j}: {glo}..{ghi} misses {lo}..={hi}"
                );
                if cut != IntCut::All {
                    assert!(
                        f64::from(glo) >= lo - 2.0 && f64::from(ghi) <= hi + 3.0,
                        "{sil:?}: row {j}: {glo}..{ghi} much wider than {lo}..={hi}"
                    );
                }
            }
        };
        for _ in 0..400 {
            let Some((camera, l, radius)) = random_view(&mut next) else {
                continue;
            };
            let size = camera.size();
            let sil = Silhouette::new(l, radius, &camera, Margin::Linear, next(0.0, 0.01));
            check(sil, (size.width, size.height));
        }
        for _ in 0..3_000 {
            let y0 = next(-500.0, 3_000.0);
            let sil = Silhouette(Ellipse {
                y0i: y0.floor(),
                y0f: y0 - y0.floor(),
                q: next(0.0, 1.0).powi(4) * 300.0 + f32::MIN_POSITIVE,
                h0: next(0.0, 1.0).powi(3) * 4.0e6,
                xc0: next(-500.0, 3_000.0),
                kx: next(-3.0, 3.0),
            });
            check(sil, (2_500, 2_500));
        }
        assert!(rows_checked > 100_000, "too few rows checked: {rows_checked}");
        // Out of the fixed-point ranges: every column.
        let ellipse = |y0i: f32, q: f32, h0: f32, kx: f32| {
            Silhouette(Ellipse {
                y0i,
                y0f: 0.25,
                q,
                h0,
                xc0: 5.0,
                kx,
            })
        };
        assert_ne!(ellipse(10.0, 1.0, 100.0, 0.5).int_cut((0, 48)), IntCut::All);
        for sil in [
            ellipse(10.0, 300.0, 100.0, 0.5),
            ellipse(10.0, 1.0, 3.0e7, 0.5),
            ellipse(10.0, 1.0, 100.0, 4.0e4),
            ellipse(10.0, f32::NAN, 100.0, 0.5),
            // An ellipse (q > 0) whose other coefficients are not finite: int_cut's
            // own rejection, not `ALL`'s.
            ellipse(10.0, 1.0, f32::NAN, 0.5),
            ellipse(f32::NAN, 1.0, 100.0, 0.5),
            ellipse(10.0, 1.0, 100.0, f32::INFINITY),
            ellipse(3.0e5, 1.0, 100.0, 0.5),
            Silhouette::ALL,
        ] {
            assert_eq!(sil.int_cut((0, 48)), IntCut::All, "{sil:?}");
        }
        assert_eq!(IntCut::All.row_span(7, 48), Some((0, 48)));
    }

    /// `rows` is exactly the set of rows passing `row_span`'s test, so no row outside
    /// it has a span: random spheres and cameras (on screen, off screen above and
    /// below, sub-pixel, huge, with and without a margin), plain and random
    /// coefficients near the ends of the image, and the degenerate cases (every row).
    /// `on_plane` holds every pixel whose ray (the ideal one, or one turned by up to the
    /// stepping error) meets the plane inside the disc (and the cylinder): random
    /// cameras, planes, discs and cylinders, every pixel. The same set with a radius
    /// 5 % short misses some of them: the check can fail.
    #[test]
    fn on_plane_holds_every_pixel_whose_ray_meets_it() {
        let mut next = uniform(0x5851_f42d_4c95_7f2d);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let unit = |a: [f64; 3]| {
            let l = dot(a, a).sqrt();
            [a[0] / l, a[1] / l, a[2] / l]
        };
        let v64 = |v: Vec3| [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
        let (mut inside, mut missed_short, mut bounded) = (0u32, 0u32, 0u32);
        for case in 0..300 {
            let Some((camera, _, _)) = random_view(&mut next) else {
                continue;
            };
            let size = camera.size();
            let eye = v64(camera.eye());
            let n = unit([f64::from(next(-0.5, 0.5)), 1.0, f64::from(next(-0.5, 0.5))]);
            // A point of the plane near the origin, relative to the eye.
            let on = [
                f64::from(next(-2.0, 2.0)) - eye[0],
                f64::from(next(-2.5, 0.0)) - eye[1],
                f64::from(next(-2.0, 2.0)) - eye[2],
            ];
            let radius = f64::from(next(0.05, 2.0));
            let axis = (case % 2 == 1).then(|| {
                let a = unit([
                    f64::from(next(-1.0, 1.0)),
                    f64::from(next(0.5, 2.0)),
                    f64::from(next(-1.0, 1.0)),
                ]);
                (a, radius * dot(a, n) * f64::from(next(0.5, 1.0)))
            });
            let step_err = if case % 3 == 0 { 0.0 } else { next(0.0, 1e-4) };
            let within = |p: [f64; 3], short: f64| {
                let q = [p[0] - on[0], p[1] - on[1], p[2] - on[2]];
                dot(q, q) <= (radius * short).powi(2)
                    && axis.is_none_or(|(a, r)| dot(q, q) - dot(q, a).powi(2) <= (r * short).powi(2))
            };
            let sil = Silhouette::on_plane(on, n, radius, axis, &camera, step_err);
            let short = Silhouette::on_plane(
                on,
                n,
                radius * 0.95,
                axis.map(|(a, r)| (a, r * 0.95)),
                &camera,
                0.0,
            );
            if sil.is_all() {
                continue;
            }
            bounded += 1;
            let (f, du, dv) = (
                v64(camera.first_direction()),
                v64(camera.pixel_step()),
                v64(camera.scanline_step()),
            );
            let s = dot(on, n);
            for j in 0..size.height {
                for i in 0..size.width {
                    let (x, y) = (f64::from(i), f64::from(j));
                    let turn = f64::from(step_err);
                    let e = [
                        f64::from(next(-1.0, 1.0)) * turn / 2.0,
                        f64::from(next(-1.0, 1.0)) * turn / 2.0,
                        f64::from(next(-1.0, 1.0)) * turn / 2.0,
                    ];
                    let d = [
                        f[0] + x * du[0] + y * dv[0] + e[0],
                        f[1] + x * du[1] + y * dv[1] + e[1],
                        f[2] + x * du[2] + y * dv[2] + e[2],
                    ];
                    let t = s / dot(n, d);
                    if !(t > 0.0) {
                        continue;
                    }
                    let p = [t * d[0], t * d[1], t * d[2]];
                    if !within(p, 1.0) {
                        continue;
                    }
                    inside += 1;
                    let holds = |sil: Silhouette| {
                        sil.row_span(j, 0, size.width)
                            .is_some_and(|(lo, hi)| lo <= i && i < hi)
                    };
                    assert!(
                        holds(sil),
                        "case {case}: pixel ({i}, {j}) meets the disc, outside {sil:?}"
                    );
                    if within(p, 0.95) && !short.is_all() && !holds(short) {
                        // Inside the short disc too, yet outside its region: cannot be.
                        panic!("case {case}: pixel ({i}, {j}) outside the short region");
                    }
                    if !within(p, 0.95) && !short.is_all() && !holds(short) {
                        missed_short += 1;
                    }
                }
            }
        }
        assert!(
            bounded > 100 && inside > 10_000,
            "{bounded} bounded cases, {inside} pixels inside"
        );
        assert!(
            missed_short > 100,
            "a 5 % shorter disc missed only {missed_short} pixels"
        );
    }

    #[test]
    fn rows_hold_every_row_span() {
        let mut next = uniform(0x2545_f491_4f6c_dd1d);
        let check = |sil: Silhouette, (w, h): (u32, u32)| {
            let (j0, j1) = sil.rows(h);
            assert!(j0 <= j1 && j1 <= h, "{sil:?}: rows {j0}..{j1} of {h}");
            let Some(Ellipse { y0i, y0f, q, h0, .. }) = sil.get() else {
                return 0;
            };
            let mut spans = 0;
            for j in 0..h {
                let passes = !(Silhouette::row_cut(j, y0i, y0f, q, h0).1 < 0.0);
                assert_eq!(passes, (j0..j1).contains(&j), "{sil:?}: row {j}, rows {j0}..{j1}");
                if sil.row_span(j, 0, w).is_some() {
                    assert!(
                        (j0..j1).contains(&j),
                        "{sil:?}: row {j} has a span outside {j0}..{j1}"
                    );
                    spans += 1;
                }
            }
            spans
        };
        let mut spans = 0;
        for _ in 0..400 {
            let Some((camera, l, radius)) = random_view(&mut next) else {
                continue;
            };
            let size = camera.size();
            let margin = if next(0.0, 1.0) < 0.5 {
                0.0
            } else {
                next(0.0, 0.01)
            };
            let sil = Silhouette::new(l, radius, &camera, Margin::Linear, margin);
            spans += check(sil, (size.width, size.height));
        }
        // Random coefficients: centres near and past the image's ends, thin and tall.
        for _ in 0..2_000 {
            let y0 = next(-50.0, 350.0);
            let sil = Silhouette(Ellipse {
                y0i: y0.floor(),
                y0f: y0 - y0.floor(),
                q: next(0.0, 1.0).powi(4) * 50.0 + f32::MIN_POSITIVE,
                h0: next(-10.0, 1.0e4),
                xc0: next(-10.0, 300.0),
                kx: next(-2.0, 2.0),
            });
            spans += check(sil, (300, 300));
        }
        assert!(spans > 10_000, "too few rows with spans: {spans}");
        // `ALL` (q ≤ 0 or NaN) and ellipses whose coefficients are not finite.
        for (q, h0) in [
            (f32::NAN, 1.0),
            (0.0, 1.0),
            (-1.0, 1.0),
            (f32::INFINITY, 1.0),
            (1.0, f32::NAN),
        ] {
            let sil = Silhouette(Ellipse {
                y0i: 10.0,
                y0f: 0.5,
                q,
                h0,
                xc0: 5.0,
                kx: 0.0,
            });
            assert_eq!(sil.rows(48), (0, 48));
        }
        assert_eq!(Silhouette::ALL.rows(48), (0, 48));
        assert_eq!(Silhouette::ALL.rows(0), (0, 0));
    }

    /// `band_reach` contains every point of the ellipse in the band, and `band_inside`
    /// holds only columns whose whole vertical segment is inside, on random spheres
    /// seen by random cameras; probed on a fine grid, at the band's ends and at the
    /// rows where the left and right edges reach furthest (where a reach taken at the
    /// band's ends alone would be too narrow).
    #[test]
    fn band_reach_and_inside_hold_on_a_fine_grid() {
        let mut next = uniform(0x9E37_79B9_7F4A_7C15);
        let (mut probed, mut inside_probed, mut interior_extreme) = (0u32, 0u32, 0u32);
        for _ in 0..300 {
            let eye = Vec3::new(next(-2.0, 2.0), next(-2.0, 2.0), next(4.0, 9.0));
            let camera = Camera::new(
                eye,
                Vec3::new(next(-1.0, 1.0), next(-1.0, 1.0), 0.0),
                Vec3::new(0.0, 1.0, 0.0),
                next(0.4, 1.6),
                Size::new(64, 48),
            )
            .unwrap();
            let centre = Vec3::new(next(-3.0, 3.0), next(-3.0, 3.0), next(-3.0, 2.0));
            let radius = next(0.05, 1.5);
            let l = centre - eye;
            let Some(Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            }) = Silhouette::new(l, radius, &camera, Margin::Linear, 0.0).get()
            else {
                continue;
            };
            let sil = Silhouette::new(l, radius, &camera, Margin::Linear, 0.0);
            let reach = sil.reach_consts();
            // The ellipse in f64 from its own f32 coefficients.
            let y0 = f64::from(y0i) + f64::from(y0f);
            let inside = |x: f64, y: f64| {
                let dy = y - y0;
                let xc = f64::from(xc0) + f64::from(kx) * dy;
                (x - xc) * (x - xc) <= f64::from(h0) - f64::from(q) * dy * dy
            };
            let half_height = (f64::from(h0) / f64::from(q)).sqrt();
            let m = (f64::from(h0) / (f64::from(q) * (f64::from(q) + f64::from(kx) * f64::from(kx)))).sqrt();
            for j in 0..48u32 {
                for h in [0.0f32, 0.25, 0.375] {
                    let (yl, yh) = (f64::from(j) - f64::from(h), f64::from(j) + f64::from(h));
                    let mut ys: std::vec::Vec<f64> =
                        (0..=16).map(|k| yl + (yh - yl) * f64::from(k) / 16.0).collect();
                    // The edges' extreme rows, where they fall inside the band.
                    for e in [y0 - f64::from(kx) * m, y0 + f64::from(kx) * m] {
                        if e > yl && e < yh {
                            ys.push(e);
                            interior_extreme += 1;
                        }
                    }
                    ys.extend(
                        [y0 - half_height, y0 + half_height]
                            .iter()
                            .filter(|&&y| y >= yl && y <= yh),
                    );
                    let got = sil.band_reach(j, h, reach);
                    for &y in &ys {
                        let dy = y - y0;
                        let hw2 = f64::from(h0) - f64::from(q) * dy * dy;
                        if hw2 < 0.0 {
                            continue;
                        }
                        let xc = f64::from(xc0) + f64::from(kx) * dy;
                        for x in [xc - hw2.sqrt(), xc + hw2.sqrt()] {
                            let (lo, hi) = got.expect("the ellipse reaches this band");
                            assert!(
                                f64::from(lo) <= x && x <= f64::from(hi),
                                "row {j} ± {h}: point ({x}, {y}) outside reach {lo}..{hi}"
                            );
                            probed += 1;
                        }
                    }
                    if let Some((lo, hi)) = sil.band_inside(j, h) {
                        for k in 0..=8 {
                            let x = f64::from(lo) + (f64::from(hi) - f64::from(lo)) * f64::from(k) / 8.0;
                            for &y in &ys {
                                assert!(
                                    inside(x, y),
                                    "row {j} ± {h}: ({x}, {y}) in band_inside but outside"
                                );
                                inside_probed += 1;
                            }
                        }
                    }
                }
            }
        }
        assert!(
            probed > 10_000 && inside_probed > 10_000,
            "{probed} / {inside_probed}"
        );
        // The extreme rows were inside bands often: the case the clamp exists for.
        assert!(interior_extreme > 100, "{interior_extreme}");
    }

    /// The shrunk silhouette lies inside the enlarged one and both bracket the sphere's
    /// own (margins zero): its cut with a row is narrower, and it disappears for a
    /// sphere too small for the margins.
    #[test]
    fn inner_silhouette_is_inside_the_outer() {
        let camera = Camera::new(
            Vec3::new(0.0, 0.0, 10.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            0.8,
            Size::new(64, 48),
        )
        .unwrap();
        let l = Vec3::new(0.3, -0.2, -10.0);
        let outer = Silhouette::new(l, 1.0, &camera, Margin::Quadratic, 1e-6);
        let exact = Silhouette::new(l, 1.0, &camera, Margin::Linear, 0.0);
        let inner = Silhouette::inner(l, 1.0, &camera, Margin::Quadratic, 1e-6).unwrap();
        let width = |s: &Silhouette| match s.get() {
            Some(Ellipse { h0, .. }) => h0,
            None => f32::INFINITY,
        };
        assert!(width(&inner) < width(&exact) && width(&exact) < width(&outer));
        // Quadratic margin 2⁻¹⁷·|L|² ≈ 7.6e-4 against r² = 1e-4: nothing is proven.
        assert!(Silhouette::inner(l, 0.01, &camera, Margin::Quadratic, 0.0).is_none());
        assert!(Silhouette::inner(l, 0.01, &camera, Margin::Linear, 0.0).is_some());
    }
}

/// The cone around the camera's axis `w` that holds every primary ray through a pixel
/// centre (its half-angle `β` the angle to the farthest pixel centre): a sphere whose
/// enlarged angular radius `α` plus `β` is less than the angle `θ` between its centre
/// and the centre ray is met by no primary ray. Once per frame, and only for a frame
/// that leaves spheres out for its scale (`trace/frame.rs`); in `f32`, with every
/// bound loose enough for its rounding: `sin α` is taken as
/// `(r/|l|)·(1 + 2⁻¹⁰) + 2⁻⁸ + 2.002·step_err` (above either test margin's enlargement
/// and the stepping's, see [`Silhouette::new`]), and the cosines compared with a slack
/// of `10⁻⁵` (`α + β < π`, where the cosine decreases:
/// `θ > α + β ⇔ cos θ < cos α·cos β − sin α·sin β`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ViewCone {
    /// The camera's unit axis `w`.
    axis: Vec3,
    cos_b: f32,
    sin_b: f32,
    /// The angular enlargement `2⁻⁸ + 2.002·step_err`.
    widen: f32,
}

impl ViewCone {
    /// The camera's cone: around `w`, through the pixel centre farthest from it, at
    /// `((W − 1)/2, (H − 1)/2)` pixels on the image plane at distance `F·w` (`F` the
    /// first pixel's direction). `None` where that is not a positive distance.
    pub(crate) fn new(camera: &Camera, step_err: f32) -> Option<Self> {
        let size = camera.size();
        let axis = camera.w();
        let d = camera.first_direction().dot(axis);
        let x = (size.width.max(1) - 1) as f32 * 0.5 * camera.pixel_width();
        let y = (size.height.max(1) - 1) as f32 * 0.5 * camera.pixel_height();
        let tan_b = crate::math::sqrt_exact(x * x + y * y) / d;
        if !(d > 0.0 && tan_b.is_finite()) {
            return None;
        }
        let cos_b = 1.0 / crate::math::sqrt_exact(1.0 + tan_b * tan_b);
        Some(Self {
            axis,
            cos_b,
            sin_b: tan_b * cos_b,
            widen: 1.0 / 256.0 + 2.002 * step_err,
        })
    }

    /// Whether no primary ray meets the sphere `l = centre − eye`, radius `radius`.
    pub(crate) fn misses(&self, l: Vec3, radius: f32) -> bool {
        // Scaled to its largest coordinate first: no square overflows at 10³⁸.
        let m = l.max_abs();
        if !(m > 0.0 && m.is_finite()) {
            return false;
        }
        let Some(dir) = (l * (1.0 / m)).try_normalize() else {
            return false;
        };
        let len = (l * (1.0 / m)).dot(l * (1.0 / m));
        let sin_a = radius / m / crate::math::sqrt_exact(len) * (1.0 + 1.0 / 1024.0) + self.widen;
        if !(sin_a < 1.0) {
            return false;
        }
        let cos_a = crate::math::sqrt_exact(1.0 - sin_a * sin_a);
        self.axis.dot(dir) < cos_a * self.cos_b - sin_a * self.sin_b - 1e-5
    }
}
