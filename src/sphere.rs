//! Spheres and the ray–sphere intersection methods.
//!
//! Every test works with the ray `r(t) = eye + t·d` for an **unnormalised** direction
//! `d` (so `a = d·d` is general, and the fast square root never has to normalise a
//! ray), `L = centre − eye` and `c = |L|² − r²` computed once per frame, and returns the
//! nearest root with `0 < t < t_max`: the entry point, or the exit point when the eye
//! is inside the sphere. A tangent ray (discriminant exactly 0) is a hit; every NaN or
//! infinity that rounding could produce fails the `0 < t < t_max` comparison, so no
//! NaN leaves a test.

use embedded_graphics::pixelcolor::Rgb888;

use crate::error::SphereError;
use crate::math::{ExactSqrt, FastSqrt, SqrtFn};
use crate::render::{SphereTest, Sqrt};
use crate::vec3::Vec3;

/// A sphere: centre, radius and (8-bit sRGB) colour.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_raytracer::{Sphere, Vec3};
///
/// // `const`: lives in flash. `try_new` in a const context turns a bad sphere into a
/// // compile error instead of a run-time one.
/// static RED: Sphere = match Sphere::try_new(Vec3::new(0.0, 0.0, -3.0), 1.0, Rgb888::new(255, 0, 0)) {
///     Ok(s) => s,
///     Err(_) => panic!("invalid sphere"),
/// };
/// let t = RED.intersect_robust(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0));
/// assert_eq!(t, Some(2.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius; `> 0` for a valid sphere.
    pub radius: f32,
    /// Object colour.
    pub color: Rgb888,
}

impl Sphere {
    /// A sphere, unchecked (for `static` scenes whose numbers are known good).
    ///
    /// A non-positive or non-finite radius does not panic anywhere: such a sphere is
    /// simply never hit, or hit and shaded at the 0.3 floor.
    #[must_use]
    pub const fn new(center: Vec3, radius: f32, color: Rgb888) -> Self {
        Self {
            center,
            radius,
            color,
        }
    }

    /// A sphere, checked: finite centre and radius, radius `> 0`.
    pub const fn try_new(center: Vec3, radius: f32, color: Rgb888) -> Result<Self, SphereError> {
        if !(center.is_finite() && radius.is_finite()) {
            return Err(SphereError::NotFinite);
        }
        if !(radius > 0.0) {
            return Err(SphereError::RadiusNotPositive);
        }
        Ok(Self::new(center, radius, color))
    }

    /// Nearest hit `t > 0` of the ray `origin + t·dir` with the chosen method.
    #[must_use]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, test: SphereTest, sqrt: Sqrt) -> Option<f32> {
        let s = SphereConsts::new(self, origin, Vec3::ZERO);
        let a = dir.dot(dir);
        match (test, sqrt) {
            (SphereTest::Algebraic, Sqrt::Exact) => {
                <Algebraic as HitTest>::hit::<ExactSqrt>(&s, dir, a, f32::INFINITY)
            }
            (SphereTest::Algebraic, Sqrt::Fast) => {
                <Algebraic as HitTest>::hit::<FastSqrt>(&s, dir, a, f32::INFINITY)
            }
            (SphereTest::Geometric, Sqrt::Exact) => {
                <Geometric as HitTest>::hit::<ExactSqrt>(&s, dir, a, f32::INFINITY)
            }
            (SphereTest::Geometric, Sqrt::Fast) => {
                <Geometric as HitTest>::hit::<FastSqrt>(&s, dir, a, f32::INFINITY)
            }
            (SphereTest::Robust, Sqrt::Exact) => {
                <Robust as HitTest>::hit::<ExactSqrt>(&s, dir, a, f32::INFINITY)
            }
            (SphereTest::Robust, Sqrt::Fast) => {
                <Robust as HitTest>::hit::<FastSqrt>(&s, dir, a, f32::INFINITY)
            }
            // A single ray is an anchor: the forward-differenced test evaluated directly.
            (SphereTest::ForwardDiff | SphereTest::Auto, Sqrt::Exact) => {
                <ForwardDiff as HitTest>::hit::<ExactSqrt>(&s, dir, a, f32::INFINITY)
            }
            (SphereTest::ForwardDiff | SphereTest::Auto, Sqrt::Fast) => {
                <ForwardDiff as HitTest>::hit::<FastSqrt>(&s, dir, a, f32::INFINITY)
            }
        }
    }

    /// The slides' algebraic test: `a t² + b t + c = 0` with `a = d·d`,
    /// `b = 2 d·(eye − C)`, `c = |eye − C|² − r²`, discriminant `b² − 4ac`, roots
    /// `(−b ± √disc)/2a`.
    ///
    /// **Fails** for a sphere far away relative to its size: `b²` and `4ac` are both
    /// ≈ `4a|L|²` and their difference `4a(r² − dist²)` cancels catastrophically.
    /// Measured by the accuracy lab (`tests/stability.rs`): no error up to
    /// distance/radius 100, edge pixels flip from 178, half the disc is wrong at 3162,
    /// and from 17783 the f32 rounding of `|L|²` swamps `r²` and every ray is a hit. `−b − √disc` also cancels
    /// for the near root when the eye is close to the surface.
    #[must_use]
    pub fn intersect_algebraic(&self, origin: Vec3, dir: Vec3) -> Option<f32> {
        self.intersect(origin, dir, SphereTest::Algebraic, Sqrt::Exact)
    }

    /// The slides' geometric test: `t_ca = L·d̂`, `d² = |L|² − t_ca²`, miss if
    /// `d² > r²`, `t_hc = √(r² − d²)`, distance `t_ca ∓ t_hc`.
    ///
    /// **Fails** the same way as the algebraic form for far, small spheres: `|L|² − t_ca²`
    /// cancels catastrophically (measured: edge pixels from distance/radius 178). It also
    /// normalises the ray with the square root, so with [`Sqrt::Fast`] (up to 6 % off)
    /// `t_ca` and hence `d²` are wrong and coverage fails everywhere.
    #[must_use]
    pub fn intersect_geometric(&self, origin: Vec3, dir: Vec3) -> Option<f32> {
        self.intersect(origin, dir, SphereTest::Geometric, Sqrt::Exact)
    }

    /// The robust test of Haines et al. (Ray Tracing Gems, ch. 7): discriminant from
    /// the perpendicular vector, `r² − |L − (b/a)·d|²` with `b = L·d`, which has no
    /// cancellation between two large squares, and the stable roots `q = b + sign(b)·√(a·disc)`,
    /// `t = c/q` and `t = q/a` (no `−b + √…` cancellation).
    ///
    /// Measured with zero coverage errors up to distance/radius 1e5 in f32 (the largest
    /// the sweep reaches). Remaining failure: when `b = 0` and the
    /// discriminant is exactly 0 (eye exactly on the surface, ray tangent) `q = 0` and
    /// the ray is reported as a miss.
    #[must_use]
    pub fn intersect_robust(&self, origin: Vec3, dir: Vec3) -> Option<f32> {
        self.intersect(origin, dir, SphereTest::Robust, Sqrt::Exact)
    }
}

/// A sphere's per-frame constants, relative to the eye. Built once per frame so the
/// per-pixel tests only multiply and add.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SphereConsts {
    /// `L = centre − eye`.
    pub l: Vec3,
    /// `|L|²`.
    pub l2: f32,
    /// `r²`.
    pub r2: f32,
    /// `c = |L|² − r²` (negative: the eye is inside).
    pub c: f32,
    /// `L·w`, for the view-space normal.
    pub lw: f32,
    /// `1/r`.
    pub inv_r: f32,
    /// The object colour's channels as `f32`, for the shading.
    pub rgb: [f32; 3],
    /// Forward differencing along a scanline (per frame, see [`ForwardDiff`]): the
    /// pixel step `du`,
    pub du: Vec3,
    /// `X₁ = L × du`, the per-column change of `X = L × d`,
    pub x1: Vec3,
    /// `L·du`, the per-column change of `b = L·d`,
    pub ldu: f32,
    /// `r²·(du·du)` and `|X₁|²`,
    pub r2_uu: f32,
    pub x1x1: f32,
    /// the constant second difference of the discriminant, `2(r²·du·du − |X₁|²)`,
    pub dd2: f32,
    /// the anchor interval K (re-evaluate directly every K columns),
    pub anchor: u32,
    /// and [`Auto`]'s per-frame choice: forward differences (`true`) or robust.
    pub use_fd: bool,
}

impl SphereConsts {
    /// Per-frame constants for `sphere` seen from `eye`; `w` is the view direction.
    pub(crate) fn new(sphere: &Sphere, eye: Vec3, w: Vec3) -> Self {
        let l = sphere.center - eye;
        let l2 = l.dot(l);
        let r2 = sphere.radius * sphere.radius;
        Self {
            l,
            l2,
            r2,
            c: l2 - r2,
            lw: l.dot(w),
            inv_r: 1.0 / sphere.radius,
            rgb: crate::shade::channels(sphere.color),
            du: Vec3::ZERO,
            x1: Vec3::ZERO,
            ldu: 0.0,
            r2_uu: 0.0,
            x1x1: 0.0,
            dd2: 0.0,
            anchor: 1,
            use_fd: false,
        }
    }

    /// Adds the per-frame forward-differencing constants for the column step `du` and
    /// anchor interval `k` (≥ 1), and [`Auto`]'s choice given the pixel width `pw`.
    pub(crate) fn with_row_step(mut self, du: Vec3, k: u32, pw: f32) -> Self {
        let k = k.max(1);
        let x1 = self.l.cross(du);
        let x1x1 = x1.dot(x1);
        let r2_uu = self.r2 * du.dot(du);
        self.du = du;
        self.x1 = x1;
        self.ldu = self.l.dot(du);
        self.r2_uu = r2_uu;
        self.x1x1 = x1x1;
        self.dd2 = 2.0 * (r2_uu - x1x1);
        self.anchor = k;
        self.use_fd = auto_uses_forward_diff(self.c, self.r2, pw, k);
        self
    }
}

/// [`Auto`]'s rule for one sphere and frame: forward differences when their error bound
/// ([`ForwardDiff`]) moves a silhouette edge by at most 1/16 pixel, i.e.
/// `2⁻²⁴·K·(R + 2K) ≤ 1/16` with `R = r/(√(|L|² − r²)·pw)` the sphere's radius on screen
/// in pixels; the robust test otherwise — and always when the eye is inside (or on) the
/// sphere, where `R` is unbounded.
///
/// Why these two candidates: forward differences cost three additions per sphere and
/// pixel and are as well conditioned as the robust test (perpendicular distance via
/// `L × d`, no `|L|² − t²` cancellation), so no slides' test is cheaper *and*
/// sufficient: the algebraic and geometric tests cost a dot product and more per pixel
/// and fail from distance/radius 178 (measured).
#[must_use]
pub(crate) fn auto_uses_forward_diff(c: f32, r2: f32, pw: f32, k: u32) -> bool {
    if !(c > 0.0) {
        return false;
    }
    // Radius on screen in pixels (tangent-cone half-angle over the pixel angle at the
    // image centre). Assumption: off-axis in a wide field of view a sphere covers up to
    // 1/cos²θ more pixels than this, so there the 1/16 px promise holds only for the
    // centre-equivalent radius (not yet taken from the frame's ellipse).
    let r_px = crate::math::sqrt_exact(r2 / c) / pw;
    let k = k as f32;
    FD_EDGE_SCALE * k * (r_px + 2.0 * k) <= 1.0 / 16.0
}

/// `2⁻²⁴`: one rounding per forward-difference step, relative to the disc's range.
const FD_EDGE_SCALE: f32 = 1.0 / 16_777_216.0;

/// A ray–sphere test as a strategy type: the render loop is monomorphised over it.
pub(crate) trait HitTest {
    /// Nearest root `0 < t < t_max` of the ray `eye + t·d`, `a = d·d`.
    fn hit<Q: SqrtFn>(s: &SphereConsts, d: Vec3, a: f32, t_max: f32) -> Option<f32>;
}

/// The nearer of two roots `t0 ≤ t1` that lies in `(0, t_max)`. NaN fails every
/// comparison, so it never comes out.
#[inline(always)]
fn nearest(t0: f32, t1: f32, t_max: f32) -> Option<f32> {
    let t = if t0 > 0.0 { t0 } else { t1 };
    if t > 0.0 && t < t_max {
        Some(t)
    } else {
        None
    }
}

/// [`Sphere::intersect_algebraic`] as a strategy type.
pub(crate) struct Algebraic;
/// [`Sphere::intersect_geometric`] as a strategy type.
pub(crate) struct Geometric;
/// [`Sphere::intersect_robust`] as a strategy type.
pub(crate) struct Robust;

impl HitTest for Algebraic {
    #[inline(always)]
    fn hit<Q: SqrtFn>(s: &SphereConsts, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        // Compute quadratic sphere coefficients (origin − centre = −L).
        let b = -2.0 * d.dot(s.l);
        let disc = b * b - 4.0 * a * s.c;
        if disc < 0.0 {
            return None;
        }
        let root = Q::sqrt(disc);
        let two_a = 2.0 * a;
        nearest((-b - root) / two_a, (-b + root) / two_a, t_max)
    }
}

impl HitTest for Geometric {
    #[inline(always)]
    fn hit<Q: SqrtFn>(s: &SphereConsts, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        // Normalise the ray: t_ca is measured along the unit direction.
        let len = Q::sqrt(a);
        let t_ca = d.dot(s.l) / len;
        // A sphere behind an eye that is outside it cannot be hit.
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
        nearest((t_ca - t_hc) / len, (t_ca + t_hc) / len, t_max)
    }
}

impl HitTest for Robust {
    #[inline(always)]
    fn hit<Q: SqrtFn>(s: &SphereConsts, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
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

/// The nearer of the stable roots of `a t² − 2b t + c = 0` given `root = √(b² − ac)`:
/// `q = b + sign(b)·root` has no `b − root` cancellation, and the roots are `c/q` and
/// `q/a` (Haines et al.). Shared by the robust and the forward-differenced tests.
#[inline(always)]
fn stable_roots(s: &SphereConsts, b: f32, root: f32, a: f32, t_max: f32) -> Option<f32> {
    let q = if b >= 0.0 { b + root } else { b - root };
    let (t_near, t_far) = if b >= 0.0 {
        (s.c / q, q / a)
    } else {
        (q / a, s.c / q)
    };
    nearest(t_near, t_far, t_max)
}

/// A sphere test as the row loop sees it: it may keep per-row state for each sphere
/// (forward differences), and is told the column `i` it is evaluated at. Columns come
/// in increasing steps of one within a sphere's span; the span starts at `lo`.
pub(crate) trait RowTest {
    /// Per-row, per-sphere state.
    type State: Copy;
    /// The state at the start of a span `[lo, hi)`.
    fn row_start(lo: u32) -> Self::State;
    /// Nearest root `0 < t < t_max` for column `i` with direction `d`, `a = d·d`.
    fn hit<Q: SqrtFn>(
        st: &mut Self::State,
        s: &SphereConsts,
        d: Vec3,
        a: f32,
        i: u32,
        t_max: f32,
    ) -> Option<f32>;
}

macro_rules! stateless_row_test {
    ($($t:ty),+) => {$(
        impl RowTest for $t {
            type State = ();
            #[inline(always)]
            fn row_start(_lo: u32) {}
            #[inline(always)]
            fn hit<Q: SqrtFn>(_st: &mut (), s: &SphereConsts, d: Vec3, a: f32, _i: u32, t_max: f32) -> Option<f32> {
                <$t as HitTest>::hit::<Q>(s, d, a, t_max)
            }
        }
    )+};
}
stateless_row_test!(Algebraic, Geometric, Robust);

/// The forward-differenced scanline test ([`SphereTest::ForwardDiff`]).
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
/// at each span start and every `K` columns ([`FD_ANCHOR_INTERVAL`]).
///
/// **Error bound.** After `m < K` steps from an anchor, the additions' rounding gives
/// `|disc_fd − disc| ≤ 2⁻²³·m·(D + m·Δmax)` on top of the direct evaluation's, with
/// `D ≈ a·r²` the discriminant's range and `Δmax ≈ 2r²/R` its largest step (`R` the
/// sphere's radius on screen in pixels). Divided by the edge slope `≈ 2r²/R` this moves
/// a silhouette edge by at most `2⁻²⁴·K·(R + 2K)` pixels: `< 0.001` px for K = 16 at
/// R = 320, but several pixels for an unanchored 8192-wide row (tested).
pub(crate) struct ForwardDiff;

/// [`SphereTest::Auto`]: per sphere and frame, [`ForwardDiff`] or [`Robust`] by
/// [`auto_uses_forward_diff`].
pub(crate) struct Auto;

/// The anchor interval K of the forward-differenced test ([`SphereTest::ForwardDiff`]): direct re-evaluation every K columns.
///
/// Chosen from the measurement `cargo test --test speed forward_diff_error_against_k
/// -- --nocapture` (forward differences against the robust test, incremental stepping,
/// exact root): for every K from 1 to 8192 and every standard scene there is no
/// coverage flip and no colour more than one level off; the number of one-level
/// differences grows with K (crowd: 1 at K = 1, 27 at K = 16, 37 from K = 32 on; drift
/// 480×270: 1, 7, 20, 103 at K = 1, 16, 32, 1024) while the anchor's cost (≈ 25
/// operations) is already < 2 per pixel at K = 16. K = 16 keeps those differences to a
/// few dozen pixels per frame.
pub const FD_ANCHOR_INTERVAL: u32 = 16;

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
    /// Anchor: `b`, `disc` and `Δ` evaluated directly for direction `d` (`a = d·d`).
    #[inline(always)]
    fn anchor(s: &SphereConsts, d: Vec3, a: f32) -> (f32, f32, f32) {
        let b = d.dot(s.l);
        let x = s.l.cross(d);
        let disc = a * s.r2 - x.dot(x);
        // disc(i+1) − disc(i) = r²·(2 d·du + du·du) − (2 X·X₁ + |X₁|²).
        let da = 2.0 * d.dot(s.du);
        let delta = (s.r2 * da + s.r2_uu) - (2.0 * x.dot(s.x1) + s.x1x1);
        (b, disc, delta)
    }

    /// The robust stable roots from `b` and `disc = a·(r² − |perp|²)`.
    #[inline(always)]
    fn roots<Q: SqrtFn>(s: &SphereConsts, b: f32, disc: f32, a: f32, t_max: f32) -> Option<f32> {
        if disc < 0.0 {
            return None;
        }
        stable_roots(s, b, Q::sqrt(disc), a, t_max)
    }
}

/// One ray is an anchor: the forward-differenced test evaluated directly (what a
/// single-ray query such as [`Sphere::intersect`] means).
impl HitTest for ForwardDiff {
    #[inline(always)]
    fn hit<Q: SqrtFn>(s: &SphereConsts, d: Vec3, a: f32, t_max: f32) -> Option<f32> {
        let (b, disc, _) = Self::anchor(s, d, a);
        Self::roots::<Q>(s, b, disc, a, t_max)
    }
}

impl RowTest for ForwardDiff {
    type State = FdState;

    #[inline(always)]
    fn row_start(lo: u32) -> FdState {
        FdState {
            next: lo,
            b: 0.0,
            disc: 0.0,
            delta: 0.0,
        }
    }

    #[inline(always)]
    fn hit<Q: SqrtFn>(
        st: &mut FdState,
        s: &SphereConsts,
        d: Vec3,
        a: f32,
        i: u32,
        t_max: f32,
    ) -> Option<f32> {
        if i >= st.next {
            // Re-anchor: direct evaluation, next one K columns on.
            let (b, disc, delta) = Self::anchor(s, d, a);
            *st = FdState {
                next: i.saturating_add(s.anchor),
                b,
                disc,
                delta,
            };
        } else {
            // Forward differences: b linear, disc quadratic.
            st.b += s.ldu;
            st.disc += st.delta;
            st.delta += s.dd2;
        }
        Self::roots::<Q>(s, st.b, st.disc, a, t_max)
    }
}

impl RowTest for Auto {
    type State = FdState;

    #[inline(always)]
    fn row_start(lo: u32) -> FdState {
        <ForwardDiff as RowTest>::row_start(lo)
    }

    #[inline(always)]
    fn hit<Q: SqrtFn>(
        st: &mut FdState,
        s: &SphereConsts,
        d: Vec3,
        a: f32,
        i: u32,
        t_max: f32,
    ) -> Option<f32> {
        // A per-frame constant per sphere: the branch is predicted.
        if s.use_fd {
            <ForwardDiff as RowTest>::hit::<Q>(st, s, d, a, i, t_max)
        } else {
            <Robust as HitTest>::hit::<Q>(s, d, a, t_max)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Auto's rule at its edges: the eye inside or on the sphere, and the on-screen
    /// radius where `2⁻²⁴·K·(R + 2K)` crosses 1/16 px (K = 16: R = 65 504 px).
    #[test]
    fn auto_rule_boundaries() {
        let pw = 1e-3;
        // R = √(r²/c)/pw: choose c for a given R with r = 1.
        let c_for = |r_px: f32| 1.0 / (r_px * pw) / (r_px * pw);
        assert!(auto_uses_forward_diff(c_for(100.0), 1.0, pw, 16));
        assert!(auto_uses_forward_diff(c_for(65_000.0), 1.0, pw, 16));
        assert!(!auto_uses_forward_diff(c_for(66_000.0), 1.0, pw, 16));
        // A longer anchor interval shrinks the range: K = 4096 allows R ≤ 2⁸ − 2K < 0.
        assert!(!auto_uses_forward_diff(c_for(10.0), 1.0, pw, 4096));
        // Eye inside (c < 0), on the surface (c = 0), NaN: robust.
        assert!(!auto_uses_forward_diff(-1.0, 1.0, pw, 16));
        assert!(!auto_uses_forward_diff(0.0, 1.0, pw, 16));
        assert!(!auto_uses_forward_diff(f32::NAN, 1.0, pw, 16));
    }

    /// A single-ray query with the forward-differenced test is its direct evaluation,
    /// which agrees with the robust test on an easy ray.
    #[test]
    fn forward_diff_single_ray_is_direct() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0, Rgb888::new(1, 2, 3));
        let d = Vec3::new(0.05, -0.02, -1.0);
        let fd = s
            .intersect(Vec3::ZERO, d, SphereTest::ForwardDiff, Sqrt::Exact)
            .unwrap();
        let robust = s.intersect_robust(Vec3::ZERO, d).unwrap();
        assert!(
            (fd - robust).abs() <= 2.0 * f32::EPSILON * robust,
            "{fd} vs {robust}"
        );
        assert_eq!(
            s.intersect(
                Vec3::ZERO,
                Vec3::new(0.5, 0.0, -1.0),
                SphereTest::Auto,
                Sqrt::Exact
            ),
            None
        );
    }
}
