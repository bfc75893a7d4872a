//! The sphere primitive: its checked constructor and the single-ray queries, which go
//! through the one dispatch to the test strategy types of [`intersect`](crate::intersect).

use embedded_graphics::pixelcolor::Rgb888;

use crate::dispatch::{dispatch_ray, Visit};
use crate::error::SphereError;
use crate::intersect::{Scale, SphereGeom, TestStrategy};
use crate::material::Material;
use crate::math::SqrtFn;
use crate::method::{SphereTest, Sqrt};
use crate::stepping::Stepper;
use crate::vec3::Vec3;

/// A sphere: centre, radius, (8-bit sRGB) colour and [`Material`] (matte by default).
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
    /// Highlight and mirror response ([`Material::DEFAULT`] unless set).
    pub material: Material,
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
            material: Material::DEFAULT,
        }
    }

    /// The same sphere with another material (unchecked; [`Sphere::check`] checks it).
    #[must_use]
    pub const fn with_material(mut self, material: Material) -> Self {
        self.material = material;
        self
    }

    /// A sphere, checked: finite centre and radius, radius `> 0`.
    pub const fn try_new(center: Vec3, radius: f32, color: Rgb888) -> Result<Self, SphereError> {
        Self::new(center, radius, color).check()
    }

    /// The sphere if its numbers are usable: [`Sphere::try_new`]'s rules and a valid
    /// [`Material`].
    pub const fn check(self) -> Result<Self, SphereError> {
        if !(self.center.is_finite() && self.radius.is_finite()) {
            return Err(SphereError::NotFinite);
        }
        if !(self.radius > 0.0) {
            return Err(SphereError::RadiusNotPositive);
        }
        match self.material.check() {
            Ok(_) => Ok(self),
            Err(e) => Err(SphereError::Material(e)),
        }
    }

    /// Nearest hit `t > 0` of the ray `origin + t·dir` with the chosen method (the
    /// forward-differenced tests evaluate one ray directly, as at an anchor).
    #[must_use]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, test: SphereTest, sqrt: Sqrt) -> Option<f32> {
        struct Query<'s> {
            sphere: &'s Sphere,
            origin: Vec3,
            dir: Vec3,
        }
        impl Visit for Query<'_> {
            type Output = Option<f32>;
            #[inline(always)]
            fn visit<S: Stepper, T: TestStrategy, Q: SqrtFn>(self) -> Option<f32> {
                let scale = Scale::for_spheres([self.sphere], self.origin);
                let g = SphereGeom::new(self.sphere.center, self.sphere.radius, self.origin, scale);
                T::ray::<Q>(&g, self.dir, self.dir.dot(self.dir), f32::INFINITY).map(|t| scale.unscale_t(t))
            }
        }
        dispatch_ray(
            test,
            sqrt,
            Query {
                sphere: self,
                origin,
                dir,
            },
        )
    }

    /// The slides' algebraic test: `a t² + b t + c = 0` with `a = d·d`,
    /// `b = 2 d·(eye − C)`, `c = |eye − C|² − r²`, discriminant `b² − 4ac`, roots
    /// `(−b ± √disc)/2a`.
    ///
    /// **Fails** for a sphere far away relative to its size: `b²` and `4ac` are both
    /// ≈ `4a|L|²` and their difference `4a(r² − dist²)` cancels catastrophically.
    /// Measured by the accuracy lab (`lab/tests/lab/stability.rs`): no error up to
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

#[cfg(test)]
mod tests {
    use super::*;

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
