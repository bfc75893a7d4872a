//! The sphere primitive: its checked constructor and the single-ray queries, which go
//! through the one dispatch to the test strategy types of [`intersect`](crate::method::intersect).

use embedded_graphics::pixelcolor::Rgb888;

use crate::error::SphereError;
use crate::math::vec3::Vec3;
use crate::scene::material::Material;

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
}
