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
            (SphereTest::Algebraic, Sqrt::Exact) => Algebraic::hit::<ExactSqrt>(&s, dir, a, f32::INFINITY),
            (SphereTest::Algebraic, Sqrt::Fast) => Algebraic::hit::<FastSqrt>(&s, dir, a, f32::INFINITY),
            (SphereTest::Geometric, Sqrt::Exact) => Geometric::hit::<ExactSqrt>(&s, dir, a, f32::INFINITY),
            (SphereTest::Geometric, Sqrt::Fast) => Geometric::hit::<FastSqrt>(&s, dir, a, f32::INFINITY),
            (SphereTest::Robust, Sqrt::Exact) => Robust::hit::<ExactSqrt>(&s, dir, a, f32::INFINITY),
            (SphereTest::Robust, Sqrt::Fast) => Robust::hit::<FastSqrt>(&s, dir, a, f32::INFINITY),
        }
    }

    /// The slides' algebraic test: `a t² + b t + c = 0` with `a = d·d`,
    /// `b = 2 d·(eye − C)`, `c = |eye − C|² − r²`, discriminant `b² − 4ac`, roots
    /// `(−b ± √disc)/2a`.
    ///
    /// **Fails** for a sphere far away relative to its size: `b²` and `4ac` are both
    /// ≈ `4a|L|²` and their difference `4a(r² − dist²)` cancels catastrophically. Edge
    /// pixels start to flip from distance/radius ≈ 100; beyond ≈ 4096 the f32 rounding
    /// of `|L|²` swamps `r²` and the disc is all-or-nothing. `−b − √disc` also cancels
    /// for the near root when the eye is close to the surface.
    #[must_use]
    pub fn intersect_algebraic(&self, origin: Vec3, dir: Vec3) -> Option<f32> {
        self.intersect(origin, dir, SphereTest::Algebraic, Sqrt::Exact)
    }

    /// The slides' geometric test: `t_ca = L·d̂`, `d² = |L|² − t_ca²`, miss if
    /// `d² > r²`, `t_hc = √(r² − d²)`, distance `t_ca ∓ t_hc`.
    ///
    /// **Fails** the same way as the algebraic form for far, small spheres: `|L|² − t_ca²`
    /// cancels catastrophically (edge pixels from distance/radius ≈ 100). It also
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
    /// Holds to distance/radius ≥ 1e5 in f32. Remaining failure: when `b = 0` and the
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
    /// Object colour.
    pub color: Rgb888,
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
            color: sphere.color,
        }
    }
}

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
        // Stable roots: q has the sign of b, so b + sign(b)·√… never cancels.
        let root = Q::sqrt(a * disc);
        let q = if b >= 0.0 { b + root } else { b - root };
        let (t_near, t_far) = if b >= 0.0 {
            (s.c / q, q / a)
        } else {
            (q / a, s.c / q)
        };
        nearest(t_near, t_far, t_max)
    }
}
