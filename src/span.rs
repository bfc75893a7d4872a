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
//! half-width and one extra column on each side.
//!
//! When the enlarged sphere contains the eye or crosses the plane through the eye
//! parallel to the image, its silhouette is not a bounded ellipse (a parabola, a
//! hyperbola, or the whole image): that sphere is not culled ([`Silhouette::All`]).
//! The same fallback catches any non-finite coefficient.

use crate::camera::Camera;
use crate::vec3::Vec3;

/// How much a test's rounding can widen its hit set beyond the true silhouette.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Margin {
    /// Perpendicular-distance tests (robust, forward-differenced): linear in `|L|`.
    Linear,
    /// Tests that subtract squares of size `|L|²` (algebraic, geometric).
    Quadratic,
}

/// A sphere's silhouette for one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Silhouette {
    /// Not culled: every column of every row.
    All,
    /// The (enlarged) silhouette: for row `y`, columns
    /// `xc0 + kx·(y − y0) ± √(h0 − q·(y − y0)²)`, with the centre row split as
    /// `y0 = y0i + y0f` (`y0i` an integer, `|y0f| ≤ ½`) so that `j − y0` has one rounding.
    Ellipse {
        y0i: f32,
        y0f: f32,
        q: f32,
        h0: f32,
        xc0: f32,
        kx: f32,
    },
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
    /// The ellipse's extent; `None` when the silhouette is not a bounded ellipse.
    pub(crate) fn extent(&self) -> Option<Extent> {
        match *self {
            Silhouette::All => None,
            Silhouette::Ellipse { q, h0, .. } => Some(Extent {
                half_width: crate::math::sqrt_exact(h0),
                half_height: crate::math::sqrt_exact(h0 / q),
            }),
        }
    }

    /// The ellipse's bounding box `[x0, x1] × [y0, y1]` (image coordinates, pixel
    /// centres at integers) and a lower bound of its semi-minor axis (its area
    /// `π·h0/√q` over `π` times an upper bound of its semi-major axis, the box's
    /// half-diagonal); `None` when the silhouette is not a bounded ellipse.
    pub(crate) fn bounds(&self) -> Option<([f32; 4], f32)> {
        match *self {
            Silhouette::All => None,
            Silhouette::Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            } => {
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
    /// bound `step_err`. `All` whenever culling cannot be proven safe.
    pub(crate) fn new(l: Vec3, radius: f32, camera: &Camera, margin: Margin, step_err: f32) -> Self {
        let Some(ellipse) = ellipse(l, radius, camera, margin, step_err) else {
            return Silhouette::All;
        };
        ellipse
    }

    /// The columns `[lo, hi)` of row `j` (clamped to the visible `[i0, i1)`) whose
    /// rays can hit the sphere; `None` if none can.
    #[inline]
    pub(crate) fn row_span(&self, j: u32, i0: u32, i1: u32) -> Option<(u32, u32)> {
        match *self {
            Silhouette::All => Some((i0, i1)),
            Silhouette::Ellipse {
                y0i,
                y0f,
                q,
                h0,
                xc0,
                kx,
            } => {
                // Cut the ellipse with the scanline through the row's pixel centres.
                // `j − y0i` is exact (integers below 2²⁴), so dy has one rounding.
                let dy = (j as f32 - y0i) - y0f;
                // Slack 2⁻¹⁶·h0 covers the f32 rounding of h0 − q·dy² (≤ 3 ulp of
                // max(h0, q·dy²), and rows with q·dy² ≫ h0 are far outside anyway).
                let hw2 = (h0 - q * (dy * dy)) + h0 * (1.0 / 65536.0);
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

const TWO_M10: f64 = 1.0 / 1024.0;
const TWO_M16: f64 = 1.0 / 65_536.0;
const TWO_M17: f64 = 1.0 / 131_072.0;
const TWO_M18: f64 = 1.0 / 262_144.0;

/// The enlarged silhouette as an ellipse, or `None` when it is not a bounded ellipse.
fn ellipse(l: Vec3, radius: f32, camera: &Camera, margin: Margin, step_err: f32) -> Option<Silhouette> {
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
    // Enlarge the sphere: the test's rounding, then the stepping's.
    let r_eff = match margin {
        Margin::Linear => r * (1.0 + TWO_M16) + l_len * TWO_M18,
        Margin::Quadratic => libm::sqrt(r * r * (1.0 + TWO_M10) + l2 * TWO_M17),
    };
    let r_tot = r_eff + 2.0 * step_err * (1.0 + 1e-3) * l_len;
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
    (q > 0.0 && q.is_finite() && h0.is_finite() && kx.is_finite()).then_some(Silhouette::Ellipse {
        y0i: y0i as f32,
        y0f: (y0 - y0i) as f32,
        q,
        h0,
        xc0: xc0 as f32,
        kx,
    })
}
