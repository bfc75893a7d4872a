//! A fixed-capacity scene of spheres and the closest-hit search for one ray (through
//! the one dispatch, like the renderer).

use embedded_graphics::pixelcolor::Rgb888;
use heapless::Vec;

use crate::dispatch::{dispatch_ray, Visit};
use crate::error::SceneError;
use crate::intersect::{Scale, SphereGeom, TestStrategy};
use crate::math::SqrtFn;
use crate::method::{SphereTest, Sqrt};
use crate::sphere::Sphere;
use crate::stepping::Stepper;
use crate::vec3::Vec3;

/// Up to `N` spheres and a background colour. No allocation: the spheres live in a
/// `heapless::Vec`, inline.
///
/// A scene can be a `static` in flash:
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_raytracer::{Scene, Sphere, Vec3};
///
/// static SCENE: Scene<2> = Scene::from_array(
///     [
///         Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64)),
///         Sphere::new(Vec3::new(1.5, 0.0, -2.0), 1.0, Rgb888::new(64, 255, 64)),
///     ],
///     Rgb888::new(0, 0, 0),
/// );
/// assert_eq!(SCENE.spheres().len(), 2);
/// ```
#[derive(Clone, Debug)]
pub struct Scene<const N: usize> {
    spheres: Vec<Sphere, N>,
    background: Rgb888,
}

/// A ray's closest hit: which sphere (index into [`Scene::spheres`]) and the ray
/// parameter `t` (`point = eye + t·d`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Index of the sphere hit.
    pub index: usize,
    /// Ray parameter of the hit, `> 0`.
    pub t: f32,
}

impl<const N: usize> Scene<N> {
    /// An empty scene.
    #[must_use]
    pub const fn new(background: Rgb888) -> Self {
        Self {
            spheres: Vec::new(),
            background,
        }
    }

    /// A scene from an array of `M ≤ N` spheres, usable in a `static` (`M > N` is a
    /// compile-time error). The spheres are not checked: build them with
    /// [`Sphere::try_new`] in a const context to have bad numbers rejected at compile
    /// time.
    #[must_use]
    pub const fn from_array<const M: usize>(spheres: [Sphere; M], background: Rgb888) -> Self {
        Self {
            spheres: Vec::from_array(spheres),
            background,
        }
    }

    /// Adds a sphere after checking it ([`Sphere::try_new`]'s rules).
    pub fn push(&mut self, sphere: Sphere) -> Result<(), SceneError> {
        let sphere = Sphere::try_new(sphere.center, sphere.radius, sphere.color)?;
        self.spheres
            .push(sphere)
            .map_err(|_| SceneError::Full { capacity: N })
    }

    /// The spheres, in the order they were added.
    #[must_use]
    pub fn spheres(&self) -> &[Sphere] {
        &self.spheres
    }

    /// The colour of rays that hit nothing.
    #[must_use]
    pub const fn background(&self) -> Rgb888 {
        self.background
    }

    /// Sets the background colour.
    pub fn set_background(&mut self, background: Rgb888) {
        self.background = background;
    }

    /// The closest hit with `t > 0` of the ray `origin + t·dir` over all spheres.
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
                spheres: &self.spheres,
                origin,
                dir,
            },
        )
    }
}
