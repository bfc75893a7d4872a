//! The ray–sphere tests as strategy types, one per [`SphereTest`](crate::SphereTest)
//! choice, over a sphere's per-frame geometry `SphereGeom`.
//!
//! Every test works with the ray `r(t) = eye + t·d` for an **unnormalised** direction
//! `d` (so `a = d·d` is general, and the fast square root never has to normalise a
//! ray), `L = centre − eye` and `c = |L|² − r²` computed once per frame, and returns the
//! nearest root with `0 < t < t_max`: the entry point, or the exit point when the eye
//! is inside the sphere. A tangent ray (discriminant exactly 0) is a hit; every NaN or
//! infinity that rounding could produce fails the `0 < t < t_max` comparison, so no
//! NaN leaves a test.
//!
//! A test may keep per-frame constants of its own (`TestStrategy::Consts`, e.g. the
//! forward differences' column step) and per-row state (`TestStrategy::State`); a
//! test that needs neither pays for neither.

use core::num::NonZeroU32;

use crate::camera::span::{Extent, Margin};
use crate::math::vec3::Vec3;
use crate::math::{SqrtFn, EDGE_TOLERANCE, UNIT_ROUNDOFF};

/// A sphere's per-frame geometry relative to the ray origin (the eye, for primary
/// rays).
///
/// Built once per frame so the per-pixel tests only multiply and add.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SphereGeom {
    /// `L = centre − origin`.
    pub l: Vec3,
    /// `|L|²`.
    pub l2: f32,
    /// `r²`.
    pub r2: f32,
    /// `c = |L|² − r²` (negative: the origin is inside).
    pub c: f32,
}

impl SphereGeom {
    /// The geometry of the sphere (`center`, `radius`) seen from `origin`, in units
    /// scaled by the power of two `scale` ([`Scale`]).
    #[inline(always)]
    pub(crate) fn new(center: Vec3, radius: f32, origin: Vec3, scale: Scale) -> Self {
        let l = (center - origin) * scale.0;
        let r = radius * scale.0;
        let l2 = l.dot(l);
        let r2 = r * r;
        Self {
            l,
            l2,
            r2,
            c: l2 - r2,
        }
    }

    /// The same sphere seen from `o` (relative to this geometry's origin, same units):
    /// a secondary ray's origin on a surface.
    #[inline(always)]
    pub(crate) fn seen_from(&self, o: Vec3) -> Self {
        let l = self.l - o;
        let l2 = l.dot(l);
        Self {
            l,
            l2,
            r2: self.r2,
            c: l2 - self.r2,
        }
    }
}

/// The power of two a frame's (or a query's) eye-relative lengths are multiplied by
/// before any product is formed, so that no square overflows or loses its precision to
/// subnormals.
///
/// It is the one nearest 1 that brings every size (largest eye-relative coordinate or
/// radius) into `[2⁻⁴⁰, 2⁵⁰)`. There the tests' squares and products
/// stay far inside `f32`'s normal range: a square at most `3·2¹⁰⁰`, times a ray
/// direction's `|d|² < 2¹⁶`, below `2¹¹⁸`; at least `2⁻⁸⁰` times the stepping's
/// smallest factors, above `2⁻¹²⁰`.
///
/// Multiplying by a power of two is exact, and every test, the silhouettes and the
/// shading are homogeneous in these lengths (a hit's `t` scales with them, `n·(−w)` not
/// at all), so a scaled frame computes exactly the numbers an unscaled one would have,
/// times powers of two: the same pixels, bit for bit, wherever the sizes fit — a
/// frame's largest at most about 2⁹⁰ times its smallest — and no cost per pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Scale(pub f32);

impl Scale {
    /// `e` with `2^e ≤ m < 2^(e+1)`, for a finite `m > 0` (subnormals included).
    fn exponent(m: f32) -> i32 {
        let bits = m.to_bits() & 0x7fff_ffff;
        let biased = (bits >> 23) as i32;
        if biased == 0 {
            // Subnormal: m = bits · 2⁻¹⁴⁹.
            (31 - bits.leading_zeros() as i32) - 149
        } else {
            biased - 127
        }
    }

    /// The scale for a frame whose sizes run from `lo` to `hi` (finite, `0 < lo ≤ hi`);
    /// `None` where no normal `f32` power of two fits (`hi/lo` beyond about 2⁹⁰).
    ///
    /// The scale is `2^k` with `k` nearest 0 such that `lo·2^k ≥ 2⁻⁴⁰` and
    /// `hi·2^k < 2⁵⁰`.
    pub(crate) fn for_range(lo: f32, hi: f32) -> Option<Self> {
        const LO: i32 = -40;
        const HI: i32 = 50;
        let k_min = LO - Self::exponent(lo);
        let k_max = HI - 1 - Self::exponent(hi);
        let k = if k_min > 0 {
            k_min
        } else if k_max < 0 {
            k_max
        } else {
            0
        };
        if k < k_min || k > k_max || !(-126..=127).contains(&k) {
            return None;
        }
        Some(Scale(f32::from_bits(((127 + k) as u32) << 23)))
    }

    /// The scale for the largest eye-relative coordinate or radius `m` alone (a query):
    /// [`Self::for_range`] of `m` to `m`; 1 for 0 or a non-finite `m`.
    pub(crate) fn for_magnitude(m: f32) -> Self {
        if !m.is_finite() || m <= 0.0 {
            return Scale(1.0);
        }
        Self::for_range(m, m).unwrap_or(Scale(1.0))
    }

    /// The scale for spheres seen from `origin`.
    ///
    /// Once per frame: out of line and optimised for size (`cold`), not unrolled.
    #[cold]
    #[inline(never)]
    pub(crate) fn for_spheres<'s>(
        spheres: impl IntoIterator<Item = &'s crate::scene::sphere::Sphere>,
        origin: Vec3,
    ) -> Self {
        let mut m = 0.0f32;
        for s in spheres {
            // Comparisons pass NaN over: a NaN sphere never decides the scale.
            for x in [(s.center - origin).max_abs(), s.radius.abs()] {
                if x > m {
                    m = x;
                }
            }
        }
        Self::for_magnitude(m)
    }

    /// A ray parameter in scaled units back in the caller's: exact (a power of two).
    #[inline(always)]
    pub(crate) fn unscale_t(self, t: f32) -> f32 {
        t / self.0
    }
}

/// What a test may need of the frame for its per-sphere constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowGeometry {
    /// The column step `du` of the ray direction.
    pub du: Vec3,
    /// The forward differences' anchor interval K (≥ 1).
    pub anchor: u32,
    /// The pixel width on the image plane.
    pub pixel_width: f32,
}

/// A ray–sphere test as a strategy type: the render loop and the single-ray queries are
/// monomorphised over it.
pub(crate) trait TestStrategy {
    /// Per-frame, per-sphere constants beyond the geometry.
    type Consts: Copy;
    /// Per-row, per-sphere state.
    type State: Copy;
    /// How far the test's rounding can widen its hit set (span culling's margin).
    const MARGIN: Margin;
    /// Whether this is [`Auto`], which a frame of a scene holding more than
    /// [`AUTO_FD_CAPACITY`] spheres replaces by [`Robust`].
    const AUTO: bool = false;
    /// The per-frame constants of one sphere; `extent()` computes its silhouette's size
    /// on the image (`None` when it is not a bounded ellipse), for a test that needs it.
    fn consts(g: &SphereGeom, row: &RowGeometry, extent: impl FnOnce() -> Option<Extent>) -> Self::Consts;
    /// One ray on its own: nearest root `0 < t < t_max` of `origin + t·d`, `a = d·d`.
    fn ray<Q: SqrtFn>(g: &SphereGeom, d: Vec3, a: f32, t_max: f32) -> Option<f32>;
    /// The state for a row whose span starts at column `span_lo` of the *whole* image
    /// and whose first evaluated column is `first`.
    ///
    /// `first > span_lo` where the render is clipped on the left. `dir_at(i)` is the stepping's direction at column `i` of
    /// this row, exactly as a whole render computes it. A test with row state must
    /// leave it as a whole render would have it before column `first`, so that a pixel
    /// never depends on the clip.
    fn row_start(
        g: &SphereGeom,
        c: &Self::Consts,
        span_lo: u32,
        first: u32,
        dir_at: impl FnMut(u32) -> Vec3,
    ) -> Self::State;
    /// Within a row: nearest root for column `i` with direction `d`.
    ///
    /// Columns come in increasing steps of one within a sphere's span; the span starts
    /// at `lo`.
    fn hit<Q: SqrtFn>(
        st: &mut Self::State,
        g: &SphereGeom,
        c: &Self::Consts,
        d: Vec3,
        a: f32,
        i: u32,
        t_max: f32,
    ) -> Option<f32>;
}

/// The nearer of two roots `t0 ≤ t1` that lies in `(0, t_max)`.
///
/// NaN fails every comparison, so it never comes out. `t1` is computed only when `t0` is not positive:
/// a hit in front of an eye outside the sphere pays one division, not two.
#[inline(always)]
fn nearest(t0: f32, t1: impl FnOnce() -> f32, t_max: f32) -> Option<f32> {
    let t = if t0 > 0.0 { t0 } else { t1() };
    if t > 0.0 && t < t_max {
        Some(t)
    } else {
        None
    }
}

/// A test with no constants and no row state: the row loop calls the single-ray test.
macro_rules! stateless {
    ($($t:ty => $margin:expr),+) => {$(
        impl TestStrategy for $t {
            type Consts = ();
            type State = ();
            const MARGIN: Margin = $margin;
            #[inline(always)]
            fn consts(_g: &SphereGeom, _row: &RowGeometry, _extent: impl FnOnce() -> Option<Extent>) {}
            #[inline(always)]
            fn ray<Q: SqrtFn>(g: &SphereGeom, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
                Self::test::<Q>(g, d, a, t_max)
            }
            #[inline(always)]
            fn row_start(_g: &SphereGeom, _c: &(), _span_lo: u32, _first: u32, _dir_at: impl FnMut(u32) -> Vec3) {}
            #[inline(always)]
            fn hit<Q: SqrtFn>(_st: &mut (), g: &SphereGeom, _c: &(), d: Vec3, a: f32, _i: u32, t_max: f32) -> Option<f32> {
                Self::test::<Q>(g, d, a, t_max)
            }
        }
    )+};
}

/// [`SphereTest::Algebraic`](crate::SphereTest::Algebraic): the slides' quadratic.
pub(crate) struct Algebraic;
/// [`SphereTest::Geometric`](crate::SphereTest::Geometric): the slides' `t_ca`/`d²`.
pub(crate) struct Geometric;
/// [`SphereTest::Robust`](crate::SphereTest::Robust): Haines et al.
pub(crate) struct Robust;

stateless!(
    Algebraic => Margin::Quadratic,
    Geometric => Margin::Quadratic,
    Robust => Margin::Linear
);

impl Algebraic {
    #[inline(always)]
    fn test<Q: SqrtFn>(s: &SphereGeom, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        // Compute quadratic sphere coefficients (origin − centre = −L).
        let b = -2.0 * d.dot(s.l);
        let disc = b * b - 4.0 * a * s.c;
        if disc < 0.0 {
            return None;
        }
        let root = Q::sqrt(disc);
        let two_a = 2.0 * a;
        nearest((-b - root) / two_a, || (-b + root) / two_a, t_max)
    }
}

impl Geometric {
    #[inline(always)]
    fn test<Q: SqrtFn>(s: &SphereGeom, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        // Normalise the ray: t_ca is measured along the unit direction.
        let len = Q::sqrt(a);
        let t_ca = d.dot(s.l) / len;
        // A sphere behind an origin that is outside it cannot be hit.
        if t_ca < 0.0 && s.c > 0.0 {
            return None;
        }
        // Squared distance from the centre to the ray, by Pythagoras.
        let d2 = s.l2 - t_ca * t_ca;
        if d2 > s.r2 {
            return None;
        }
        let t_hc = Q::sqrt(s.r2 - d2);
        // Distances along the unit ray, back to the parameter of `d`.
        nearest((t_ca - t_hc) / len, || (t_ca + t_hc) / len, t_max)
    }
}

impl Robust {
    #[inline(always)]
    fn test<Q: SqrtFn>(s: &SphereGeom, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        let b = d.dot(s.l);
        // Discriminant from the perpendicular from the centre to the ray (no cancellation).
        let perp = s.l - d * (b / a);
        let disc = s.r2 - perp.dot(perp);
        if disc < 0.0 {
            return None;
        }
        stable_roots(s, b, Q::sqrt(a * disc), a, t_max)
    }
}

/// The nearer of the stable roots of `a t² − 2b t + c = 0` given `root = √(b² − ac)`.
///
/// `q = b + sign(b)·root` has no `b − root` cancellation, and the roots are `c/q` and
/// `q/a` (Haines et al.). Shared by the robust and the forward-differenced tests.
#[inline(always)]
fn stable_roots(s: &SphereGeom, b: f32, root: f32, a: f32, t_max: f32) -> Option<f32> {
    if b >= 0.0 {
        let q = b + root;
        nearest(s.c / q, || q / a, t_max)
    } else {
        let q = b - root;
        nearest(q / a, || s.c / q, t_max)
    }
}

/// [`SphereTest::ForwardDiff`](crate::SphereTest::ForwardDiff): the forward-differenced
/// scanline test.
///
/// Along a scanline the direction is linear in the column, `d(i) = d₀ + i·du`, so with
/// `X = L × d` (linear too):
/// - `b(i) = L·d` is linear: `b += L·du`;
/// - the discriminant `disc(i) = a·r² − |X|²` (= `a·(r² − |perp|²)`, the robust
///   test's discriminant times `a`, no `|L|² − t²` cancellation) is a quadratic:
///   `disc += Δ`, `Δ += 2(r²·du·du − |X₁|²)`.
///
/// Three additions per sphere and pixel and a comparison; the square root only where
/// `disc ≥ 0`, then the robust stable roots `q = b ± √disc`, `t = c/q`, `q/a`.
/// `b`, `disc` and `Δ` are **anchored** (evaluated directly from the stepped direction)
/// at each span start and every `K` columns after it ([`FD_ANCHOR_INTERVAL`]). The span
/// start is the whole image's, not the visible part's: a render clipped on the left
/// replays the anchor before its first column and the differences up to it, so every
/// pixel is the whole render's, bit for bit.
///
/// **Error bound.** After `m < K` steps from an anchor, the additions' rounding gives
/// `|disc_fd − disc| ≤ 2⁻²³·m·(D + m·Δmax)` on top of the direct evaluation's, with
/// `D ≈ a·r²` the discriminant's range and `Δmax ≈ 2r²/R` its largest step (`R` the
/// sphere's radius on screen in pixels). Divided by the edge slope `≈ 2r²/R` this moves
/// a silhouette edge by at most `2⁻²⁴·K·(R + 2K)` pixels: `< 0.001` px for K = 16 at
/// R = 320, but several pixels for an unanchored 8192-wide row (tested).
pub(crate) struct ForwardDiff;

/// [`SphereTest::Auto`](crate::SphereTest::Auto): per sphere and frame, [`ForwardDiff`]
/// or [`Robust`] by [`auto_uses_forward_diff`].
pub(crate) struct Auto;

/// The anchor interval K of the forward-differenced test
/// ([`SphereTest::ForwardDiff`](crate::SphereTest::ForwardDiff)): direct re-evaluation
/// every K columns.
///
/// Chosen from the measurement in `docs/accuracy.md` ("The anchor interval of the
/// forward differences"): for every K from 1 to 8192 and every standard scene there is
/// no coverage flip and no colour more than one level off, and the number of one-level
/// differences grows with K, while the anchor's cost (≈ 25 operations) is already < 2
/// per pixel at K = 16. K = 16 keeps those differences to a few dozen pixels per frame
/// (`tests/api/speed.rs`' `forward_diff_error_against_k` asserts the chosen K is as
/// good as K = 1).
pub const FD_ANCHOR_INTERVAL: u32 = 16;

/// The most spheres a scene may hold for
/// [`SphereTest::Auto`](crate::SphereTest::Auto) to take forward differences.
///
/// A frame of a scene holding more is drawn with the robust test for every sphere, bit
/// for bit `Robust`'s render. The pixels follow the spheres a scene holds, never its type. A
/// render without lights, planes or mirrors of a scene type with a larger capacity
/// (`Scene<64>`) holding at most this many spheres builds its per-sphere data for this
/// many, not for the capacity (the path with lights keeps its capacity's arrays).
///
/// Why: a frame's per-sphere data is sized by its capacity, and forward differences
/// keep constants and row state for every sphere, where the robust test keeps none. With
/// this rule the `f32` render of a `Scene<64>` without lights stays within the 6 KiB of
/// stack the Cortex-M4F firmware is held to, whichever choice the rule makes (the
/// integer kernel of a chip without an FPU keeps its own per-sphere data). The robust
/// test costs the 64-sphere `crowd` about what forward differences cost on the
/// Cortex-M4F, and more on a host with fast division and on a chip without an FPU. The
/// stack and instruction figures, from `bash .ci/firmware`: `docs/firmware.md` ("On a
/// Cortex-M4F", Stack); the host's: `docs/speed_vs_accuracy.md`.
///
/// ```
/// use embedded_graphics::{pixelcolor::Rgb888, prelude::*};
/// use embedded_raytracer::{AUTO_FD_CAPACITY, Camera, Method, Render, Scene, Sphere, SphereTest, Sqrt, Stepping, Vec3};
///
/// // A row of small spheres, one more than the limit.
/// let mut scene: Scene<64> = Scene::new(Rgb888::BLACK);
/// for k in 0..=AUTO_FD_CAPACITY {
///     let x = k as f32 * 0.3 - 5.0;
///     scene.push(Sphere::new(Vec3::new(x, 0.0, 0.0), 0.2, Rgb888::WHITE))?;
/// }
/// let camera = Camera::new(Vec3::new(0.0, 0.0, 8.0), Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0),
///     1.2, Size::new(96, 32))?;
/// let pixels = |test| {
///     let mut out = Vec::new();
///     let render: Render<64, Rgb888> = Render::new(&scene, &camera);
///     render
///         .with_method(Method::new(Stepping::Direct, test, Sqrt::Exact))
///         .trace(|s| out.push((s.hit.map(|h| h.t.to_bits()), s.color)));
///     out
/// };
/// assert!(pixels(SphereTest::Auto) == pixels(SphereTest::Robust));
/// // (Forward differences round differently here, so the test is the robust one.)
/// assert!(pixels(SphereTest::ForwardDiff) != pixels(SphereTest::Robust));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub const AUTO_FD_CAPACITY: usize = 32;

/// The forward differences' per-frame constants of one sphere.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FdConsts {
    /// The pixel step `du`,
    du: Vec3,
    /// `X₁ = L × du`, the per-column change of `X = L × d`,
    x1: Vec3,
    /// `L·du`, the per-column change of `b = L·d`,
    ldu: f32,
    /// `r²·(du·du)` and `|X₁|²`,
    r2_uu: f32,
    x1x1: f32,
    /// the constant second difference of the discriminant, `2(r²·du·du − |X₁|²)`,
    dd2: f32,
    /// the anchor interval K (re-evaluate directly every K columns; non-zero, so the
    /// division by it has no panic path),
    anchor: NonZeroU32,
    /// and [`Auto`]'s per-frame choice: forward differences (`true`) or robust.
    use_fd: bool,
}

impl FdConsts {
    #[inline(always)]
    fn new(g: &SphereGeom, row: &RowGeometry, extent: Option<Extent>) -> Self {
        let du = row.du;
        let x1 = g.l.cross(du);
        let x1x1 = x1.dot(x1);
        let r2_uu = g.r2 * du.dot(du);
        let anchor = NonZeroU32::new(row.anchor).unwrap_or(NonZeroU32::MIN);
        Self {
            du,
            x1,
            ldu: g.l.dot(du),
            r2_uu,
            x1x1,
            dd2: 2.0 * (r2_uu - x1x1),
            anchor,
            use_fd: auto_uses_forward_diff(g.c, g.r2, row.pixel_width, anchor.get(), extent),
        }
    }
}

/// [`Auto`]'s rule for one sphere and frame: forward differences where their error
/// bound ([`ForwardDiff`]) moves a silhouette edge by at most [`EDGE_TOLERANCE`]
/// (1/16 pixel), the robust test otherwise.
///
/// The robust test always where the eye is inside (or on) the sphere or its silhouette
/// is not a bounded ellipse (`extent` is `None`).
///
/// The bound, with `u = 2⁻²⁴`, `K` the anchor interval, `Rx` the silhouette's largest
/// half-width in columns (from the frame's ellipse, off-axis growth included), `Ry` its
/// half-height in rows and `R₀ = r/(√(|L|² − r²)·pw)` a lower bound of its half-width
/// (the image-centre size, with the pixel's real width):
///
/// `u·K·(Rx² + K² + 2K·max(Rx, K)) / (2·R₀) · max(1, Ry/R₀) ≤ 1/16`.
///
/// It is the forward differences' disc error after up to K steps,
/// `u·K·(Dmax + K·Δmax)` with `Dmax ≤ k(Rx² + K²)` and `Δmax ≤ 2k·max(Rx, K)` (the
/// columns stepped from an anchor reach K past the silhouette's centre), divided by the
/// smallest gradient of the disc on the silhouette, `2k·R₀` at its sides and
/// `2k·R₀²/Ry` at its top and bottom (`k` the disc's curvature per column²). For
/// spheres much larger than K pixels it is `≈ u·K·Rx/2`: forward differences up to
/// `Rx ≈ 2¹⁷` px at K = 16; for spheres much smaller than a pixel the `K²/R₀` term
/// rules them out (below `R₀ ≈ 0.006` px at K = 16), and so do very non-square pixels,
/// where a sphere a fraction of a column wide spans many rows.
///
/// Why these two candidates: forward differences cost three additions per sphere and
/// pixel and are as well conditioned as the robust test (perpendicular distance via
/// `L × d`, no `|L|² − t²` cancellation), so no slides' test is cheaper *and*
/// sufficient: the algebraic and geometric tests cost a dot product and more per pixel
/// and fail for far, small spheres (`docs/accuracy.md`, "Failure points").
#[must_use]
pub(crate) fn auto_uses_forward_diff(c: f32, r2: f32, pw: f32, k: u32, extent: Option<Extent>) -> bool {
    let Some(extent) = extent else {
        return false;
    };
    if !(c > 0.0) {
        return false;
    }
    let r0 = crate::math::sqrt_exact(r2 / c) / pw;
    let rx = extent.half_width.max(r0);
    let k = k as f32;
    let disc_error = UNIT_ROUNDOFF * k * (rx * rx + k * k + 2.0 * k * rx.max(k));
    let aspect = (extent.half_height / r0).max(1.0);
    // NaN and infinities (a zero-width sphere) fail the comparison: robust.
    disc_error / (2.0 * r0) * aspect <= EDGE_TOLERANCE
}

/// Per-row forward-differencing state of one sphere.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FdState {
    /// Column of the next direct evaluation.
    next: u32,
    /// `b = L·d`, `disc = a·r² − |L × d|²` and `Δ = disc(i+1) − disc(i)` at the current column.
    b: f32,
    disc: f32,
    delta: f32,
}

impl ForwardDiff {
    /// Direct evaluation of `b = L·d` and `disc = a·r² − |X|²` with `X = L × d`.
    #[inline(always)]
    fn direct(s: &SphereGeom, d: Vec3, a: f32) -> (f32, f32, Vec3) {
        let b = d.dot(s.l);
        let x = s.l.cross(d);
        let disc = a * s.r2 - x.dot(x);
        (b, disc, x)
    }

    /// Anchor: `b`, `disc` and `Δ` evaluated directly for direction `d` (`a = d·d`).
    #[inline(always)]
    fn anchor(s: &SphereGeom, c: &FdConsts, d: Vec3, a: f32, i: u32) -> FdState {
        let (b, disc, x) = Self::direct(s, d, a);
        // disc(i+1) − disc(i) = r²·(2 d·du + du·du) − (2 X·X₁ + |X₁|²).
        let da = 2.0 * d.dot(c.du);
        let delta = (s.r2 * da + c.r2_uu) - (2.0 * x.dot(c.x1) + c.x1x1);
        FdState {
            next: i.saturating_add(c.anchor.get()),
            b,
            disc,
            delta,
        }
    }

    /// A state that anchors at column `next` (before any evaluation).
    #[inline(always)]
    fn lazy(next: u32) -> FdState {
        FdState {
            next,
            b: 0.0,
            disc: 0.0,
            delta: 0.0,
        }
    }

    /// The state a whole render has before column `first`: the anchor at column `p`
    /// (direction `dir_at(p)`), then the differences up to `first − 1`.
    ///
    /// Only renders clipped on the left get here, so it stays out of line (and off the pixel loop's stack).
    #[cold]
    #[inline(never)]
    fn replay(
        g: &SphereGeom,
        c: &FdConsts,
        p: u32,
        first: u32,
        mut dir_at: impl FnMut(u32) -> Vec3,
    ) -> FdState {
        let d = dir_at(p);
        let mut st = Self::anchor(g, c, d, d.dot(d), p);
        for _ in p + 1..first {
            Self::step(&mut st, c);
        }
        st
    }

    /// One column on: `b` linear, `disc` quadratic.
    #[inline(always)]
    fn step(st: &mut FdState, c: &FdConsts) {
        st.b += c.ldu;
        st.disc += st.delta;
        st.delta += c.dd2;
    }

    /// The robust stable roots from `b` and `disc = a·(r² − |perp|²)`.
    #[inline(always)]
    fn roots<Q: SqrtFn>(s: &SphereGeom, b: f32, disc: f32, a: f32, t_max: f32) -> Option<f32> {
        if disc < 0.0 {
            return None;
        }
        stable_roots(s, b, Q::sqrt(disc), a, t_max)
    }
}

impl TestStrategy for ForwardDiff {
    type Consts = FdConsts;
    type State = FdState;
    const MARGIN: Margin = Margin::Linear;

    #[inline(always)]
    fn consts(g: &SphereGeom, row: &RowGeometry, _extent: impl FnOnce() -> Option<Extent>) -> FdConsts {
        // Forward differences everywhere: `use_fd` is Auto's and stays unread here.
        FdConsts::new(g, row, None)
    }

    /// One ray is an anchor: the forward-differenced test evaluated directly.
    #[inline(always)]
    fn ray<Q: SqrtFn>(g: &SphereGeom, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        let (b, disc, _) = Self::direct(g, d, a);
        Self::roots::<Q>(g, b, disc, a, t_max)
    }

    fn row_start(
        g: &SphereGeom,
        c: &FdConsts,
        span_lo: u32,
        first: u32,
        dir_at: impl FnMut(u32) -> Vec3,
    ) -> FdState {
        // The anchor a whole render would use last before `first`: the span start, or
        // a multiple of K after it.
        let anchor = first
            .checked_sub(span_lo)
            .map(|gap| span_lo + gap / c.anchor * c.anchor.get())
            .filter(|&p| p < first);
        match anchor {
            Some(p) => Self::replay(g, c, p, first, dir_at),
            // The next column evaluated is an anchor: evaluate it there.
            None => Self::lazy(first.max(span_lo)),
        }
    }

    #[inline(always)]
    fn hit<Q: SqrtFn>(
        st: &mut FdState,
        g: &SphereGeom,
        c: &FdConsts,
        d: Vec3,
        a: f32,
        i: u32,
        t_max: f32,
    ) -> Option<f32> {
        if i >= st.next {
            // Re-anchor: direct evaluation, next one K columns on.
            *st = Self::anchor(g, c, d, a, i);
        } else {
            Self::step(st, c);
        }
        Self::roots::<Q>(g, st.b, st.disc, a, t_max)
    }
}

impl TestStrategy for Auto {
    type Consts = FdConsts;
    type State = FdState;
    const MARGIN: Margin = Margin::Linear;
    const AUTO: bool = true;

    #[inline(always)]
    fn consts(g: &SphereGeom, row: &RowGeometry, extent: impl FnOnce() -> Option<Extent>) -> FdConsts {
        FdConsts::new(g, row, extent())
    }

    /// One ray: as [`ForwardDiff`] (an anchor).
    #[inline(always)]
    fn ray<Q: SqrtFn>(g: &SphereGeom, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        <ForwardDiff as TestStrategy>::ray::<Q>(g, d, a, t_max)
    }

    fn row_start(
        g: &SphereGeom,
        c: &FdConsts,
        span_lo: u32,
        first: u32,
        dir_at: impl FnMut(u32) -> Vec3,
    ) -> FdState {
        if c.use_fd {
            <ForwardDiff as TestStrategy>::row_start(g, c, span_lo, first, dir_at)
        } else {
            // The robust test keeps no state.
            ForwardDiff::lazy(first)
        }
    }

    #[inline(always)]
    fn hit<Q: SqrtFn>(
        st: &mut FdState,
        g: &SphereGeom,
        c: &FdConsts,
        d: Vec3,
        a: f32,
        i: u32,
        t_max: f32,
    ) -> Option<f32> {
        // A per-frame constant per sphere: the branch is predicted.
        if c.use_fd {
            <ForwardDiff as TestStrategy>::hit::<Q>(st, g, c, d, a, i, t_max)
        } else {
            Robust::test::<Q>(g, d, a, t_max)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Auto's rule at its edges: the eye inside or on the sphere, no bounded
    /// silhouette, spheres too large or too small, and a sphere far narrower than it is
    /// tall.
    ///
    /// Too large is `R ≈ 2¹⁷` px at `K = 16`, too small `R ≈ 0.006` px; far narrower
    /// comes from very non-square pixels.
    #[test]
    fn auto_rule_boundaries() {
        let pw = 1e-3;
        // R₀ = √(r²/c)/pw: choose c for a given R₀ with r = 1.
        let c_for = |r_px: f32| 1.0 / (r_px * pw) / (r_px * pw);
        let round = |r: f32| {
            Some(Extent {
                half_width: r,
                half_height: r,
            })
        };
        let fd = |r: f32, k: u32| auto_uses_forward_diff(c_for(r), 1.0, pw, k, round(r));
        assert!(fd(100.0, 16));
        assert!(fd(120_000.0, 16));
        assert!(!fd(140_000.0, 16));
        assert!(fd(0.007, 16));
        assert!(!fd(0.005, 16));
        // A longer anchor interval shrinks the range from both ends.
        assert!(fd(10.0, 64));
        assert!(!fd(10.0, 4096));
        // Much taller than wide: the top and bottom edges move by Ry/R₀ more.
        let tall = Some(Extent {
            half_width: 2.0,
            half_height: 50_000.0,
        });
        assert!(!auto_uses_forward_diff(c_for(2.0), 1.0, pw, 16, tall));
        // No bounded silhouette; eye inside (c < 0), on the surface (c = 0), NaN: robust.
        assert!(!auto_uses_forward_diff(c_for(100.0), 1.0, pw, 16, None));
        assert!(!auto_uses_forward_diff(-1.0, 1.0, pw, 16, round(1.0)));
        assert!(!auto_uses_forward_diff(0.0, 1.0, pw, 16, round(1.0)));
        assert!(!auto_uses_forward_diff(f32::NAN, 1.0, pw, 16, round(1.0)));
    }
}
