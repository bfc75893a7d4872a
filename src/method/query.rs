//! Single-ray queries through the one dispatch: [`Sphere::intersect`] and the slides'
//! tests by name, and [`Scene::closest_hit`].
//!
//! They are the scene objects' methods, kept
//! here so that the scene's types sit below the methods that test them.

use crate::math::vec3::Vec3;
use crate::math::SqrtFn;
use crate::method::dispatch::{dispatch_ray, Visit};
use crate::method::intersect::{Scale, SphereGeom, TestStrategy};
use crate::method::stepping::Stepper;
use crate::method::{SphereTest, Sqrt};
use crate::scene::sphere::Sphere;
use crate::scene::{Hit, Scene};

impl Sphere {
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
    /// Edge pixels flip first, then half the disc is wrong, and once the f32 rounding of
    /// `|L|²` swamps `r²` every ray is a hit (the distances, measured by the accuracy
    /// lab's `lab/tests/lab/stability.rs`: `docs/accuracy.md`, "Failure points").
    /// `−b − √disc` also cancels for the near root when the eye is close to the
    /// surface.
    #[must_use]
    pub fn intersect_algebraic(&self, origin: Vec3, dir: Vec3) -> Option<f32> {
        self.intersect(origin, dir, SphereTest::Algebraic, Sqrt::Exact)
    }

    /// The slides' geometric test: `t_ca = L·d̂`, `d² = |L|² − t_ca²`, miss if
    /// `d² > r²`, `t_hc = √(r² − d²)`, distance `t_ca ∓ t_hc`.
    ///
    /// **Fails** the same way as the algebraic form for far, small spheres: `|L|² − t_ca²`
    /// cancels catastrophically (where edge pixels flip: `docs/accuracy.md`, "Failure
    /// points"). It also
    /// normalises the ray with the square root, so with [`Sqrt::Fast`] (up to 6 % off)
    /// `t_ca` and hence `d²` are wrong and coverage fails everywhere.
    #[must_use]
    pub fn intersect_geometric(&self, origin: Vec3, dir: Vec3) -> Option<f32> {
        self.intersect(origin, dir, SphereTest::Geometric, Sqrt::Exact)
    }

    /// The robust test of Haines et al. (Ray Tracing Gems, ch. 7): the discriminant from
    /// the perpendicular vector and the stable roots.
    ///
    /// The discriminant is `r² − |L − (b/a)·d|²` with `b = L·d`, which has no
    /// cancellation between two large squares; the roots are `t = c/q` and `t = q/a`
    /// with `q = b + sign(b)·√(a·disc)` (no `−b + √…` cancellation). The accuracy lab
    /// finds no coverage error in `f32` as far as its sweep reaches (`docs/accuracy.md`,
    /// "Failure points"). Remaining failure: when `b = 0` and the
    /// discriminant is exactly 0 (eye exactly on the surface, ray tangent) `q = 0` and
    /// the ray is reported as a miss.
    #[must_use]
    pub fn intersect_robust(&self, origin: Vec3, dir: Vec3) -> Option<f32> {
        self.intersect(origin, dir, SphereTest::Robust, Sqrt::Exact)
    }
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Scene<N, L, P, D> {
    /// The closest hit with `t > 0` of the ray `origin + t·dir` over all spheres (planes
    /// are not searched).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb888;
    /// use embedded_raytracer::{Scene, Sphere, SphereTest, Sqrt, Vec3};
    ///
    /// let mut scene: Scene<2> = Scene::new(Rgb888::new(0, 0, 0));
    /// scene.push(Sphere::new(Vec3::new(0.0, 0.0, -10.0), 1.0, Rgb888::new(255, 0, 0))).unwrap();
    /// scene.push(Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0, Rgb888::new(0, 255, 0))).unwrap();
    /// let hit = scene.closest_hit(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), SphereTest::Robust, Sqrt::Exact);
    /// assert_eq!(hit.map(|h| (h.index, h.t)), Some((1, 4.0)));
    /// ```
    #[must_use]
    pub fn closest_hit(&self, origin: Vec3, dir: Vec3, test: SphereTest, sqrt: Sqrt) -> Option<Hit> {
        struct Query<'s> {
            spheres: &'s [Sphere],
            origin: Vec3,
            dir: Vec3,
        }
        impl Visit for Query<'_> {
            type Output = Option<Hit>;
            #[inline(always)]
            fn visit<S: Stepper, T: TestStrategy, Q: SqrtFn>(self) -> Option<Hit> {
                // Closest hit: each test gets the nearest `t` found so far as its
                // `t_max`, so a farther sphere is rejected by the same comparison that
                // finds hits. Constants are made per sphere as it is tested (no
                // per-query buffer on the stack).
                let a = self.dir.dot(self.dir);
                let scale = Scale::for_spheres(self.spheres, self.origin);
                let mut t_max = f32::INFINITY;
                let mut best = None;
                for (index, sphere) in self.spheres.iter().enumerate() {
                    let g = SphereGeom::new(sphere.center, sphere.radius, self.origin, scale);
                    if let Some(t) = T::ray::<Q>(&g, self.dir, a, t_max) {
                        t_max = t;
                        best = Some(Hit { index, t });
                    }
                }
                best.map(|h| Hit {
                    t: scale.unscale_t(h.t),
                    ..h
                })
            }
        }
        dispatch_ray(
            test,
            sqrt,
            Query {
                spheres: self.spheres(),
                origin,
                dir,
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::Rgb888;

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
