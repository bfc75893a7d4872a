//! A minimal `f32` 3-vector: exactly the operations the kernel uses, nothing more.

use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A 3-vector of `f32` (a point or a direction in world space; right-handed).
///
/// Plain `Copy` data with `const fn` constructors, so scenes can live in flash.
/// Arithmetic is IEEE-754 single precision with no fused multiply-add, so the same
/// inputs give bit-identical results on the host and on a Cortex-M4F.
///
/// ```
/// use embedded_raytracer::Vec3;
/// let x = Vec3::new(1.0, 0.0, 0.0);
/// let y = Vec3::new(0.0, 1.0, 0.0);
/// assert_eq!(x.cross(y), Vec3::new(0.0, 0.0, 1.0)); // right-handed
/// assert_eq!((x + y).dot(x), 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3 {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component.
    pub z: f32,
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Vec3 = Vec3::new(0.0, 0.0, 0.0);

    /// A vector from its components.
    #[must_use]
    pub const fn new(x: f32, y: f32, z: f32) -> Self {
        Self { x, y, z }
    }

    /// Dot product.
    #[must_use]
    #[inline(always)]
    pub fn dot(self, o: Vec3) -> f32 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product (right-handed: `x × y = z`).
    #[must_use]
    #[inline(always)]
    pub fn cross(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// `self · self`.
    #[must_use]
    #[inline(always)]
    pub fn length_squared(self) -> f32 {
        self.dot(self)
    }

    /// Euclidean length, with the correctly rounded square root.
    #[must_use]
    pub fn length(self) -> f32 {
        crate::math::sqrt_exact(self.length_squared())
    }

    /// `true` if every component is finite (not NaN, not ±∞).
    #[must_use]
    pub const fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }

    /// The unit vector in the direction of `self`, or `None` when the length is zero,
    /// subnormal-small or not finite (so no NaN or ∞ can come out).
    #[must_use]
    pub fn try_normalize(self) -> Option<Vec3> {
        let len = self.length();
        // Below ~1e-18 the squared length is subnormal and has lost precision.
        if len.is_finite() && len > 1e-18 {
            Some(self * (1.0 / len))
        } else {
            None
        }
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn add(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl AddAssign for Vec3 {
    #[inline(always)]
    fn add_assign(&mut self, o: Vec3) {
        *self = *self + o;
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl SubAssign for Vec3 {
    #[inline(always)]
    fn sub_assign(&mut self, o: Vec3) {
        *self = *self - o;
    }
}

impl Mul<f32> for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn mul(self, s: f32) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}
